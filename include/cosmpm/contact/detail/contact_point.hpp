#pragma once
// Which face of a rigid body a contact node uses (RigidContact, rigid_contact.hpp): the nearest
// one, unless the material lies on another side of a body thinner than the node's support.
#include <cmath>
#include <limits>

#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::detail {

// Direction of increasing material mass at a node (central differences of nodal mass,
// one-sided on the grid faces): it points from the body into the material.
template <int Dim>
Vec<Dim> mass_gradient(const contact::GridView<Dim>& view, Index n) {
  const auto ijk = view.grid.node_ijk(n);
  Vec<Dim> g = Vec<Dim>::Zero();
  Index stride = 1;
  for (int d = 0; d < Dim; ++d) {
    const bool has_lower = ijk[d] > 0;
    const bool has_upper = ijk[d] < view.grid.nodes(d) - 1;
    const double lower = has_lower ? view.mass[n - stride] : view.mass[n];
    const double upper = has_upper ? view.mass[n + stride] : view.mass[n];
    const double span = (has_lower && has_upper) ? 2.0 : 1.0;
    g[d] = (upper - lower) / (span * view.grid.cell_size()[d]);
    stride *= view.grid.nodes(d);
  }
  return g;
}

// The face a boundary point lies on, and its coordinates there (along, across).
inline int face_of(const contact::BoundaryPoint& p) {
  return p.edge;
}
inline int face_of(const contact::FacePoint& p) {
  return p.face;
}
inline Vec<2> face_coordinates(const contact::BoundaryPoint& p) {
  return Vec<2>(p.along, 0.0);
}
inline Vec<2> face_coordinates(const contact::FacePoint& p) {
  return p.on_face;
}

// The boundary point whose normal the node uses: the closest one, unless the material lies
// on another side (a node inside or behind a body thinner than the support sees the face
// the material touches, not the nearest one); then the closest of the edges within the
// node's support that face the material.
template <int Dim>
typename contact::RigidBody<Dim>::Point contact_point(const contact::GridView<Dim>& view,
                                                      const contact::RigidBody<Dim>& body, Index n,
                                                      const Vec<Dim>& x, const Vec<Dim>& reach) {
  using Point = typename contact::RigidBody<Dim>::Point;
  const Point closest = body.closest(x);
  const Vec<Dim> g = mass_gradient(view, n);
  if (closest.normal.dot(g) >= 0.0) return closest;
  const bool inside = closest.signed_distance < 0.0;
  Point best = closest;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int e = 0; e < body.face_count(); ++e) {
    if (!body.face_meets_open_box(e, x, reach)) continue;
    const Point p = body.closest_on_face(x, e, inside);
    // Behind a thin body the facing edge lies beyond it: its face normal, not the offset.
    const Vec<Dim> normal = body.face_normal(e);
    if (normal.dot(g) <= 0.0) continue;
    const double distance = std::abs(p.signed_distance);
    if (distance < best_distance) {
      best = p;
      best.normal = normal;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace cosmpm::detail
