#pragma once
// The nodes a step's particles reach (EngineState::node_range). The dense node passes (the
// records' clearing, the node fields from the records, the grid update, the remapped
// velocities, the rate records) run over them only: a soil bed under a tall grid leaves most
// nodes empty (the flat blade: 5,700 of 8,591).
//
// Every node outside the range holds zero fields, the values a pass over it would give: no
// particle reaches it, so its mass, momenta and forces are zero and its velocities are
// cleared; the face conditions keep a zero field zero, and contact laws skip nodes without
// mass. A node that leaves the range is zeroed when it leaves.
#include <algorithm>

#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/simulation/node_fields.hpp"

namespace cosmpm::stages {

// Every node: the records a scatter at positions not yet sorted into blocks clears (the fused
// passes, at the end-of-step positions). The next step's range then comes from the stencils
// the scatter met (stages/fused_pass.hpp, map_to_grid_or_reuse).
template <class State>
NodeRange all_nodes(const State& s) {
  return {0, s.grid.node_count()};
}

// The node range becomes `range` (every node with s.prune_node_range off); the nodes that
// leave it are zeroed.
template <class State>
void set_node_range(State& s, NodeRange range) {
  if (!s.prune_node_range) range = all_nodes(s);
  const NodeRange old = s.node_range;
  s.nodes.clear(old.first, std::min(range.first, old.end));
  s.nodes.clear(std::max(range.end, old.first), old.end);
  s.node_range = range;
}

// The range of the layers (along the slowest axis, whose node index stride is the longest)
// that the particles' blocks can reach, as sorted by the block scheduler. A particle's S
// stencil nodes along an axis include one of its cell's two nodes, so from cell c they reach
// from node c - (S - 1) to node c + S.
template <class State>
void reach_occupied_nodes(State& s) {
  constexpr int Dim = State::dim;
  constexpr Index S = State::kernel_type::support;
  const auto [first_cell, last_cell] = s.blocks.occupied_span();
  if (first_cell > last_cell) {
    set_node_range(s, {0, 0});
    return;
  }
  Index layer = 1;  // nodes per layer
  for (int d = 0; d < Dim - 1; ++d) layer *= s.grid.nodes(d);
  const Index low = std::max<Index>(0, first_cell - (S - 1));
  const Index high = std::min<Index>(s.grid.nodes(Dim - 1) - 1, last_cell + S);
  set_node_range(s, {low * layer, (high + 1) * layer});
}

// The calling thread's static share of a node range (static_share's split of its size).
inline Share node_share(NodeRange range) {
  const Share share = cosmpm::static_share(range.size());
  return {range.first + share.first, range.first + share.last};
}

}  // namespace cosmpm::stages
