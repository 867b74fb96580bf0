// Flow fronts and the mass ahead of them, on a block with a dilute tail.
#include <doctest/doctest.h>

#include <cmath>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/flow_front.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;
namespace field = particles::field;

TEST_CASE("flow fronts of a block: its edges, either way") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {40, 20});
  const auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.1, 0.0), Vec<2>(0.4, 0.2), 2));
  // The outermost particle centres sit half a particle (6.25 mm) inside; the half size adds it.
  CHECK(analysis::extreme_front(store).position == doctest::Approx(0.4));
  CHECK(analysis::extreme_front(store, 0, -1).position == doctest::Approx(0.1));
  CHECK(analysis::extreme_front(store, 1).position == doctest::Approx(0.2));
  const auto profile =
      analysis::height_profile(store, {.from = 0.0, .to = 1.0, .bin_width = 0.025});
  CHECK(analysis::deposit_front(profile, 0.01) == doctest::Approx(0.4));
  CHECK(analysis::mass_beyond(store, 0.4).count == 0);
  CHECK_THROWS_WITH_AS(analysis::extreme_front(store, 2), doctest::Contains("axis = 2"), Error);
  CHECK_THROWS_WITH_AS(analysis::extreme_front(store, 0, 0), doctest::Contains("direction = 0"),
                       Error);
}

TEST_CASE("a dilute tail ahead of the deposit: the deposit front ignores it, its mass counted") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {40, 20});
  auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(0.3, 0.1), 2));
  const double block_mass = 1000.0 * 0.3 * 0.1;
  // Tail: 10 particles stretched along the floor from 0.3 to 0.8 m, each of 1/100 of a block
  // particle's initial volume, grown 50 times (a one-particle-thick dilute tail).
  const double v0 = 0.0125 * 0.0125 / 100.0;
  const Index first = store.append(10);
  for (Index k = 0; k < 10; ++k) {
    const Index p = first + k;
    store.get<field::Position<2>>()[p] = Vec<2>(0.325 + 0.05 * static_cast<double>(k), 0.002);
    store.get<field::InitialPosition<2>>()[p] = Vec<2>(0.29, 0.09);
    store.get<field::InitialVolume>()[p] = v0;
    store.get<field::Volume>()[p] = 50.0 * v0;
    store.get<field::Mass>()[p] = 1000.0 * v0;
  }
  const auto profile =
      analysis::height_profile(store, {.from = 0.0, .to = 1.0, .bin_width = 0.025});
  // The tail's bins hold 1.56e-6 m^2 / 0.025 m = 6e-5 m of material, far below 1 mm.
  CHECK(analysis::deposit_front(profile, 1e-3) == doctest::Approx(0.3));
  // The extreme front is the last tail particle: 0.775 + sqrt(50 v0) / 2.
  CHECK(analysis::extreme_front(store).position ==
        doctest::Approx(0.775 + 0.5 * std::sqrt(50.0 * v0)));
  const auto tail = analysis::mass_beyond(store, 0.3);
  CHECK(tail.count == 10);
  CHECK(tail.mass == doctest::Approx(10.0 * 1000.0 * v0));
  CHECK(tail.mass / block_mass == doctest::Approx(1.0 / 1920.0));  // 10 / (100 x 192 particles)
  CHECK_THROWS_WITH_AS(analysis::deposit_front(profile, 1.0),
                       doctest::Contains("no bin holds min_thickness = 1"), Error);
}

}  // namespace
