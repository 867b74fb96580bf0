#pragma once
// Velocity boundary conditions on the faces of the grid box, applied to the nodes of each face.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace cosmpm::grid {

enum class BoundaryKind {
  free,      // nothing imposed
  fixed,     // all velocity components zero
  roller,    // normal velocity zero, tangential free
  friction,  // no penetration, free separation, Coulomb friction on the tangential velocity
};

struct FaceCondition {
  BoundaryKind kind = BoundaryKind::free;
  double friction_coefficient = 0.0;  // mu, used by BoundaryKind::friction
};

// Faces are numbered 2 * axis + side: 0 = x_min, 1 = x_max, 2 = y_min, 3 = y_max, ...
template <int Dim>
class BoundaryConditions {
 public:
  static constexpr int face_count = 2 * Dim;
  static constexpr int face(int axis, bool upper) { return 2 * axis + (upper ? 1 : 0); }

  void set(int face_index, BoundaryKind kind, double friction_coefficient = 0.0) {
    require_in_range("BoundaryConditions::set", "face", face_index, 0, face_count - 1,
                     Bounds::closed);
    if (kind == BoundaryKind::friction) {
      require_non_negative("BoundaryConditions::set", "friction_coefficient", friction_coefficient);
    }
    faces_[face_index] = {kind, friction_coefficient};
  }
  const FaceCondition& operator[](int face_index) const { return faces_[face_index]; }

  // Imposes the face condition on the updated velocity `v` of a node lying on that face and
  // returns the components it imposed kinematically (bit d for component d). A friction wall
  // imposes only its normal component: the tangential ones it reduces by friction (the removed
  // normal velocity is the impulse that bounds them), a resistance that a rigid body pushing
  // the material along the wall overcomes (contact::RigidContact::conditions_applied).
  static unsigned apply(const FaceCondition& condition, int axis, bool upper, Vec<Dim>& v) {
    constexpr unsigned all = (1u << Dim) - 1u;
    const unsigned normal = 1u << axis;
    switch (condition.kind) {
      case BoundaryKind::free:
        return 0u;
      case BoundaryKind::fixed:
        v.setZero();
        return all;
      case BoundaryKind::roller:
        v[axis] = 0.0;
        return normal;
      case BoundaryKind::friction: {
        // Outward normal: -e_axis at the lower face, +e_axis at the upper one.
        const double outward = upper ? v[axis] : -v[axis];
        if (outward <= 0.0) return 0u;  // separating: free
        v[axis] = 0.0;
        double tangential_norm = 0.0;
        for (int d = 0; d < Dim; ++d) {
          if (d != axis) tangential_norm += v[d] * v[d];
        }
        tangential_norm = std::sqrt(tangential_norm);
        if (tangential_norm == 0.0) return normal;
        const double allowed = condition.friction_coefficient * outward;
        const double scale = tangential_norm > allowed ? 1.0 - allowed / tangential_norm : 0.0;
        for (int d = 0; d < Dim; ++d) {
          if (d != axis) v[d] *= scale;
        }
        return normal;
      }
    }
    return 0u;
  }

 private:
  std::array<FaceCondition, face_count> faces_{};
};

// f(n) for every node n on the lower (upper = false) or upper face normal to `axis`.
template <int Dim, class F>
void for_each_face_node(const Grid<Dim>& grid, int axis, bool upper, F&& f) {
  std::array<Index, Dim> ijk{};
  ijk[axis] = upper ? grid.nodes(axis) - 1 : 0;
  Index total = 1;
  for (int d = 0; d < Dim; ++d) {
    if (d != axis) total *= grid.nodes(d);
  }
  for (Index k = 0; k < total; ++k) {
    Index rest = k;
    for (int d = 0; d < Dim; ++d) {
      if (d == axis) continue;
      ijk[d] = rest % grid.nodes(d);
      rest /= grid.nodes(d);
    }
    f(grid.node_index(ijk));
  }
}

// f(n), in increasing n, for every node n in [first, last) on the lower (upper = false) or upper
// face normal to `axis`: a thread's share of a node pass (stages/grid_conditions.hpp) visits its
// own face nodes without stepping through the others'. Nodes are numbered i + n_0 (j + n_1 k): the
// face's nodes come in blocks of `inner` consecutive indices, one block every `outer`.
template <int Dim, class F>
void for_each_face_node_in(const Grid<Dim>& grid, int axis, bool upper, Index first, Index last,
                           F&& f) {
  Index inner = 1;
  for (int d = 0; d < axis; ++d) inner *= grid.nodes(d);
  const Index outer = inner * grid.nodes(axis);
  const Index offset = inner * (upper ? grid.nodes(axis) - 1 : 0);
  first = std::max(first, Index{0});
  last = std::min(last, grid.node_count());
  if (first >= last) return;
  for (Index block = first / outer; block * outer < last; ++block) {
    const Index begin = block * outer + offset;
    for (Index n = std::max(begin, first); n < std::min(begin + inner, last); ++n) f(n);
  }
}

// The face conditions on the nodes [first, last) of a nodal velocity field, face by face in face
// order, so a node on several faces (a corner) takes them in the order of the faces. With
// `imposed` (one entry per node, zeroed by the caller), each node's entry collects the
// components the conditions imposed (BoundaryConditions::apply).
template <int Dim>
void apply_boundary_conditions(const BoundaryConditions<Dim>& conditions, const Grid<Dim>& grid,
                               Vec<Dim>* velocity, Index first, Index last,
                               unsigned char* imposed = nullptr) {
  for (int face = 0; face < 2 * Dim; ++face) {
    const auto& condition = conditions[face];
    if (condition.kind == BoundaryKind::free) continue;
    const int axis = face / 2;
    const bool upper = face % 2 == 1;
    for_each_face_node_in(grid, axis, upper, first, last, [&](Index n) {
      const unsigned components =
          BoundaryConditions<Dim>::apply(condition, axis, upper, velocity[n]);
      if (imposed != nullptr) imposed[n] |= static_cast<unsigned char>(components);
    });
  }
}

// The same on every node of the grid.
template <int Dim>
void apply_boundary_conditions(const BoundaryConditions<Dim>& conditions, const Grid<Dim>& grid,
                               std::vector<Vec<Dim>>& velocity,
                               std::vector<unsigned char>* imposed = nullptr) {
  apply_boundary_conditions(conditions, grid, velocity.data(), 0, grid.node_count(),
                            imposed != nullptr ? imposed->data() : nullptr);
}

}  // namespace cosmpm::grid
