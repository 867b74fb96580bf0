#pragma once
// The Coulomb correction of one approaching contact node of RigidContact (rigid_contact.hpp):
// stick or slip relative to the body, with the components a grid wall will impose left out of
// the slip (GridView::held; docs/theory/mpm.md, "Walls the body slides along").
#include <cmath>
#include <cstddef>

#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/interface.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::detail {

// The components view.held marks at node n, if the body's normal has none of them and at
// least one tangential direction stays free; else none.
template <int Dim>
unsigned walled_components(const contact::GridView<Dim>& view, Index n, const Vec<Dim>& normal) {
  if (view.held.empty()) return 0u;
  const unsigned held = view.held[static_cast<std::size_t>(n)];
  if (held == 0u) return 0u;
  int free = 0;
  for (int d = 0; d < Dim; ++d) {
    if (((held >> d) & 1u) == 0u) {
      ++free;
    } else if (std::abs(normal[d]) > 1e-12) {
      return 0u;  // the wall holds part of the normal: conditions_applied reconciles it
    }
  }
  return free >= 2 ? held : 0u;  // the normal's component and a tangential one
}

template <int Dim>
struct CoulombCorrection {
  Vec<Dim> velocity;
  contact::NodeState state;
};

// Approach (v_n = v_rel . normal < 0): the normal part removed, the tangential part stuck
// (|v_t| <= mu |v_n|) or reduced by mu |v_n|. A walled component takes no part in the slip,
// if a free tangential direction remains: the wall sets it (it keeps its trial value), and
// the limit mu |v_n| belongs to the slip the wall leaves. With a single tangential direction
// (2D) nothing changes.
template <int Dim>
CoulombCorrection<Dim> coulomb_correction(const Vec<Dim>& v_trial, const Vec<Dim>& v_body,
                                          const Vec<Dim>& normal, double v_n, double mu,
                                          unsigned walled) {
  Vec<Dim> slip = v_trial - v_body;
  for (int d = 0; d < Dim; ++d) {
    if ((walled >> d) & 1u) slip[d] = 0.0;
  }
  const Vec<Dim> v_t = slip - v_n * normal;
  const double v_t_norm = v_t.norm();
  const double limit = mu * (-v_n);
  CoulombCorrection<Dim> c{v_body, contact::NodeState::stick};
  if (v_t_norm > limit) {
    c.velocity = v_body + (1.0 - limit / v_t_norm) * v_t;
    c.state = contact::NodeState::slip;
  }
  for (int d = 0; d < Dim; ++d) {
    if ((walled >> d) & 1u) c.velocity[d] = v_trial[d];
  }
  return c;
}

}  // namespace cosmpm::detail
