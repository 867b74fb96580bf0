#pragma once
// Packings made the way the paper made its DEM layer: particles placed on a loose lattice
// above the rig from a fixed height, with random sizes and orientations, rained under
// gravity into the rig and settled (Coetzee 2014, Sect. 2: about 10,000 particles along the
// rig); then trimmed to the layer depth, and the porosity of the result measured.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/assembly.hpp"
#include "cosmpm/dem/clump.hpp"

namespace cosmpm::dem {

// SplitMix64: the same numbers on every platform (std's distributions are not specified).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

// What is rained: a clump shape (one disk of diameter 1 for disks) of unit size, scaled by a
// size drawn uniformly from [min_size, max_size] (PFC's uniform distribution).
struct Grains {
  ClumpShape shape = ClumpShape({{Vec<2>::Zero(), 0.5}});
  double min_size = 0.009;  // m
  double max_size = 0.011;  // m
  double density = 855.0;   // kg/m^3 (Table 1)

  void validate(const char* where) const {
    require_positive(where, "min size", min_size);
    require_in_range(where, "max size", max_size, min_size, 1e300, Bounds::left_closed);
    require_positive(where, "density", density);
  }
  double mean_area() const {
    // E[s^2] for s uniform in [a, b] is (a^2 + ab + b^2) / 3.
    return shape.area() * (min_size * min_size + min_size * max_size + max_size * max_size) / 3.0;
  }
};

// Where the lattice goes: between x = left and x = right, rows from y = bottom (the fixed
// height of the lowest row) upwards, never above y = top (the top of the rig's walls).
struct RainColumn {
  double left = 0.0;
  double right = 1.0;
  double bottom = 0.5;
  double top = 2.0;
};

// Adds `count` grains on a jittered lattice (one per site, no overlaps), row by row from the
// bottom; returns the index of the first body added. Throws when they do not fit.
inline Index rain(Assembly& assembly, const Grains& grains, Index count, const RainColumn& column,
                  std::uint64_t seed = 1) {
  const char* where = "dem::rain";
  grains.validate(where);
  require_in_range(where, "particle count", static_cast<double>(count), 1.0, 1e9, Bounds::closed);
  require(column.right > column.left && column.top > column.bottom,
          "dem::rain: the rain column must have right > left and top > bottom");
  const double reach = 2.0 * grains.shape.bounding_radius() * grains.max_size;  // largest extent
  const double spacing = 1.02 * reach;
  const auto columns = static_cast<Index>(std::floor((column.right - column.left) / spacing));
  const auto rows_fit = static_cast<Index>(std::floor((column.top - column.bottom) / spacing));
  const Index capacity = std::max<Index>(columns, 0) * std::max<Index>(rows_fit, 0);
  if (count > capacity) {
    throw Error(std::string(where) + ": " + std::to_string(count) +
                " particles do not fit above the rig: its walls hold " + std::to_string(capacity) +
                " lattice sites of " + cosmpm::detail::format_number(spacing) +
                " m between x = " + cosmpm::detail::format_number(column.left) + " and " +
                cosmpm::detail::format_number(column.right) +
                " m, y = " + cosmpm::detail::format_number(column.bottom) + " and " +
                cosmpm::detail::format_number(column.top) + " m (valid range [1, " +
                std::to_string(capacity) + "])");
  }
  Random random(seed);
  const Index first = assembly.body_count();
  for (Index k = 0; k < count; ++k) {
    const Index row = k / columns, col = k % columns;
    const double size = random.uniform(grains.min_size, grains.max_size);
    const double room = 0.5 * (spacing - 2.0 * grains.shape.bounding_radius() * size);
    const Vec<2> centre(
        column.left + (static_cast<double>(col) + 0.5) * spacing + random.uniform(-room, room),
        column.bottom + (static_cast<double>(row) + 0.5) * spacing + random.uniform(-room, room));
    const double angle = random.uniform(0.0, 2.0 * pi);
    assembly.add_clump(grains.shape, size, centre, angle, grains.density);
  }
  return first;
}

struct SettleReport {
  double time = 0.0;  // simulated, s
  std::int64_t steps = 0;
  double unbalanced_force_ratio = 1.0;
  bool settled = false;
};

// Steps until PFC's mean unbalanced force ratio falls below `ratio` (checked every 100 steps,
// after at least `min_time`) or `max_time` has passed. `on_step` is called after each step.
template <class Sim, class OnStep = void (*)(const Sim&)>
SettleReport settle(
    Sim& sim, double dt, double max_time, double ratio, double min_time = 0.0,
    OnStep on_step = [](const Sim&) {}) {
  const char* where = "dem::settle";
  require_positive(where, "max time", max_time);
  require_positive(where, "unbalanced force ratio", ratio);
  SettleReport report;
  const double start = sim.time();
  while (sim.time() - start < max_time) {
    sim.step(dt);
    on_step(sim);
    ++report.steps;
    if (report.steps % 100 == 0 && sim.time() - start >= min_time) {
      report.unbalanced_force_ratio = sim.unbalanced_force_ratio();
      if (report.unbalanced_force_ratio < ratio) {
        report.settled = true;
        break;
      }
    }
  }
  report.time = sim.time() - start;
  if (!report.settled) report.unbalanced_force_ratio = sim.unbalanced_force_ratio();
  return report;
}

// Removes the bodies whose centroid lies above `height` (PFC's way of levelling a layer).
inline Index trim_above(Assembly& assembly, double height) {
  return assembly.remove_bodies_if([&](Index b) { return assembly.position(b)[1] > height; });
}

// Porosity of the window [lower, upper]: the fraction of a grid of sample points (spacing
// `resolution`) covered by no disk. Exact up to the sampling: overlapping disks of a clump
// are counted once and disks cut by the window edge only in part.
inline double porosity(const Assembly& assembly, const Vec<2>& lower, const Vec<2>& upper,
                       double resolution) {
  const char* where = "dem::porosity";
  require_positive(where, "resolution", resolution);
  require(upper[0] > lower[0] && upper[1] > lower[1],
          "dem::porosity: the window needs upper > lower on both axes");
  const auto& x = assembly.elements().get<tag::Position<2>>();
  const auto& r = assembly.elements().get<field::Radius>();
  const double cell = std::max(2.0 * assembly.max_radius(), resolution);
  const auto nx = static_cast<Index>(std::ceil((upper[0] - lower[0]) / cell)) + 2;
  const auto ny = static_cast<Index>(std::ceil((upper[1] - lower[1]) / cell)) + 2;
  std::vector<std::vector<std::int32_t>> cells(static_cast<std::size_t>(nx * ny));
  auto cell_of = [&](const Vec<2>& p, Index& i, Index& j) {
    i = static_cast<Index>(std::floor((p[0] - lower[0]) / cell)) + 1;
    j = static_cast<Index>(std::floor((p[1] - lower[1]) / cell)) + 1;
  };
  for (std::size_t e = 0; e < x.size(); ++e) {
    Index i = 0, j = 0;
    cell_of(x[e], i, j);
    if (i < 0 || j < 0 || i >= nx || j >= ny) continue;
    cells[static_cast<std::size_t>(i + nx * j)].push_back(static_cast<std::int32_t>(e));
  }
  const auto mx = static_cast<Index>(std::floor((upper[0] - lower[0]) / resolution));
  const auto my = static_cast<Index>(std::floor((upper[1] - lower[1]) / resolution));
  require(mx > 0 && my > 0, "dem::porosity: the window is smaller than the resolution");
  Index covered = 0;
  for (Index b = 0; b < my; ++b) {
    for (Index a = 0; a < mx; ++a) {
      const Vec<2> p(lower[0] + (static_cast<double>(a) + 0.5) * resolution,
                     lower[1] + (static_cast<double>(b) + 0.5) * resolution);
      Index ci = 0, cj = 0;
      cell_of(p, ci, cj);
      bool inside = false;
      for (Index j = std::max<Index>(cj - 1, 0); j <= std::min(cj + 1, ny - 1) && !inside; ++j) {
        for (Index i = std::max<Index>(ci - 1, 0); i <= std::min(ci + 1, nx - 1) && !inside; ++i) {
          for (const std::int32_t e : cells[static_cast<std::size_t>(i + nx * j)]) {
            const auto u = static_cast<std::size_t>(e);
            if ((p - x[u]).squaredNorm() <= r[u] * r[u]) {
              inside = true;
              break;
            }
          }
        }
      }
      covered += inside ? 1 : 0;
    }
  }
  return 1.0 - static_cast<double>(covered) / static_cast<double>(mx * my);
}

}  // namespace cosmpm::dem
