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
#include <array>
#include <string>

#include "cosmpm/core/error.hpp"
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

// The fused pass's second-half records not yet added (stages/fused_pass.hpp, over_halves):
// the node pass that reads the records completes them in its own thread's nodes
// (complete_records), so no thread adds them all alone between the passes.
struct PendingUpper {
  double* upper = nullptr;
  Index first = 0;
  Index end = 0;
  Index width = 0;
  NodeRange lower{0, 0};  // outside it the first half's records are zero
};

// Takes the pending second-half records for a node pass over records of `width` doubles.
template <class State>
PendingUpper take_pending_upper(State& s, Index width) {
  const PendingUpper pending{s.scatter_upper.data(), s.upper_first, s.upper_end, width,
                             s.lower_nodes};
  if (pending.end > pending.first) {
    require(s.upper_width == width, "a node pass read " + std::to_string(width) +
                                        " doubles per node where the fused pass wrote " +
                                        std::to_string(s.upper_width));
  }
  s.upper_first = s.upper_end = 0;
  s.lower_nodes = {0, 0};
  return pending;
}

// The records of the nodes [first, last) completed: their second-half terms added to their
// first half's, in that order, and zeroed for the next pass.
inline void add_pending_upper(const PendingUpper& pending, double* records, Index first,
                              Index last) {
  first = std::max(first, pending.first);
  last = std::min(last, pending.end);
  double* const upper = pending.upper;
  for (Index i = first * pending.width; i < last * pending.width; ++i) {
    records[i] += upper[i];
    upper[i] = 0.0;
  }
}

// A run of nodes [first, last) whose complete records lie in `records` (record n at
// records + n * width), which the reader zeroes after reading.
struct RecordRun {
  Index first;
  Index last;
  double* records;
};

// The runs of complete_records, in node order.
struct RecordRuns {
  std::array<RecordRun, 5> runs;  // cut at most at four bounds
  int count = 0;
  const RecordRun* begin() const { return runs.data(); }
  const RecordRun* end() const { return runs.data() + count; }
};

// The records of the nodes [first, last) completed, as add_pending_upper, where both halves
// wrote; where only the second half did, its own records are complete as they are (the first
// half's are +0, and +0 + x is x: a sum that starts at +0 is never -0) and are read there, in
// place of a pass that adds them (on two threads the thread whose nodes the second half
// reaches did that pass alone). Returns where each run's records are.
inline RecordRuns complete_records(const PendingUpper& pending, double* records, Index first,
                                   Index last) {
  RecordRuns runs;
  const std::array<Index, 4> bounds{pending.first, pending.end, pending.lower.first,
                                    pending.lower.end};
  for (Index n = first; n < last;) {
    Index next = last;
    for (const Index bound : bounds) {
      if (bound > n && bound < next) next = bound;
    }
    const bool upper = n >= pending.first && n < pending.end;
    const bool lower = n >= pending.lower.first && n < pending.lower.end;
    if (upper && lower) add_pending_upper(pending, records, n, next);
    double* const source = upper && !lower ? pending.upper : records;
    if (runs.count > 0 && runs.runs[runs.count - 1].records == source) {
      runs.runs[runs.count - 1].last = next;
    } else {
      runs.runs[runs.count++] = {n, next, source};
    }
    n = next;
  }
  return runs;
}

// Drops pending second-half records: whatever clears the records starts afresh.
template <class State>
void discard_pending_upper(State& s) {
  if (s.upper_end > s.upper_first) {
    const auto at = [&](Index n) { return s.scatter_upper.begin() + n * s.upper_width; };
    std::fill(at(s.upper_first), at(s.upper_end), 0.0);
  }
  s.upper_first = s.upper_end = 0;
  s.lower_nodes = {0, 0};
}

}  // namespace cosmpm::stages::detail
