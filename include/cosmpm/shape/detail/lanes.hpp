#pragma once
// What the kernels' evaluate_lanes share: a pack's floors and cells, in doubles, converted as
// whole packs (lane by lane it took a dozen instructions per lane and axis).
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::shape::detail {

// Each lane's floor, for xi >= 0 (truncation is floor) and below 2^31.
template <class P>
inline P floor_lanes(const P& xi) {
  constexpr int lanes = static_cast<int>(sizeof(P) / sizeof(double));
  return __builtin_convertvector(__builtin_convertvector(xi, IntPack<lanes>), P);
}

// The cell holding each lane's xi (0 <= xi <= the last node); the last node belongs to the
// last cell, as in the kernels' evaluate.
template <class P>
inline P cell_lanes(const P& xi, Index node_count) {
  const P whole = floor_lanes(xi);
  const P last_cell = P{} + static_cast<double>(node_count - 2);
  return whole < last_cell ? whole : last_cell;
}

}  // namespace cosmpm::shape::detail
