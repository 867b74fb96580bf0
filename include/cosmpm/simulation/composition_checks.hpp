#pragma once
// The checks of a composition, run before anything else of a Simulation is instantiated: each
// failure is a static_assert naming what is wrong (tests/compile_fail/ checks the messages).
#include "cosmpm/contact/concept.hpp"
#include "cosmpm/continuum/concept.hpp"
#include "cosmpm/integrator/concept.hpp"
#include "cosmpm/material/concept.hpp"
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

// A continuum's own `is_cosserat` and `dim` (a type without them, e.g. a material given
// where a continuum belongs, is left to check_continuum's message).
template <class Continuum>
consteval bool continuum_is_cosserat() {
  if constexpr (requires { Continuum::is_cosserat; }) {
    return static_cast<bool>(Continuum::is_cosserat) && !material::ConstitutiveModel<Continuum>;
  } else {
    return false;
  }
}
template <class Continuum>
consteval int continuum_dimension() {
  if constexpr (requires { Continuum::dim; }) {
    return static_cast<int>(Continuum::dim);
  } else {
    return 0;
  }
}

// The composition's checks, run before anything else of Simulation is instantiated; each
// failure is a static_assert naming what is wrong.
template <int Dim, class Kernel, class Continuum, class Contact, class Scheme, class Transfer>
struct CompositionChecks {
  static consteval bool check() {
    static_assert(Dim == 2 || Dim == 3, "Simulation<Dim, ...>: Dim is 2 (plane strain) or 3");
    static_assert(Dim == 2 || !continuum_is_cosserat<Continuum>(),
                  "Simulation<3, ...>: the Cosserat continuum is 2D only (plane strain, one "
                  "micro-rotation omega_3); use continuum::Classical with a 3D model, e.g. "
                  "continuum::Classical<material::MohrCoulomb<double, 3>>");
    static_assert(continuum_is_cosserat<Continuum>() || continuum_dimension<Continuum>() == 0 ||
                      continuum_dimension<Continuum>() == Dim,
                  "Simulation<Dim, ...>: the continuum's model is of another dimension than the "
                  "simulation; at Dim = 3 use a 3D model, e.g. "
                  "continuum::Classical<material::LinearElastic<double, 3>>, at Dim = 2 a "
                  "plane-strain one");
    if constexpr ((Dim == 2 || !continuum_is_cosserat<Continuum>()) &&
                  (continuum_dimension<Continuum>() == 0 ||
                   continuum_dimension<Continuum>() == Dim)) {
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
