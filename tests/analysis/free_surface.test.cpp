// The free surface as curves on seeded shapes.
#include <doctest/doctest.h>

#include <cmath>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/free_surface.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;

TEST_CASE("free surface of a rectangle: one flat curve at its top") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {100, 50});
  const auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.2, 0.0), Vec<2>(0.5, 0.1), 2));
  const auto curves = analysis::free_surface(store, 0.005);  // one particle spacing
  REQUIRE(curves.size() == 1);
  REQUIRE(curves[0].size() == 60);  // 0.3 m / 5 mm
  for (std::size_t k = 0; k < curves[0].size(); ++k) {
    CHECK(curves[0][k][1] == doctest::Approx(0.1).epsilon(1e-12));
    if (k > 0) CHECK(curves[0][k][0] > curves[0][k - 1][0]);  // left to right
  }
  CHECK(curves[0].front()[0] == doctest::Approx(0.2025));  // particle centres
  CHECK(curves[0].back()[0] == doctest::Approx(0.4975));
}

TEST_CASE("free surface of two heaps: two curves, each on its heap's slope") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {100, 50});
  // Two triangles: slope 1 rising to x = 0.3 (apex 0.2 m), slope -0.5 falling from x = 0.6.
  auto store = test::seeded(
      particles::seed_polygon(grid, {Vec<2>(0.1, 0.0), Vec<2>(0.3, 0.0), Vec<2>(0.3, 0.2)}, 2));
  test::append(store, particles::seed_polygon(
                          grid, {Vec<2>(0.6, 0.0), Vec<2>(0.8, 0.0), Vec<2>(0.6, 0.1)}, 2));
  const auto curves = analysis::free_surface(store, 0.005);
  REQUIRE(curves.size() == 2);
  for (const auto& point : curves[0]) {
    CAPTURE(point[0]);
    CHECK(point[0] < 0.3);
    // Within one particle spacing (5 mm) plus half a spacing times the slope of the line.
    CHECK(std::abs(point[1] - (point[0] - 0.1)) <= 0.005 + 0.0025 + 1e-12);
  }
  for (const auto& point : curves[1]) {
    CAPTURE(point[0]);
    CHECK(point[0] > 0.6);
    CHECK(std::abs(point[1] - 0.5 * (0.8 - point[0])) <= 0.005 + 0.00125 + 1e-12);
  }
  CHECK(analysis::free_surface(test::AnalysisStore{}, 0.01).empty());
  CHECK_THROWS_WITH_AS(analysis::free_surface(store, -1.0), doctest::Contains("bin_width = -1"),
                       Error);
}

}  // namespace
