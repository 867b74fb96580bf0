// The runs of DruckerPrager with linear shape functions and each integrator (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::MUSL, DruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USL, DruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USF, DruckerPrager>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::FusedMUSL, DruckerPrager>);
}  // namespace flat_blade
