// Bad input is a cosmpm::Error naming the value and its valid range; an unstable run stops
// with a message naming the element, the step and the cause.
#include <doctest/doctest.h>

#include <string>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

using namespace cosmpm;

TEST_CASE("errors: non-positive stiffness, radius or density, negative friction") {
  CHECK_THROWS_WITH_AS(dem::LinearSpring({.normal_stiffness = -1.0}),
                       doctest::Contains("normal stiffness k_n [N/m] = -1 must be positive"),
                       Error);
  CHECK_THROWS_WITH_AS(dem::LinearSpring({.shear_stiffness = 0.0}),
                       doctest::Contains("valid range (0, inf)"), Error);
  CHECK_THROWS_WITH_AS(dem::LinearSpring({.friction = -0.1}),
                       doctest::Contains("friction coefficient mu = -0.1"), Error);
  CHECK_THROWS_WITH_AS(dem::LinearSpring({}, {.normal_ratio = 1.5}), doctest::Contains("[0, 1)"),
                       Error);
  dem::Assembly a;
  CHECK_THROWS_WITH_AS(a.add_disk(Vec<2>(0, 0), 0.0, 855.0), doctest::Contains("radius = 0"),
                       Error);
  CHECK_THROWS_WITH_AS(a.add_disk(Vec<2>(0, 0), 0.005, -855.0),
                       doctest::Contains("density = -855 must be positive"), Error);
  CHECK_THROWS_WITH_AS(dem::ClumpShape::two_disks(0.004, 0.006),
                       doctest::Contains("length = 0.004 is outside the valid range [0.006"),
                       Error);
  CHECK_THROWS_WITH_AS(dem::LocalDamping(1.0), doctest::Contains("alpha = 1"), Error);
  dem::Simulation<> sim(dem::Assembly{});
  CHECK_THROWS_WITH_AS(sim.add_plane_wall("blade", Vec<2>(0, 0), Vec<2>(0, 1), {.friction = -1}),
                       doctest::Contains("wall 'blade': friction coefficient mu = -1"), Error);
}

TEST_CASE("errors: walls may touch but not overlap") {
  dem::Simulation<> sim(dem::Assembly{});
  sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {});
  // A blade standing on the floor touches it: fine.
  sim.add_polygon_wall("blade", contact::RigidBody<2>::box(Vec<2>(0.05, 0), Vec<2>(0.06, 0.35)),
                       {});
  CHECK_THROWS_WITH_AS(
      sim.add_polygon_wall("sunk",
                           contact::RigidBody<2>::box(Vec<2>(0.2, -0.01), Vec<2>(0.21, 0.35)), {}),
      doctest::Contains("'sunk' overlaps 'floor'"), Error);
  CHECK_THROWS_WITH_AS(
      sim.add_polygon_wall("crossing",
                           contact::RigidBody<2>::box(Vec<2>(0.055, 0.1), Vec<2>(0.3, 0.11)), {}),
      doctest::Contains("overlaps 'blade'"), Error);
  CHECK_THROWS_WITH_AS(sim.add_plane_wall("ceiling", Vec<2>(0, -0.1), Vec<2>(0, -1), {}),
                       doctest::Contains("leave -0.1 m between them"), Error);
  CHECK(sim.walls().size() == 2);  // the rejected walls were not kept
}

TEST_CASE("errors: more particles than the rig holds") {
  dem::Assembly a;
  dem::Grains grains;  // 9-11 mm disks: 11.2 mm lattice sites
  // 101 columns of 11.22 mm over 1.14 m, 98 rows between 0.4 and 1.5 m: 9898 sites.
  CHECK_THROWS_WITH_AS(dem::rain(a, grains, 10000, {0.0, 1.14, 0.4, 1.5}),
                       doctest::Contains("10000 particles do not fit above the rig"), Error);
  CHECK_THROWS_WITH_AS(dem::rain(a, grains, 10000, {0.0, 1.14, 0.4, 1.5}),
                       doctest::Contains("valid range [1, 9898]"), Error);
  CHECK(a.body_count() == 0);
}

TEST_CASE("errors: a time step above the critical one is refused") {
  dem::Assembly a;
  a.add_disk(Vec<2>(0, 0), 0.005, 855.0);
  dem::Simulation<> sim(std::move(a));
  const double critical = sim.critical_time_step();
  CHECK_THROWS_WITH_AS(sim.step(1.5 * critical),
                       doctest::Contains("exceeds the critical time step"), Error);
  CHECK_THROWS_WITH_AS(sim.step(-1.0), doctest::Contains("dt [s] = -1"), Error);
}

TEST_CASE("errors: a particle moving more than its radius in a step stops the run") {
  dem::Assembly a;
  a.add_disk(Vec<2>(0, 0.01), 0.005, 855.0);
  a.add_disk(Vec<2>(0.5, 0.01), 0.005, 855.0, Vec<2>(-1e4, 0.0));  // 10 km/s
  dem::Simulation<> sim(std::move(a));
  const double dt = 0.5 * sim.critical_time_step();
  CHECK_THROWS_WITH_AS(sim.step(dt), doctest::Contains("unstable at step 1"), Error);
  CHECK_THROWS_WITH_AS(sim.step(dt),
                       doctest::Contains("element 1 (body 1, radius 0.005 m) moved "
                                         "more than its radius in one step"),
                       Error);
}
