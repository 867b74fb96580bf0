// Mass of all, of flagged and of removed particles.
#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/mass.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;

TEST_CASE("mass of all, flagged and removed particles") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  // 0.2 m x 0.1 m at 2000 kg/m^3: 40 kg/m in 8 particles of 5 kg/m.
  auto store =
      test::seeded(particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.1), 2), 2000.0);
  REQUIRE(store.size() == 8);
  const auto all = analysis::mass_of(store);
  CHECK(all.count == 8);
  CHECK(all.mass == doctest::Approx(40.0));
  const std::vector<std::uint8_t> frozen{1, 0, 0, 1, 0, 0, 0, 1};
  CHECK(analysis::mass_of(store, frozen).count == 3);
  CHECK(analysis::mass_of(store, frozen).mass == doctest::Approx(15.0));
  const std::vector<bool> none(8, false);
  CHECK(analysis::mass_of(store, none).mass == 0.0);
  CHECK_THROWS_WITH_AS(analysis::mass_of(store, std::vector<bool>(7, true)),
                       doctest::Contains("the particle store has 8 entries but flags has 7"),
                       Error);
  // A removal policy takes particles out: the difference is what left.
  store.resize(5);
  const auto removed = analysis::removed_since(all, store);
  CHECK(removed.count == 3);
  CHECK(removed.mass == doctest::Approx(15.0));
}

}  // namespace
