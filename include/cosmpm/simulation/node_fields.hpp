#pragma once
// The fields the engine keeps on grid nodes, and the node records its transfers work on.
//
// NodeFields are the public per-field arrays (contact laws, output and tests read them). The
// particle-grid maps instead read and write records of C doubles per node (node n's component
// c at n * C + c), so a stencil row is one run of memory reached from one address; node passes
// copy between the two.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "cosmpm/core/types.hpp"

namespace cosmpm {

// A contiguous run of node indices, [first, end).
struct NodeRange {
  Index first;
  Index end;
  Index size() const { return end - first; }
};

// Translational fields per node, and R rotational degrees of freedom per node (the
// continuum's; Cosserat 2D: R = 1, the micro-rotation), stored node-major (n * R + k) and
// empty when R = 0.
template <int Dim, int R>
struct NodeFields {
  std::vector<double> mass;
  std::vector<Vec<Dim>> momentum;  // momentum, then velocity at the start of the step
  std::vector<Vec<Dim>> force;
  std::vector<Vec<Dim>> velocity;  // updated velocity (end of the step)
  std::vector<Vec<Dim>> acceleration;
  // Lumped rotational inertia sum N m J, spin momentum then start spin, moment, end spin and
  // spin acceleration.
  std::vector<double> rotational_inertia;
  std::vector<double> spin_momentum;
  std::vector<double> moment;
  std::vector<double> spin;
  std::vector<double> spin_acceleration;

  explicit NodeFields(Index nodes = 0) { resize(nodes); }

  void resize(Index nodes) {
    const auto n = static_cast<std::size_t>(nodes);
    mass.assign(n, 0.0);
    momentum.assign(n, Vec<Dim>::Zero());
    force.assign(n, Vec<Dim>::Zero());
    velocity.assign(n, Vec<Dim>::Zero());
    acceleration.assign(n, Vec<Dim>::Zero());
    for (auto* field : {&rotational_inertia, &spin_momentum, &moment, &spin, &spin_acceleration})
      field->assign(n * static_cast<std::size_t>(R), 0.0);
  }

  // Every field of the nodes [first, end) zeroed: what the node passes give a node no
  // particle reaches.
  void clear(Index first, Index end) {
    if (end <= first) return;
    const auto a = static_cast<std::ptrdiff_t>(first);
    const auto b = static_cast<std::ptrdiff_t>(end);
    std::fill(mass.begin() + a, mass.begin() + b, 0.0);
    for (auto* field : {&momentum, &force, &velocity, &acceleration})
      std::fill(field->begin() + a, field->begin() + b, Vec<Dim>::Zero());
    for (auto* field : {&rotational_inertia, &spin_momentum, &moment, &spin, &spin_acceleration})
      std::fill(field->begin() + a * R, field->begin() + b * R, 0.0);
  }
};

// The particle-to-grid record: weighted-only components first (mass, momentum, rotational
// inertia and spin momentum, and A affine-momentum terms of an affine transfer), then those
// that also take a gradient term (force, moment).
template <int Dim, int R, int A = 0>
struct ScatterRecord {
  static constexpr int mass = 0;
  static constexpr int momentum = 1;  // Dim components
  static constexpr int inertia = 1 + Dim;
  static constexpr int spin_momentum = 1 + Dim + R;
  static constexpr int affine = 1 + Dim + 2 * R;  // A = Dim x Dim components, row-major
  static constexpr int weighted = 1 + Dim + 2 * R + A;
  static constexpr int force = weighted;  // Dim components
  static constexpr int moment = weighted + Dim;
  static constexpr int all = weighted + Dim + R;
};

// The grid-to-particle record: the fields with gradients (velocity, spin) first, then the
// accelerations.
template <int Dim, int R>
struct GatherRecord {
  static constexpr int velocity = 0;  // Dim components
  static constexpr int spin = Dim;
  static constexpr int with_gradient = Dim + R;
  static constexpr int acceleration = with_gradient;  // Dim components
  static constexpr int spin_acceleration = with_gradient + Dim;
  static constexpr int all = 2 * with_gradient;
};

}  // namespace cosmpm
