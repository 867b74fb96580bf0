// Seeding at Dim = 3: boxes and extruded polygons, counted and placed against the sub-cell
// centres they must hold, with bad input named.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/particles/seeding.hpp"

namespace {
using namespace cosmpm;
// 10 x 6 x 8 cells of 0.1 x 0.05 x 0.1 m, origin off zero.
const grid::Grid<3> grid3(Vec<3>(-0.5, 0.1, 0.0), Vec<3>(1.0, 0.3, 0.8), {10, 6, 8});
}  // namespace

TEST_CASE("seed_box<3>: n^3 particles per cell at sub-cell centres, volume and half-width") {
  // The box covers cells 2..5 along x (4 cells), 1..3 along y (2 cells of 0.05 from 0.15), and
  // 0..2 along z (3 cells): 4 x 2 x 3 = 24 cells, 8 particles each with n = 2.
  const auto s = particles::seed_box(grid3, Vec<3>(-0.3, 0.15, 0.0), Vec<3>(0.1, 0.25, 0.3), 2);
  CHECK(s.positions.size() == 24u * 8u);
  CHECK(s.volume == doctest::Approx(0.1 * 0.05 * 0.1 / 8.0).epsilon(1e-14));
  CHECK(s.half_width == Vec<3>::Constant(0.25));
  for (const auto& x : s.positions) {
    // Each coordinate is a sub-cell centre: (k + 1/2) h / 2 from the origin.
    const Vec<3> units = (x - grid3.origin()).cwiseQuotient(grid3.cell_size()) * 2.0;
    for (int d = 0; d < 3; ++d) {
      CHECK(std::abs(units[d] - std::floor(units[d]) - 0.5) < 1e-9);
    }
    CHECK(grid3.contains(x));
  }
  // The total volume is the box's.
  CHECK(s.volume * static_cast<double>(s.positions.size()) ==
        doctest::Approx(0.4 * 0.1 * 0.3).epsilon(1e-12));
}

TEST_CASE("seed_extruded_polygon: a 2D section extruded across the width") {
  // A right triangle in the xz plane, legs 0.6 (x, from -0.4) and 0.6 (z, from 0), extruded
  // along y over [0.1, 0.3] (4 cells of 0.05): every y layer holds the 2D triangle's seeding.
  const std::vector<Vec<2>> triangle{Vec<2>(-0.4, 0.0), Vec<2>(0.2, 0.0), Vec<2>(-0.4, 0.6)};
  const auto s = particles::seed_extruded_polygon(grid3, triangle, 1, 0.1, 0.3, 2);
  // The section's own 2D seeding on the xz grid.
  const grid::Grid<2> section(Vec<2>(-0.5, 0.0), Vec<2>(1.0, 0.8), {10, 8});
  const auto s2 = particles::seed_polygon(section, triangle, 2);
  const std::size_t layers = 4 * 2;  // 4 cells of 0.05 along y, 2 particles per cell
  CHECK(s.positions.size() == s2.positions.size() * layers);
  CHECK(s.volume == doctest::Approx(s2.volume * 0.05 / 2.0).epsilon(1e-14));
  for (const auto& x : s.positions) {
    CHECK(particles::inside_polygon(triangle, Vec<2>(x[0], x[2])));
    CHECK(x[1] >= 0.1);
    CHECK(x[1] <= 0.3);
  }
  // Volume: the triangle's area 0.18 times the width 0.2, to the seeding's staircase error
  // (sub-cell centres inside the hypotenuse): within 5 % at 20 sub-cells along each leg.
  const double seeded = s.volume * static_cast<double>(s.positions.size());
  CHECK(seeded == doctest::Approx(0.18 * 0.2).epsilon(0.05));
  // Along z (axis 2) the polygon is in (x, y).
  const auto flat = particles::seed_extruded_polygon(
      grid3, {Vec<2>(-0.5, 0.1), Vec<2>(0.5, 0.1), Vec<2>(0.5, 0.4), Vec<2>(-0.5, 0.4)}, 2, 0.0,
      0.1, 1);
  CHECK(flat.positions.size() == 10u * 6u);
}

TEST_CASE("seed_extruded_polygon: bad input throws naming the value and its range") {
  const std::vector<Vec<2>> triangle{Vec<2>(-0.4, 0.0), Vec<2>(0.2, 0.0), Vec<2>(-0.4, 0.6)};
  CHECK_THROWS_WITH_AS(particles::seed_extruded_polygon(grid3, triangle, 3, 0.1, 0.3, 2),
                       doctest::Contains("axis = 3"), Error);
  CHECK_THROWS_WITH_AS(particles::seed_extruded_polygon(grid3, triangle, 3, 0.1, 0.3, 2),
                       doctest::Contains("[0, 2]"), Error);
  CHECK_THROWS_WITH_AS(particles::seed_extruded_polygon(grid3, triangle, 1, 0.3, 0.1, 2),
                       doctest::Contains("upper = 0.1 must exceed lower = 0.3"), Error);
  CHECK_THROWS_WITH_AS(
      particles::seed_extruded_polygon(grid3, {Vec<2>(0, 0), Vec<2>(1, 0)}, 1, 0.1, 0.3, 2),
      doctest::Contains("vertex count = 2"), Error);
  CHECK_THROWS_WITH_AS(particles::seed_extruded_polygon(grid3, triangle, 1, 0.1, 0.3, 0),
                       doctest::Contains("particles_per_cell_per_axis = 0"), Error);
  // Outside the grid: no sub-cell centre.
  CHECK_THROWS_WITH_AS(particles::seed_extruded_polygon(grid3, triangle, 1, 2.0, 3.0, 2),
                       doctest::Contains("holds no sub-cell centre"), Error);
}
