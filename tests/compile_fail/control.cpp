// Must compile: the harness's control, the compositions above made right.
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
struct WithAdvance {
  static const char* name() { return "with advance (test)"; }
  void correct(contact::GridView<2>&) {}
  void advance(double, double) {}
};
using Right = Simulation<2, shape::CubicBSpline, continuum::Classical<material::MohrCoulomb<>>,
                         WithAdvance, integrator::MUSL, transfer::APIC>;
using Right3D =
    Simulation<3, shape::QuadraticBSpline, continuum::Classical<material::MohrCoulomb<double, 3>>,
               contact::SingleField, integrator::USF>;
int main() {
  return sizeof(Right) + sizeof(Right3D) > 0 ? 0 : 1;
}
