#pragma once
// The candidate contacts of the DEM: element pairs and element-wall pairs closer than a skin,
// found with a cell list (Verlet lists). Building them is linear in the number of elements:
// elements are counting-sorted into square cells of side 2 r_max + skin, and each element
// looks at the 3 x 3 cells around its own. The lists are reused for as long as no element has
// drifted more than skin / 2 since they were built (and no wall more than the rest of the
// skin), so no contact can be missed in between. Each pair keeps its shear-force history
// across rebuilds. Pairs are sorted by (first, second) and wall candidates by (element, wall),
// whatever the thread count, so results are bit-identical for any number of threads.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/contact_law.hpp"
#include "cosmpm/dem/detail/parallel.hpp"
#include "cosmpm/dem/fields.hpp"

namespace cosmpm::dem {

class ContactLists {
 public:
  // Particle pairs: first < second, different bodies.
  std::vector<std::int32_t> first;
  std::vector<std::int32_t> second;
  std::vector<ContactHistory> history;     // the contact law's memory
  std::vector<Index> first_offsets;        // pairs of element e as first: [off[e], off[e+1])
  std::vector<Index> second_offsets;       // the same for second, into second_pairs
  std::vector<std::int32_t> second_pairs;  // pair indices, increasing for each element
  // Element-wall candidates.
  std::vector<std::int32_t> wall_element;
  std::vector<std::int32_t> wall_index;
  std::vector<ContactHistory> wall_history;
  std::vector<Index> wall_offsets;  // candidates of element e: [off[e], off[e+1])
  std::vector<Vec<2>> built_at;     // element positions when built
  Index builds = 0;

  Index pair_count() const { return static_cast<Index>(first.size()); }
  Index wall_candidate_count() const { return static_cast<Index>(wall_element.size()); }

  // Builds the lists for `elements`; `wall_gap(w, x)` is the distance of x from wall w's
  // surface (negative inside) and `wall_enabled(w)` whether it takes part. With
  // `keep_history` the shear histories of pairs present before and now are carried over
  // (the elements must be the same ones as at the last build).
  template <class WallGap, class WallEnabled>
  void build(const ElementStore& elements, double skin, int threads, Index walls,
             WallGap&& wall_gap, WallEnabled&& wall_enabled, bool keep_history) {
    const Index n = elements.size();
    const auto& x = elements.get<tag::Position<2>>();
    const auto& r = elements.get<field::Radius>();
    const auto& body = elements.get<tag::Body>();
    build_cells(x, r, skin);

    std::vector<std::int32_t> old_first, old_second;
    std::vector<ContactHistory> old_history;
    std::vector<Index> old_offsets;
    std::vector<std::int32_t> old_wall_element, old_wall_index;
    std::vector<ContactHistory> old_wall_history;
    std::vector<Index> old_wall_offsets;
    keep_history = keep_history && static_cast<Index>(first_offsets.size()) == n + 1 &&
                   static_cast<Index>(wall_offsets.size()) == n + 1;
    if (keep_history) {
      old_first.swap(first);
      old_second.swap(second);
      old_history.swap(history);
      old_offsets.swap(first_offsets);
      old_wall_element.swap(wall_element);
      old_wall_index.swap(wall_index);
      old_wall_history.swap(wall_history);
      old_wall_offsets.swap(wall_offsets);
    }

    // Pass 1: how many candidates each element has (as first, and against walls).
    std::vector<Index> pair_counts(static_cast<std::size_t>(n) + 1, 0);
    std::vector<Index> wall_counts(static_cast<std::size_t>(n) + 1, 0);
    detail::parallel_for(threads, n, [&](Index i) {
      Index count = 0;
      for_each_neighbour(x, r, body, i, skin, [&](Index) { ++count; });
      pair_counts[static_cast<std::size_t>(i)] = count;
      Index wc = 0;
      for (Index w = 0; w < walls; ++w) {
        if (wall_enabled(w) &&
            wall_gap(w, x[static_cast<std::size_t>(i)]) - r[static_cast<std::size_t>(i)] < skin) {
          ++wc;
        }
      }
      wall_counts[static_cast<std::size_t>(i)] = wc;
    });
    first_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
    wall_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
    for (Index i = 0; i < n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      first_offsets[u + 1] = first_offsets[u] + pair_counts[u];
      wall_offsets[u + 1] = wall_offsets[u] + wall_counts[u];
    }
    const auto pairs = static_cast<std::size_t>(first_offsets.back());
    const auto wall_pairs = static_cast<std::size_t>(wall_offsets.back());
    first.assign(pairs, 0);
    second.assign(pairs, 0);
    history.assign(pairs, ContactHistory{});
    wall_element.assign(wall_pairs, 0);
    wall_index.assign(wall_pairs, 0);
    wall_history.assign(wall_pairs, ContactHistory{});

    // Pass 2: fill, sort each element's partners, carry the histories over.
    detail::parallel_for(threads, n, [&](Index i) {
      const auto u = static_cast<std::size_t>(i);
      const Index begin = first_offsets[u];
      Index k = begin;
      for_each_neighbour(x, r, body, i, skin, [&](Index j) {
        first[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(i);
        second[static_cast<std::size_t>(k++)] = static_cast<std::int32_t>(j);
      });
      std::sort(second.begin() + begin, second.begin() + k);
      Index wk = wall_offsets[u];
      for (Index w = 0; w < walls; ++w) {
        if (wall_enabled(w) && wall_gap(w, x[u]) - r[u] < skin) {
          wall_element[static_cast<std::size_t>(wk)] = static_cast<std::int32_t>(i);
          wall_index[static_cast<std::size_t>(wk++)] = static_cast<std::int32_t>(w);
        }
      }
      if (!keep_history) return;
      carry(old_second, old_history, old_offsets[u], old_offsets[u + 1], second, history, begin, k);
      carry(old_wall_index, old_wall_history, old_wall_offsets[u], old_wall_offsets[u + 1],
            wall_index, wall_history, wall_offsets[u], wk);
    });

    // Pairs by their second element, in increasing pair order.
    second_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
    for (const std::int32_t j : second) ++second_offsets[static_cast<std::size_t>(j) + 1];
    for (Index i = 0; i < n; ++i) {
      second_offsets[static_cast<std::size_t>(i) + 1] +=
          second_offsets[static_cast<std::size_t>(i)];
    }
    second_pairs.assign(pairs, 0);
    std::vector<Index> cursor(second_offsets.begin(), second_offsets.end() - 1);
    for (std::size_t p = 0; p < pairs; ++p) {
      second_pairs[static_cast<std::size_t>(cursor[static_cast<std::size_t>(second[p])]++)] =
          static_cast<std::int32_t>(p);
    }
    built_at = x;
    ++builds;
  }

 private:
  // Copies the history of keys present in both sorted runs.
  static void carry(const std::vector<std::int32_t>& old_keys,
                    const std::vector<ContactHistory>& old_values, Index old_begin, Index old_end,
                    const std::vector<std::int32_t>& keys, std::vector<ContactHistory>& values,
                    Index begin, Index end) {
    Index a = old_begin;
    for (Index b = begin; b < end && a < old_end; ++b) {
      const std::int32_t key = keys[static_cast<std::size_t>(b)];
      while (a < old_end && old_keys[static_cast<std::size_t>(a)] < key) ++a;
      if (a < old_end && old_keys[static_cast<std::size_t>(a)] == key) {
        values[static_cast<std::size_t>(b)] = old_values[static_cast<std::size_t>(a)];
      }
    }
  }

  void build_cells(const std::vector<Vec<2>>& x, const std::vector<double>& r, double skin) {
    const Index n = static_cast<Index>(x.size());
    lower_ = Vec<2>::Constant(std::numeric_limits<double>::infinity());
    Vec<2> upper = -lower_;
    double r_max = 0.0;
    for (Index e = 0; e < n; ++e) {
      lower_ = lower_.cwiseMin(x[static_cast<std::size_t>(e)]);
      upper = upper.cwiseMax(x[static_cast<std::size_t>(e)]);
      r_max = std::max(r_max, r[static_cast<std::size_t>(e)]);
    }
    if (n == 0) lower_ = upper = Vec<2>::Zero();
    cell_ = std::max(2.0 * r_max + skin, 1e-12);
    // A particle flung far away must not blow up the grid: coarser cells stay correct.
    for (;;) {
      nx_ = static_cast<Index>(std::floor((upper[0] - lower_[0]) / cell_)) + 1;
      ny_ = static_cast<Index>(std::floor((upper[1] - lower_[1]) / cell_)) + 1;
      if (nx_ * ny_ <= 4 * n + 64) break;
      cell_ *= 1.5;
    }
    const Index cells = nx_ * ny_;
    cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
    cell_of_.resize(static_cast<std::size_t>(n));
    for (Index e = 0; e < n; ++e) {
      const Index c = cell_index(x[static_cast<std::size_t>(e)]);
      cell_of_[static_cast<std::size_t>(e)] = c;
      ++cell_start_[static_cast<std::size_t>(c) + 1];
    }
    for (Index c = 0; c < cells; ++c) {
      cell_start_[static_cast<std::size_t>(c) + 1] += cell_start_[static_cast<std::size_t>(c)];
    }
    cell_items_.resize(static_cast<std::size_t>(n));
    std::vector<Index> cursor(cell_start_.begin(), cell_start_.end() - 1);
    for (Index e = 0; e < n; ++e) {
      cell_items_[static_cast<std::size_t>(
          cursor[static_cast<std::size_t>(cell_of_[static_cast<std::size_t>(e)])]++)] =
          static_cast<std::int32_t>(e);
    }
  }

  Index cell_index(const Vec<2>& p) const {
    const Index i = std::clamp<Index>(static_cast<Index>((p[0] - lower_[0]) / cell_), 0, nx_ - 1);
    const Index j = std::clamp<Index>(static_cast<Index>((p[1] - lower_[1]) / cell_), 0, ny_ - 1);
    return i + nx_ * j;
  }

  // f(j) for every element j > i of another body within r_i + r_j + skin of element i.
  template <class F>
  void for_each_neighbour(const std::vector<Vec<2>>& x, const std::vector<double>& r,
                          const std::vector<std::int32_t>& body, Index i, double skin,
                          F&& f) const {
    const auto u = static_cast<std::size_t>(i);
    const Index c = cell_of_[u];
    const Index ci = c % nx_, cj = c / nx_;
    for (Index j = std::max<Index>(cj - 1, 0); j <= std::min(cj + 1, ny_ - 1); ++j) {
      for (Index k = std::max<Index>(ci - 1, 0); k <= std::min(ci + 1, nx_ - 1); ++k) {
        const Index cell = k + nx_ * j;
        for (Index s = cell_start_[static_cast<std::size_t>(cell)];
             s < cell_start_[static_cast<std::size_t>(cell) + 1]; ++s) {
          const auto other = static_cast<std::size_t>(cell_items_[static_cast<std::size_t>(s)]);
          if (other <= u || body[other] == body[u]) continue;
          const double reach = r[u] + r[other] + skin;
          if ((x[other] - x[u]).squaredNorm() < reach * reach) f(static_cast<Index>(other));
        }
      }
    }
  }

  Vec<2> lower_ = Vec<2>::Zero();
  double cell_ = 1.0;
  Index nx_ = 1;
  Index ny_ = 1;
  std::vector<Index> cell_start_;
  std::vector<Index> cell_of_;
  std::vector<std::int32_t> cell_items_;
};

}  // namespace cosmpm::dem
