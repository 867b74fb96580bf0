#pragma once
// The deterministic parallel scatter: particles are bucketed into blocks of cells, and blocks
// of one colour (parity per axis) never share a node, so they scatter in parallel without
// locks; colours run in order and particles within a block in index order, so the sum at
// every node is taken in the same order whatever the thread count.
#include <algorithm>
#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/stencil_grid.hpp"

namespace cosmpm {

// What a particle visit of BlockScheduler::for_each_coloured reports.
enum class Visit { done, invalid_stencil, misplaced };

template <int Dim, shape::Kernel Kernel>
class BlockScheduler {
 public:
  // Cells per block along each axis. Longer along x, the fastest axis of seeded particle
  // indices, so a block's particles sit in longer runs of memory (fewer jumps in the scatter).
  static constexpr Index block_cells(int axis) { return axis == 0 ? 16 : 4; }
  static constexpr Index smallest_block_cells() { return block_cells(Dim > 1 ? 1 : 0); }
  // Same-colour blocks are two apart: they share no node only if a block spans at least the
  // kernel's support (a particle's stencil reaches support - 1 cells beyond its own).
  static_assert(smallest_block_cells() >= Kernel::support,
                "BlockScheduler: a particle block must span at least the kernel's support, or the "
                "parallel scatter races; raise block_cells() to the kernel's support");

  explicit BlockScheduler(const grid::Grid<Dim>& grid) {
    Index block_total = 1;
    for (int d = 0; d < Dim; ++d) {
      blocks_per_axis_[d] = (grid.cells(d) + block_cells(d) - 1) / block_cells(d);
      block_total *= blocks_per_axis_[d];
    }
    block_start_.assign(static_cast<std::size_t>(block_total + 1), 0);
    for (Index block = 0; block < block_total; ++block) {
      colour_blocks_[static_cast<std::size_t>(colour_of(block))].push_back(block);
    }
  }

  // What a particle loop needs to find and note particles' blocks, copied out of the
  // scheduler: a loop that stores Index values (the blocks themselves) would otherwise have
  // to reload the block counts for every particle.
  struct Lookup {
    std::array<Index, Dim> blocks_per_axis;
    Index* particle_block;

    // The block of cells a particle belongs to, from the cell that holds it.
    COSMPM_ALWAYS_INLINE Index block_of_cell(const std::array<Index, Dim>& cell) const {
      Index block = 0;
      for (int d = Dim - 1; d >= 0; --d) {
        // cell >= 0: unsigned division is a shift
        const auto b = static_cast<std::size_t>(cell[d]) / static_cast<std::size_t>(block_cells(d));
        block = block * blocks_per_axis[d] + static_cast<Index>(b);
      }
      return block;
    }
  };
  // Valid until the particle count changes (the next bucket()).
  Lookup lookup() { return {blocks_per_axis_, particle_block_.data()}; }

  // Called when a map moved a particle to another block: sorted again before the next scatter.
  void mark_changed() { changed_ = true; }

  // Sorts particles into blocks when needed: new particles, or particles the engine moved to
  // another block (the scatter finds any other move and calls resort()).
  template <class Positions>
  void bucket(const Positions& x, Index count, const shape::StencilGrid<Dim>& stencil_grid) {
    if (static_cast<Index>(particle_block_.size()) != count) {
      assign(x, count, stencil_grid);
    } else if (!changed_) {
      return;
    }
    sort(count);
  }

  // Every particle's block from its position, then sorted.
  template <class Positions>
  void resort(const Positions& x, Index count, const shape::StencilGrid<Dim>& stencil_grid) {
    assign(x, count, stencil_grid);
    sort(count);
  }

  // Runs f(p) over all particles, coloured (see the top of this header), with `threads`.
  // Returns the first particle whose visit reported an invalid stencil and the first
  // misplaced one (`count` for none); f may also return nothing. Also notes the largest team
  // of threads that ran a colour (last_team_size()).
  // One team runs the colours one after another, a barrier between them. Thread t takes the
  // t-th of `team` contiguous runs of each colour's blocks, the runs cut where the colour's
  // particles are shared equally, so a thread scatters the same region of the grid (and, with
  // particles indexed in seeding order, about the particles its static share of the particle
  // loops holds) in every colour and every step.
  template <class F>
  std::array<Index, 2> for_each_coloured([[maybe_unused]] int threads, Index count, F&& f) {
    const Index* start = block_start_.data();
    const Index* order = order_.data();
    Index first_invalid = count;
    Index first_misplaced = count;
    int team = 1;
    parallel_region(threads, count, [&] {
      // Locals: read through the closure, the arrays' addresses were reloaded per particle
      // (every store of f could alias the closure).
      const Index* const block_start = start;
      const Index* const sorted = order;
      F& visit_particle = f;
      const int thread = current_thread();
      const int size = current_team_size();
      if (thread == 0) team = size;
      Index invalid = count, misplaced = count;  // this thread's firsts
      for (const auto& blocks : colour_blocks_) {
        const auto [first, last] = share_of(blocks, thread, size);
        for (Index b = first; b < last; ++b) {
          const Index block = blocks[static_cast<std::size_t>(b)];
          for (Index i = block_start[block]; i < block_start[block + 1]; ++i) {
            const Index p = sorted[i];
            if constexpr (std::is_void_v<std::invoke_result_t<F&, Index>>) {
              visit_particle(p);
            } else {
              const Visit visit = visit_particle(p);
              if (visit == Visit::invalid_stencil) [[unlikely]]
                invalid = std::min(invalid, p);
              if (visit == Visit::misplaced) [[unlikely]]
                misplaced = std::min(misplaced, p);
            }
          }
        }
        team_barrier();
      }
      combine_min(first_invalid, invalid);
      combine_min(first_misplaced, misplaced);
    });
    last_team_size_ = team;
    return {first_invalid, first_misplaced};
  }

  // The cells along the slowest axis (Dim - 1, whose index strides are the longest) spanned by
  // the blocks that hold particles, as {first, last}; first > last if no block holds one. As
  // sorted by the last bucket() or resort().
  std::array<Index, 2> occupied_span() const {
    const Index* start = block_start_.data();
    const auto total = static_cast<Index>(block_start_.size()) - 1;
    Index first = 0;
    while (first < total && start[first + 1] == start[first]) ++first;
    if (first == total) return {1, 0};
    Index last = total - 1;
    while (start[last + 1] == start[last]) --last;
    const Index plane = total / blocks_per_axis_[Dim - 1];  // blocks per slowest-axis layer
    const Index cells = block_cells(Dim - 1);
    return {first / plane * cells, (last / plane + 1) * cells - 1};
  }

  // Threads that ran the last coloured pass (1 when it ran serially): lets a test check that
  // the parallel path it means to exercise actually ran.
  int last_team_size() const { return last_team_size_; }

 private:
  template <class Positions>
  void assign(const Positions& x, Index count, const shape::StencilGrid<Dim>& stencil_grid) {
    particle_block_.resize(static_cast<std::size_t>(count));
    for (Index p = 0; p < count; ++p) {
      std::array<Index, Dim> cell;
      for (int d = 0; d < Dim; ++d) {
        const double xi = (x[p][d] - stencil_grid.origin[d]) * stencil_grid.inverse_cell_size[d];
        // Clamped into the grid (NaN to 0): the stencil reports a particle outside.
        const double clamped =
            xi >= 0.0 ? (xi < stencil_grid.last[d] ? xi : stencil_grid.last[d]) : 0.0;
        cell[d] = stencil_grid.cell_of(d, clamped);
      }
      particle_block_[p] = lookup().block_of_cell(cell);
    }
  }

  // Blocks [first, last) of a colour's list for thread `thread` of `team`: the t-th run when
  // the list is cut into `team` contiguous runs of about equal particle counts (a run ends at
  // the first block whose cumulative count reaches (t + 1) / team of the colour's particles).
  std::array<Index, 2> share_of(const std::vector<Index>& blocks, int thread, int team) const {
    const auto size = static_cast<Index>(blocks.size());
    if (team == 1) return {0, size};
    Index total = 0;
    for (const Index block : blocks) total += block_start_[block + 1] - block_start_[block];
    // The run of thread k ends after the block that takes the cumulative count to
    // ceil(total (k + 1) / team): thread k's run is (end of k - 1, end of k].
    const auto end_of = [&](int k) {
      if (k < 0) return Index{0};
      if (k + 1 >= team) return size;
      const Index target = (total * (k + 1) + team - 1) / team;
      Index sum = 0;
      Index b = 0;
      while (b < size && sum < target) {
        sum += block_start_[blocks[static_cast<std::size_t>(b)] + 1] -
               block_start_[blocks[static_cast<std::size_t>(b)]];
        ++b;
      }
      return b;
    };
    return {end_of(thread - 1), end_of(thread)};
  }

  // Counting sort by block; within a block particles keep index order, so the order (and with
  // it every nodal sum) is a function of the blocks alone.
  void sort(Index count) {
    order_.resize(static_cast<std::size_t>(count));
    std::fill(block_start_.begin(), block_start_.end(), 0);
    for (Index p = 0; p < count; ++p) ++block_start_[particle_block_[p] + 1];
    for (std::size_t b = 1; b < block_start_.size(); ++b) block_start_[b] += block_start_[b - 1];
    block_fill_.assign(block_start_.begin(), block_start_.end() - 1);
    for (Index p = 0; p < count; ++p) order_[block_fill_[particle_block_[p]]++] = p;
    changed_ = false;
  }

  int colour_of(Index block) const {
    int colour = 0;
    for (int d = 0; d < Dim; ++d) {
      colour |= static_cast<int>((block % blocks_per_axis_[d]) & 1) << d;
      block /= blocks_per_axis_[d];
    }
    return colour;
  }

  std::array<Index, Dim> blocks_per_axis_{};
  std::vector<Index> block_start_;
  std::array<std::vector<Index>, (1 << Dim)> colour_blocks_;  // the blocks of each colour
  std::vector<Index> block_fill_;
  std::vector<Index> particle_block_;
  std::vector<Index> order_;
  bool changed_ = false;
  int last_team_size_ = 1;
};

}  // namespace cosmpm
