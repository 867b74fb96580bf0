#pragma once
// Boundary treatment shared by the kernels whose support reaches past the grid edge.
//
// Near an edge an unmodified kernel gives weight to a ghost node one spacing outside the
// grid. The ghost's nodal value is taken as the linear extrapolation of the two nodes next
// to it, v_ghost = 2 v_edge - v_inner, so its weight N_g folds onto them:
//   N_edge += 2 N_g,  N_inner -= N_g   (the same for the gradients).
// Partition of unity and exact reproduction of linear fields survive the fold because both
// sides agree on constants and linear functions; see docs/theory/mpm.md, "Shape functions".
#include <array>
#include <cstddef>
#include <utility>

#include "cosmpm/core/types.hpp"

namespace cosmpm::shape::detail {

// The stencil starts one node below the grid (slot 0 is the ghost node -1); afterwards it
// starts at node 0 and its last slot is empty.
template <class T, std::size_t S>
inline void fold_lower_ghost(std::array<T, S>& v) {
  static_assert(S >= 3, "a folded stencil needs the ghost, the edge node and an inner node");
  const T ghost = v[0];
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((v[K] = v[K + 1]), ...);  // ascending: each slot is read before it is overwritten
  }
  (std::make_index_sequence<S - 1>{});
  v[S - 1] = T(0);
  v[0] += T(2) * ghost;
  v[1] -= ghost;
}

// The stencil ends one node above the grid (slot S-1 is the ghost node node_count); afterwards
// it ends at node node_count - 1 and its first slot is empty.
template <class T, std::size_t S>
inline void fold_upper_ghost(std::array<T, S>& v) {
  static_assert(S >= 3, "a folded stencil needs the ghost, the edge node and an inner node");
  const T ghost = v[S - 1];
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((v[S - 1 - K] = v[S - 2 - K]), ...);  // descending, for the same reason
  }
  (std::make_index_sequence<S - 1>{});
  v[0] = T(0);
  v[S - 1] += T(2) * ghost;
  v[S - 2] -= ghost;
}

// A stencil of S nodes starting at `first` may stick out of the grid by one node at either
// edge (no kernel reaches further); folds the ghost back and returns the grid's first node.
template <class T, std::size_t S>
inline Index fold_into_grid(Index first, Index node_count, std::array<T, S>& weights,
                            std::array<T, S>& gradients) {
  if (first < 0) [[unlikely]] {
    fold_lower_ghost(weights);
    fold_lower_ghost(gradients);
    return 0;
  }
  const Index last_first = node_count - static_cast<Index>(S);
  if (first > last_first) [[unlikely]] {
    fold_upper_ghost(weights);
    fold_upper_ghost(gradients);
    return last_first;
  }
  return first;
}

// fold_into_grid for the lanes of a pack P of doubles (GCC/Clang vector extensions): the lanes
// of `below` fold their lower ghost, those of `above` their upper one, each with the scalar
// fold's arithmetic; the other lanes keep their values.
template <class P, class Mask, std::size_t S>
inline void fold_lanes_into_grid(const Mask& below, const Mask& above, std::array<P, S>& v) {
  static_assert(S >= 3, "a folded stencil needs the ghost, the edge node and an inner node");
  const P zero{};
  std::array<P, S> lower, upper;
  for (std::size_t k = 0; k + 1 < S; ++k) {
    lower[k] = v[k + 1];
    upper[k + 1] = v[k];
  }
  lower[S - 1] = zero;
  upper[0] = zero;
  lower[0] += 2.0 * v[0];
  lower[1] -= v[0];
  upper[S - 1] += 2.0 * v[S - 1];
  upper[S - 2] -= v[S - 1];
  for (std::size_t k = 0; k < S; ++k) v[k] = below ? lower[k] : (above ? upper[k] : v[k]);
}
}  // namespace cosmpm::shape::detail
