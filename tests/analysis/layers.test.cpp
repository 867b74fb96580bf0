// Layer indices for coloured flow patterns, from the initial positions.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/layers.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;
namespace field = particles::field;

TEST_CASE("layers of a seeded column: equal layers counted from the base") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4), {40, 40});  // 10 mm cells
  auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.2), 2));
  const auto layer = analysis::layer_index(store, {.thickness = 0.05});
  // 0.2 m in 50 mm layers: 4 layers of 10 x 10 particles each (5 mm spacing).
  for (int k = 0; k < 4; ++k) CHECK(std::count(layer.begin(), layer.end(), k) == 200);
  // Flow does not change a colour: the layer follows the initial position.
  for (auto& x : store.get<field::Position<2>>()) x = Vec<2>(0.3, 0.01);
  CHECK(analysis::layer_index(store, {.thickness = 0.05}) == layer);
}

TEST_CASE("layer boundaries, a raised base, and particles below it") {
  const std::vector<Vec<2>> x0{Vec<2>(0, 0.0), Vec<2>(0, 0.05), Vec<2>(0, 0.0999), Vec<2>(0, 0.1)};
  // A particle on a boundary belongs to the layer above it.
  CHECK(analysis::layer_index<2>(x0, {.thickness = 0.05}) == std::vector<std::int32_t>{0, 1, 1, 2});
  CHECK(analysis::layer_index<2>(x0, {.thickness = 0.05, .base = -0.05}) ==
        std::vector<std::int32_t>{1, 2, 2, 3});
  CHECK_THROWS_WITH_AS(analysis::layer_index<2>(x0, {.thickness = 0.05, .base = 0.01}),
                       doctest::Contains("particle 0 starts at coordinate 0"), Error);
  CHECK_THROWS_WITH_AS(analysis::layer_index<2>(x0, {.thickness = 0.0}),
                       doctest::Contains("thickness = 0"), Error);
  CHECK_THROWS_WITH_AS(analysis::layer_index<2>(x0, {.thickness = 0.05, .axis = 2}),
                       doctest::Contains("axis = 2"), Error);
}

}  // namespace
