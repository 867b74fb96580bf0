#pragma once
// The gap check of RigidContact (rigid_contact.hpp, set_gap_check): per node, the smallest gap
// between body b and the particles in the node's support.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::detail {

// Per node, the smallest gap (d_p - e_p, see set_gap_check) of the particles in its support
// near body b; +inf where none.
template <int Dim>
void smallest_gaps(const contact::GridView<Dim>& view, const contact::RigidBody<Dim>& body, int b,
                   std::vector<double>& gaps) {
  const auto& g = view.grid;
  if (view.particle_positions.size() != view.particle_half_widths.size()) {
    throw Error("contact::RigidContact: the gap check of body " + std::to_string(b) + " got " +
                std::to_string(view.particle_positions.size()) + " particle positions and " +
                std::to_string(view.particle_half_widths.size()) +
                " half-widths (valid: one of each per particle)");
  }
  if (view.particle_positions.empty()) {
    throw Error("contact::RigidContact: the gap check of body " + std::to_string(b) +
                " needs the particles in the GridView (the engine passes them; a view built "
                "by hand must set particle_positions and particle_half_widths)");
  }
  gaps.assign(static_cast<std::size_t>(g.node_count()), std::numeric_limits<double>::infinity());
  const Vec<Dim> h = g.cell_size();
  const Vec<Dim> reach = view.node_reach * h;
  for (std::size_t p = 0; p < view.particle_positions.size(); ++p) {
    const Vec<Dim>& x = view.particle_positions[p];
    const Vec<Dim> extent = view.particle_half_widths[p].cwiseProduct(h);
    // A node holds the particle within reach (GIMP: reach plus the particle's half-width,
    // which this over-counts for the other kernels, on the side of more contact).
    const Vec<Dim> support = reach + extent;
    if (!body.meets_open_box(x, support + reach)) continue;  // none of its nodes touches
    const auto closest = body.closest(x);
    double gap = closest.signed_distance;
    for (int d = 0; d < Dim; ++d) gap -= std::abs(closest.normal[d]) * extent[d];
    // The nodes whose support holds the particle: |x_i - x| < support per axis.
    std::array<Index, Dim> lo{};
    std::array<Index, Dim> hi{};
    for (int d = 0; d < Dim; ++d) {
      const double cell = (x[d] - g.origin()[d]) / h[d];
      const double cells = support[d] / h[d];
      lo[d] = std::max<Index>(0, static_cast<Index>(std::floor(cell - cells)) + 1);
      hi[d] = std::min<Index>(g.cells(d), static_cast<Index>(std::ceil(cell + cells)) - 1);
    }
    grid::for_each_node_in_box(g, lo, hi, [&](Index node) {
      double& node_gap = gaps[static_cast<std::size_t>(node)];
      node_gap = std::min(node_gap, gap);
    });
  }
}

}  // namespace cosmpm::detail
