#pragma once
// The checks of a composition, run before anything else of a Simulation is instantiated: each
// failure is a static_assert naming what is wrong (tests/compile_fail/ checks the messages).
#include "cosmpm/contact/concept.hpp"
#include "cosmpm/continuum/concept.hpp"
#include "cosmpm/integrator/concept.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/simulation/block_scheduler.hpp"
#include "cosmpm/transfer/concept.hpp"

namespace cosmpm {

namespace detail {
// Instantiated with the two numbers, so the compiler's message names both.
template <int kernel_support, int block_cells>
consteval bool kernel_support_fits_block() {
  static_assert(kernel_support <= block_cells,
                "Simulation: the kernel's support (kernel_support) is wider than a particle block "
                "(block_cells, BlockScheduler::block_cells): the parallel scatter would race");
  return true;
}

// The composition's checks, run before anything else of Simulation is instantiated; each
// failure is a static_assert naming what is wrong.
template <int Dim, class Kernel, class Continuum, class Contact, class Scheme, class Transfer>
struct CompositionChecks {
  static consteval bool check() {
    static_assert(Dim == 2,
                  "Simulation<3, ...>: 3D is not implemented yet (the continua, materials and "
                  "contact laws are 2D plane strain)");
    if constexpr (Dim == 2) {
      static_assert(continuum::check_continuum<Continuum, Dim>());
      static_assert(
          kernel_support_fits_block<Kernel::support,
                                    BlockScheduler<Dim, Kernel>::smallest_block_cells()>());
      static_assert(contact::check_contact_law<Contact, Dim>());
      static_assert(!Transfer::affine || shape::has_continuous_gradient<Kernel>,
                    "Simulation: APIC needs a kernel with a continuous gradient (GIMP, "
                    "QuadraticBSpline, CubicBSpline); with shape::Linear its affine matrix takes "
                    "the velocity of nodes of vanishing mass at full weight (transfer/apic.hpp)");
      static_assert(integrator::Integrator<Scheme>,
                    "Simulation: the scheme needs `static const char* name()` and `template "
                    "<class Sim> static void step(Sim&, double dt)` (integrator/concept.hpp)");
    }
    return true;
  }
  static_assert(check());
};
}  // namespace detail

}  // namespace cosmpm
