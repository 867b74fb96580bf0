#pragma once
// The contact-law concept. A law joins the phases of a step it needs, each a member function
// the engine calls when the law has it:
//
//   add_forces(ForceView<Dim>&)  after the particle-to-grid map, before the momentum update:
//                                adds contact forces to the nodal forces (penalty laws);
//   correct(GridView<Dim>&)      after a nodal velocity field is formed (view.phase: the start
//                                velocity of USF, the end-of-step velocity, MUSL's remapped
//                                velocity): corrects it (Bardenhagen's multi-field contact,
//                                rigid bodies); boundary conditions come after and win;
//   conditions_applied(GridView<Dim>&)
//                                after the boundary conditions of each velocity phase
//                                (view.imposed: the components they imposed): a law that
//                                records forces reconciles them with what was applied, and
//                                may correct what the conditions left free (a body pushing
//                                material along a friction wall);
//   bool corrects_start_of_step() const
//                                optional: true makes USL and MUSL run correct() on the
//                                start velocity too (phase start_velocity, as USF always
//                                does) before the momentum update (Nairn, Hammerquist and
//                                Smith 2020); without it, false;
//   advance(dt, time)            at the end of every step: moves what the law owns (bodies);
//   static name()                a short description (output, checkpoint signatures).
//
// check_contact_law<L, Dim>() names whatever is missing; the engine calls it.
#include <concepts>

#include "cosmpm/contact/grid_view.hpp"

namespace cosmpm::contact {

template <class L>
concept NamedLaw = requires {
  { L::name() } -> std::convertible_to<const char*>;
};

template <class L>
concept AdvancesInTime = requires(L& law, double dt, double time) {
  law.advance(dt, time);
};

template <class L, int Dim>
concept CorrectsVelocities = requires(L& law, GridView<Dim>& view) {
  law.correct(view);
};

template <class L, int Dim>
concept ReconcilesConditions = requires(L& law, GridView<Dim>& view) {
  law.conditions_applied(view);
};

template <class L, int Dim>
concept AddsForces = requires(L& law, ForceView<Dim>& view) {
  law.add_forces(view);
};

template <class L, int Dim>
concept ContactLaw = NamedLaw<L> && AdvancesInTime<L> && std::movable<L>;

// Whether the law asks for the start-of-step correction in USL and MUSL (see above).
template <class L>
bool corrects_start_of_step(const L& law) {
  if constexpr (requires {
                  { law.corrects_start_of_step() } -> std::convertible_to<bool>;
                }) {
    return law.corrects_start_of_step();
  } else {
    return false;
  }
}

template <class L, int Dim>
consteval bool check_contact_law() {
  static_assert(NamedLaw<L>,
                "contact law: missing `static const char* name()` (a short description for "
                "output and checkpoints)");
  static_assert(AdvancesInTime<L>,
                "contact law: missing `void advance(double dt, double time)` (called at the end "
                "of every step; an empty body if the law owns nothing that moves)");
  static_assert(std::movable<L>, "contact law: must be movable (the simulation owns a copy)");
  if constexpr (requires { &L::correct; }) {
    static_assert(CorrectsVelocities<L, Dim>,
                  "contact law: has a member `correct` that does not take contact::GridView<Dim>& "
                  "(the velocity phases would never call it)");
  }
  if constexpr (requires { &L::conditions_applied; }) {
    static_assert(ReconcilesConditions<L, Dim>,
                  "contact law: has a member `conditions_applied` that does not take "
                  "contact::GridView<Dim>& (the phases after the boundary conditions would "
                  "never call it)");
  }
  if constexpr (requires { &L::add_forces; }) {
    static_assert(AddsForces<L, Dim>,
                  "contact law: has a member `add_forces` that does not take "
                  "contact::ForceView<Dim>& (the force phase would never call it)");
  }
  return ContactLaw<L, Dim>;
}

}  // namespace cosmpm::contact
