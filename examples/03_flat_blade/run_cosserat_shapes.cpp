// The runs of CosseratDruckerPrager with MUSL and the shape functions beyond linear
// (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::GIMP, integrator::MUSL, CosseratDruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::QuadraticBSpline, integrator::MUSL, CosseratDruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::CubicBSpline, integrator::MUSL, CosseratDruckerPrager>);
}  // namespace flat_blade
