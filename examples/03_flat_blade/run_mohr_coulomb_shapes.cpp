// The runs of MohrCoulomb with MUSL and the shape functions beyond linear (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::GIMP, integrator::MUSL, MohrCoulomb>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::QuadraticBSpline, integrator::MUSL, MohrCoulomb>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::CubicBSpline, integrator::MUSL, MohrCoulomb>);
}  // namespace flat_blade
