// The runs of CosseratDruckerPrager with linear shape functions and each integrator
// (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::MUSL, CosseratDruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USL, CosseratDruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USF, CosseratDruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::FusedMUSL, CosseratDruckerPrager>);
}  // namespace flat_blade
