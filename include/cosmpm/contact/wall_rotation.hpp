#pragma once
// The Cosserat rotation at a rigid body's face (Interface::Rotation), node by node, for
// RigidContact (rigid_contact.hpp). See docs/theory/mpm.md, "Rotation at a rigid body".
//
//   held:    the nodes that straddle the body's surface, those whose control volume (the
//            closed box of half a cell either side of the node, the lumped-mass tributary
//            region) the boundary crosses, take the body's angular velocity Omega; nodes
//            whose support merely reaches the body (up to a cell ahead of the face) stay free.
//   coupled: a grain of radius r at the node touches the face at x - r n. With t = e_z x n
//            (n turned a quarter counter-clockwise) and spins counter-clockwise positive, its
//            contact point slips at s = v_t - r (omega - Omega), v_t the tangential velocity
//            relative to the body. Coulomb friction acts on s; its impulse P_t along t at the
//            contact point turns the grain by -r P_t (the friction moment). Stick (s -> 0)
//            needs P_t = -m_eff s with 1 / m_eff = 1 / m + r^2 / I; it holds if |P_t| <= mu P_n
//            (P_n = m |v_n|, the normal impulse), else P_t = -mu P_n sign(s) (slip).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/interface.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::contact {

// Whether the body's boundary crosses the closed box |y - node| <= half_cell (per axis).
inline bool straddles_surface(const RigidBody<2>& body, const Vec<2>& node,
                              const Vec<2>& half_cell) {
  for (int e = 0; e < body.edge_count(); ++e) {
    // Clip the edge a + s (b - a), s in [0, 1], against the closed box.
    const Vec<2>& a = body.edge_start(e);
    const Vec<2> ab = body.edge_end(e) - a;
    double s0 = 0.0;
    double s1 = 1.0;
    bool outside = false;
    for (int d = 0; d < 2 && !outside; ++d) {
      const double p = a[d] - node[d];
      if (ab[d] == 0.0) {
        outside = std::abs(p) > half_cell[d];
        continue;
      }
      double sa = (-half_cell[d] - p) / ab[d];
      double sb = (half_cell[d] - p) / ab[d];
      if (sa > sb) std::swap(sa, sb);
      s0 = std::max(s0, sa);
      s1 = std::min(s1, sb);
      outside = s0 > s1;
    }
    if (!outside) return true;
  }
  return false;
}

// One approaching node's state after the coupled law, relative to the body.
struct GrainWallCorrection {
  Vec<2> velocity = Vec<2>::Zero();  // v - V: the normal part removed, the tangential corrected
  double spin = 0.0;                 // omega - Omega
  double tangential_impulse = 0.0;   // P_t along t = e_z x n, on the material (N s per m)
  NodeState state = NodeState::stick;
};

// The coupled law at a node approaching the body (v_rel . n < 0): mass m, rotational inertia I
// (both > 0), relative velocity and spin, unit normal n, friction mu and grain radius r.
inline GrainWallCorrection grain_wall_friction(const Vec<2>& relative_velocity,
                                               double relative_spin, const Vec<2>& normal,
                                               double mass, double inertia, double mu,
                                               double radius) {
  const Vec<2> tangent(-normal[1], normal[0]);  // e_z x n
  const double v_n = relative_velocity.dot(normal);
  const double v_t = relative_velocity.dot(tangent);
  const double slip = v_t - radius * relative_spin;
  const double effective_mass = 1.0 / (1.0 / mass + radius * radius / inertia);
  const double limit = mu * mass * (-v_n);
  GrainWallCorrection c;
  c.tangential_impulse = -effective_mass * slip;
  if (std::abs(c.tangential_impulse) > limit) {
    c.tangential_impulse = slip > 0.0 ? -limit : limit;
    c.state = NodeState::slip;
  }
  c.velocity = (v_t + c.tangential_impulse / mass) * tangent;
  c.spin = relative_spin - radius * c.tangential_impulse / inertia;
  return c;
}

// The coupled law turns the grains: it needs the continuum's spin and rotational inertia.
template <int Dim>
void require_rotational_inertia(const GridView<Dim>& view, int b) {
  const auto nodes = static_cast<std::size_t>(view.grid.node_count());
  if (view.spin.size() != nodes || view.rotational_inertia.size() != nodes) {
    throw Error("contact::RigidContact: body " + std::to_string(b) +
                " has a coupled grain rotation (Interface::with_grain_rotation_coupled), but "
                "the grid view holds " +
                std::to_string(view.spin.size()) + " nodal spins and " +
                std::to_string(view.rotational_inertia.size()) +
                " rotational inertias (valid: one of each per node, " + std::to_string(nodes) +
                ", from a Cosserat continuum)");
  }
}
template <int Dim>
double inertia_of(const GridView<Dim>& view, Index n) {
  return view.rotational_inertia.empty() ? 0.0
                                         : view.rotational_inertia[static_cast<std::size_t>(n)];
}

}  // namespace cosmpm::contact
