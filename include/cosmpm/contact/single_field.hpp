#pragma once
// The MPM default: one velocity field on the grid, so bodies stick where they touch. It joins
// no phase of the step (contact/concept.hpp).
#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/grid_view.hpp"

namespace cosmpm::contact {

struct SingleField {
  static constexpr const char* name() { return "single-field no-slip"; }
  void advance(double /*dt*/, double /*time*/) {}
};

static_assert(ContactLaw<SingleField, 2>);

}  // namespace cosmpm::contact
