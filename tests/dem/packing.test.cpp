// Packing tools: the porosity measurement on packings with known porosity, the rain lattice,
// the trim, and a small rained layer settling to rest.
#include <doctest/doctest.h>

#include <cmath>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

using namespace cosmpm;

TEST_CASE("packing: porosity of a hexagonal packing of equal disks is 1 - pi / (2 sqrt 3)") {
  dem::Assembly a;
  const double r = 0.005;
  for (int j = 0; j < 40; ++j) {
    for (int i = 0; i < 40; ++i) {
      a.add_disk(Vec<2>(2 * r * i + (j % 2) * r, std::sqrt(3.0) * r * j), r, 855.0);
    }
  }
  // A window many cells wide inside the packing; sampling at r / 20.
  const double n = dem::porosity(a, Vec<2>(0.05, 0.05), Vec<2>(0.3, 0.25), r / 20);
  CHECK(n == doctest::Approx(1.0 - pi / (2.0 * std::sqrt(3.0))).epsilon(0.02));  // 0.0931
  // Clumps count their overlapping disks once: one corn grain alone in a window.
  dem::Assembly one;
  const dem::ClumpShape grain = dem::ClumpShape::two_disks(0.010, 0.006);
  one.add_clump(grain, 1.0, Vec<2>(0.0, 0.0), 0.7, 855.0);
  const double solid = 1.0 - dem::porosity(one, Vec<2>(-0.01, -0.01), Vec<2>(0.01, 0.01), 2e-5);
  CHECK(solid * 4e-4 == doctest::Approx(grain.area()).epsilon(2e-3));
}

TEST_CASE("packing: the rain lattice places every grain without overlap, row by row") {
  dem::Assembly a;
  dem::Grains grains;
  grains.shape = dem::ClumpShape::two_disks(1.0, 0.6);
  grains.min_size = 0.008;
  grains.max_size = 0.012;
  dem::rain(a, grains, 500, {0.06, 1.2, 0.4, 2.5}, 3);
  REQUIRE(a.body_count() == 500);
  const auto& x = a.elements().get<particles::field::Position<2>>();
  const auto& r = a.elements().get<dem::field::Radius>();
  const auto& body = a.elements().get<particles::field::Body>();
  for (std::size_t i = 0; i < x.size(); ++i) {
    CHECK(x[i][0] - r[i] >= 0.06);
    CHECK(x[i][1] - r[i] >= 0.4);
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      if (body[i] != body[j]) CHECK((x[i] - x[j]).norm() >= r[i] + r[j]);
    }
  }
  CHECK(a.position(0)[1] < a.position(499)[1]);
  // The same seed gives the same grains.
  dem::Assembly b;
  dem::rain(b, grains, 500, {0.06, 1.2, 0.4, 2.5}, 3);
  CHECK(b.position(123) == a.position(123));
  const Index before = b.body_count();
  CHECK(dem::trim_above(b, 0.5) + b.body_count() == before);
  for (Index k = 0; k < b.body_count(); ++k) CHECK(b.position(k)[1] <= 0.5);
}

TEST_CASE("packing: a rained layer comes to rest on the floor and carries its weight") {
  dem::Assembly a;
  dem::Grains grains;
  grains.shape = dem::ClumpShape::two_disks(1.0, 0.6);
  dem::rain(a, grains, 200, {0.0, 0.12, 0.02, 1.0}, 9);
  double weight = 0.0;
  for (Index b = 0; b < a.body_count(); ++b) weight += 9.81 * a.mass(b);
  dem::Simulation<> sim(std::move(a));
  const Index floor = sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {});
  sim.add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), {.friction = 0});
  sim.add_plane_wall("right", Vec<2>(0.12, 0), Vec<2>(-1, 0), {.friction = 0});
  const auto report = dem::settle(sim, 0.8 * sim.critical_time_step(), 3.0, 1e-4, 0.2);
  CHECK(report.settled);
  // Smooth side walls carry nothing vertically: the floor holds the whole weight.
  CHECK(sim.wall_force(floor)[1] == doctest::Approx(-weight).epsilon(1e-3));
  CHECK(sim.kinetic_energy() < 1e-6 * weight * 0.1);
}
