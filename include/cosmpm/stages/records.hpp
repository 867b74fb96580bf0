#pragma once
// The zeros of the node records (EngineState::scatter) between the passes that write them (the
// scatters, the remap, USF's forces) and the node passes that read them. A reader zeroes each
// record right after reading it, while its cache line is at hand, and the state keeps the
// extent that may still be nonzero (EngineState::scatter_dirty); a writer then clears only
// what of its extent lies in there, usually nothing. Before, every writer cleared its extent
// in a pass of its own: 1-2 % of a step, and of the fused steps, which clear every node.
// Any writer and any reader may run in any order: what no reader zeroed stays in the extent
// and is cleared by the next writer that needs it.
#include <algorithm>

#include "cosmpm/core/types.hpp"
#include "cosmpm/simulation/node_fields.hpp"

namespace cosmpm::stages::detail {

// Before a pass adds terms to the records' doubles [first, end) of s.scatter (sized for them):
// zeroes those that may be nonzero, and counts the extent as written.
template <class State>
void zero_records_for_writing(State& s, Index first, Index end) {
  NodeRange& dirty = s.scatter_dirty;
  const Index from = std::max(first, dirty.first);
  const Index to = std::min(end, dirty.end);
  if (from < to) std::fill(s.scatter.begin() + from, s.scatter.begin() + to, 0.0);
  if (dirty.size() <= 0 || (first <= dirty.first && end >= dirty.end)) {
    dirty = {first, end};  // the rest of the buffer is zero
  } else {
    dirty = {std::min(first, dirty.first), std::max(end, dirty.end)};
  }
}

// After a pass that zeroed every record before writing (its extent covered the dirty one)
// wrote only within the doubles [first, end): the extent narrowed to them.
template <class State>
void records_written_within(State& s, Index first, Index end) {
  s.scatter_dirty = {first, end};
}

// After a node pass read the doubles [first, end) and zeroed them.
template <class State>
void records_read_and_zeroed(State& s, Index first, Index end) {
  NodeRange& dirty = s.scatter_dirty;
  if (first <= dirty.first && end >= dirty.end) {
    dirty = {0, 0};
  } else if (first <= dirty.first && end > dirty.first) {
    dirty.first = end;
  } else if (end >= dirty.end && first < dirty.end) {
    dirty.end = first;
  }
}

}  // namespace cosmpm::stages::detail
