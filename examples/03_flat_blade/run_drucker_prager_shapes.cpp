// The runs of DruckerPrager with MUSL and the shape functions beyond linear (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::GIMP, integrator::MUSL, DruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::QuadraticBSpline, integrator::MUSL, DruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::CubicBSpline, integrator::MUSL, DruckerPrager>);
}  // namespace flat_blade
