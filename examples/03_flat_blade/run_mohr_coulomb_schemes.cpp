// The runs of MohrCoulomb with linear shape functions and each integrator (compositions.hpp).
#include "run.hpp"

namespace flat_blade {
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::MUSL, MohrCoulomb>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USL, MohrCoulomb>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::USF, MohrCoulomb>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::FusedMUSL, MohrCoulomb>);
}  // namespace flat_blade
