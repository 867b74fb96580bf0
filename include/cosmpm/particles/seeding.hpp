#pragma once
// Particle seeding: n particles per cell and axis at the centres of equal sub-cells, inside
// a box, a polygon (2D) or a polygon extruded along an axis (3D). A sub-cell belongs to the
// region when its centre does.
#include <array>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace cosmpm::particles {

template <int Dim>
struct Seeding {
  std::vector<Vec<Dim>> positions;
  double volume = 0.0;  // of each particle
  Vec<Dim> half_width;  // of each particle, in cell units (for GIMP)
};

namespace detail {
// Visits the centre of every sub-cell of the grid (per_cell per axis), x fastest.
template <int Dim, class F>
void for_each_subcell_centre(const grid::Grid<Dim>& g, int per_cell, F&& f) {
  std::array<Index, Dim> count{};
  Index total = 1;
  for (int d = 0; d < Dim; ++d) {
    count[d] = g.cells(d) * per_cell;
    total *= count[d];
  }
  for (Index flat = 0; flat < total; ++flat) {
    Index rest = flat;
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) {
      const Index i = rest % count[d];
      rest /= count[d];
      x[d] = g.origin()[d] + (static_cast<double>(i) + 0.5) * g.cell_size()[d] / per_cell;
    }
    f(x);
  }
}

template <int Dim>
Seeding<Dim> empty_seeding(const grid::Grid<Dim>& g, int per_cell, const char* where) {
  require_in_range(where, "particles_per_cell_per_axis", per_cell, 1, 16, Bounds::closed);
  Seeding<Dim> seeding;
  seeding.volume = g.cell_volume();
  for (int d = 0; d < Dim; ++d) seeding.volume /= per_cell;
  seeding.half_width = Vec<Dim>::Constant(0.5 / per_cell);
  return seeding;
}
}  // namespace detail

// Particles filling the box [lower, upper].
template <int Dim>
Seeding<Dim> seed_box(const grid::Grid<Dim>& g, const Vec<Dim>& lower, const Vec<Dim>& upper,
                      int per_cell) {
  auto seeding = detail::empty_seeding(g, per_cell, "seed_box");
  for (int d = 0; d < Dim; ++d) {
    if (!(upper[d] > lower[d])) {
      throw Error("seed_box: upper corner component " + std::to_string(d) + " = " +
                  cosmpm::detail::format_number(upper[d]) +
                  " must exceed the lower one = " + cosmpm::detail::format_number(lower[d]));
    }
  }
  detail::for_each_subcell_centre(g, per_cell, [&](const Vec<Dim>& x) {
    for (int d = 0; d < Dim; ++d) {
      if (x[d] < lower[d] || x[d] > upper[d]) return;
    }
    seeding.positions.push_back(x);
  });
  require(!seeding.positions.empty(), "seed_box: the box holds no sub-cell centre of the grid");
  return seeding;
}

// Whether x lies inside the simple polygon (even-odd rule).
inline bool inside_polygon(const std::vector<Vec<2>>& polygon, const Vec<2>& x) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec<2>& a = polygon[i];
    const Vec<2>& b = polygon[j];
    if ((a[1] > x[1]) != (b[1] > x[1]) &&
        x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0]) {
      inside = !inside;
    }
  }
  return inside;
}

// Particles filling a simple polygon (vertices in order, either orientation).
inline Seeding<2> seed_polygon(const grid::Grid<2>& g, const std::vector<Vec<2>>& polygon,
                               int per_cell) {
  require_in_range("seed_polygon", "vertex count", static_cast<double>(polygon.size()), 3.0, 1e9,
                   Bounds::closed);
  auto seeding = detail::empty_seeding(g, per_cell, "seed_polygon");
  detail::for_each_subcell_centre(g, per_cell, [&](const Vec<2>& x) {
    if (inside_polygon(polygon, x)) seeding.positions.push_back(x);
  });
  require(!seeding.positions.empty(), "seed_polygon: the polygon holds no sub-cell centre");
  return seeding;
}

// Particles filling a simple polygon extruded along `axis` of a 3D grid over [lower, upper]
// on that axis. The polygon's vertices are given in the other two axes in increasing order:
// (y, z) for axis 0, (x, z) for axis 1 (a 2D section in the vertical xz plane extruded across
// the width), (x, y) for axis 2.
inline Seeding<3> seed_extruded_polygon(const grid::Grid<3>& g, const std::vector<Vec<2>>& polygon,
                                        int axis, double lower, double upper, int per_cell) {
  require_in_range("seed_extruded_polygon", "vertex count", static_cast<double>(polygon.size()),
                   3.0, 1e9, Bounds::closed);
  require_in_range("seed_extruded_polygon", "axis", axis, 0, 2, Bounds::closed);
  if (!(upper > lower)) {
    throw Error("seed_extruded_polygon: upper = " + cosmpm::detail::format_number(upper) +
                " must exceed lower = " + cosmpm::detail::format_number(lower) +
                " (the extrusion's extent along axis " + std::to_string(axis) + ")");
  }
  const int first = axis == 0 ? 1 : 0;
  const int second = axis == 2 ? 1 : 2;
  auto seeding = detail::empty_seeding(g, per_cell, "seed_extruded_polygon");
  detail::for_each_subcell_centre(g, per_cell, [&](const Vec<3>& x) {
    if (x[axis] < lower || x[axis] > upper) return;
    if (inside_polygon(polygon, Vec<2>(x[first], x[second]))) seeding.positions.push_back(x);
  });
  require(!seeding.positions.empty(),
          "seed_extruded_polygon: the extruded polygon holds no sub-cell centre");
  return seeding;
}

// Particles filling a disk (the colliding-disks benchmark of Sulsky et al. 1995).
inline Seeding<2> seed_disk(const grid::Grid<2>& g, const Vec<2>& centre, double radius,
                            int per_cell) {
  require_positive("seed_disk", "radius", radius);
  auto seeding = detail::empty_seeding(g, per_cell, "seed_disk");
  detail::for_each_subcell_centre(g, per_cell, [&](const Vec<2>& x) {
    if ((x - centre).squaredNorm() <= radius * radius) seeding.positions.push_back(x);
  });
  require(!seeding.positions.empty(), "seed_disk: the disk holds no sub-cell centre");
  return seeding;
}

}  // namespace cosmpm::particles
