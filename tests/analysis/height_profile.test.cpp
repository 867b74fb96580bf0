// The deposit height profile on seeded shapes whose surface and thickness are known.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/height_profile.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;

TEST_CASE("height profile of a rectangle: its top and its height, nothing beside it") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {40, 20});  // 25 mm cells
  for (int ppc : {1, 2, 3}) {
    const auto store =
        test::seeded(particles::seed_box(grid, Vec<2>(0.1, 0.0), Vec<2>(0.4, 0.2), ppc));
    const auto profile =
        analysis::height_profile(store, {.from = 0.0, .to = 1.0, .bin_width = 0.025, .base = 0.0});
    REQUIRE(profile.size() == 40);
    for (std::size_t i = 0; i < profile.size(); ++i) {
      const bool inside = profile.x[i] > 0.1 && profile.x[i] < 0.4;
      CAPTURE(i);
      // The top row sits half a particle below 0.2 m; its half size sqrt(V) / 2 closes the
      // gap exactly. Each bin holds one cell column: initial volumes summing to 0.025 x 0.2.
      CHECK(profile.surface[i] == doctest::Approx(inside ? 0.2 : 0.0).epsilon(1e-12));
      CHECK(profile.thickness[i] == doctest::Approx(inside ? 0.2 : 0.0).epsilon(1e-12));
      CHECK(profile.count[i] == (inside ? 8 * ppc * ppc : 0));
    }
    // Measured from a base 0.05 m up, the top is 0.05 m lower.
    const auto raised =
        analysis::height_profile(store, {.from = 0.0, .to = 1.0, .bin_width = 0.025, .base = 0.05});
    CHECK(raised.surface[8] == doctest::Approx(0.15));
  }
}

TEST_CASE("height profile of a triangle follows its slope within a particle size") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {100, 50});  // 10 mm cells
  // A heap rising from (0.1, 0) to (0.1, 0.3), down to (0.7, 0): slope 0.5.
  const auto seeding =
      particles::seed_polygon(grid, {Vec<2>(0.1, 0.0), Vec<2>(0.7, 0.0), Vec<2>(0.1, 0.3)}, 2);
  const auto store = test::seeded(seeding);
  const auto profile = analysis::height_profile(store, {.from = 0.1, .to = 0.7, .bin_width = 0.01});
  double total = 0.0;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const double exact = 0.5 * (0.7 - profile.x[i]);
    CAPTURE(profile.x[i]);
    // A bin's top particle lies within one particle spacing (5 mm) plus the slope across half
    // a bin (0.5 x 5 mm) of the line.
    CHECK(std::abs(profile.surface[i] - exact) <= 0.005 + 0.0025 + 1e-12);
    total += profile.thickness[i] * profile.bin_width;
  }
  // The thickness integrates to the seeded area.
  CHECK(total == doctest::Approx(seeding.volume * static_cast<double>(seeding.positions.size())));
}

TEST_CASE("height profile rejects bad ranges and bin widths") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  const auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), 1));
  CHECK_THROWS_WITH_AS(analysis::height_profile(store, {.from = 0.0, .to = 1.0, .bin_width = 0.0}),
                       doctest::Contains("bin_width = 0"), Error);
  CHECK_THROWS_WITH_AS(analysis::height_profile(store, {.from = 1.0, .to = 0.5, .bin_width = 0.1}),
                       doctest::Contains("to = 0.5 must be finite and exceed from = 1"), Error);
}

}  // namespace
