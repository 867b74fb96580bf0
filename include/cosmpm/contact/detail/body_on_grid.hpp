#pragma once
// RigidContact's check that a body overlaps the grid it is to touch (contact/rigid_contact.hpp).
#include <string>

#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace cosmpm::detail {

template <int Dim>
void require_body_on_grid(const grid::Grid<Dim>& g, const contact::RigidBody<Dim>& body, int b) {
  const Vec<Dim> lo = g.origin();
  const Vec<Dim> hi = g.origin() + g.extent();
  const auto point = [](const Vec<Dim>& x) {
    std::string text = "[";
    for (int d = 0; d < Dim; ++d) text += (d ? ", " : "") + detail::format_number(x[d]);
    return text + "]";
  };
  for (int d = 0; d < Dim; ++d) {
    if (body.upper_bound()[d] < lo[d] || body.lower_bound()[d] > hi[d]) {
      throw Error("contact::RigidContact: rigid body " + std::to_string(b) + " with bounding box " +
                  point(body.lower_bound()) + " - " + point(body.upper_bound()) +
                  " lies outside the grid box " + point(lo) + " - " + point(hi) +
                  " (valid range: the body must overlap the grid)");
    }
  }
}

}  // namespace cosmpm::detail
