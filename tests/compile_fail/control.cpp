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
int main() {
  return sizeof(Right) > 0 ? 0 : 1;
}
