// The runs of the nonpolar models with APIC and with F-bar (compositions.hpp, MethodsOf).
#include "run.hpp"

namespace flat_blade {
template Outcome run(
    const Case&, RunContext&,
    Composition<shape::QuadraticBSpline, integrator::MUSL, MohrCoulomb, transfer::APIC>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::MUSL, MohrCoulomb, transfer::FlipBlend,
                                 antilocking::FBar>);
template Outcome run(
    const Case&, RunContext&,
    Composition<shape::QuadraticBSpline, integrator::MUSL, DruckerPrager, transfer::APIC>);
template Outcome run(const Case&, RunContext&,
                     Composition<shape::Linear, integrator::MUSL, DruckerPrager,
                                 transfer::FlipBlend, antilocking::FBar>);
}  // namespace flat_blade
