// Particles that leave the grid box: the run stops (the default), or they leave the
// simulation, frozen or removed, counted with their mass; an unstable particle always stops.
#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using Sim =
    Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::MUSL>;

// A block resting on a fixed floor and, apart from it, a lone particle (the last one) shot up
// through the open top face.
Sim shot_block(StrayParticles policy) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {20, 10});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.stray_particles = policy;
  Sim sim(grid, test::Elastic(1e6, 0.3), parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.2, 0.0), Vec<2>(0.8, 0.3), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  const Index shot =
      sim.add_particles({Vec<2>(0.06, 0.44)}, seeding.volume, 1000.0, seeding.half_width);
  sim.particles().get<particles::field::Velocity<2>>()[shot] = Vec<2>(0.0, 5.0);
  return sim;
}

double total_mass(const Sim& sim) {
  double sum = 0.0;
  for (const double m : sim.particles().get<particles::field::Mass>()) sum += m;
  return sum;
}
}  // namespace

TEST_CASE("strays: by default a particle leaving the grid stops the run, naming it") {
  Sim sim = shot_block(StrayParticles::stop);
  const double dt = sim.time_step();
  CHECK_THROWS_WITH_AS(
      [&] {
        for (int i = 0; i < 20; ++i) sim.step(dt);
      }(),
      doctest::Contains("particle 288 at"), Error);  // 24 x 12 in the block, then the shot
}

TEST_CASE("strays: frozen particles leave the simulation, kept as they were and counted") {
  Sim sim = shot_block(StrayParticles::freeze);
  const Index count = sim.particles().size();
  const double mass = total_mass(sim);
  const double particle_mass = sim.particles().get<particles::field::Mass>()[count - 1];
  const double dt = sim.time_step();
  Index seen_in_a_step = 0;
  for (int i = 0; i < 200; ++i) {
    sim.step(dt);
    seen_in_a_step += sim.stray_particles().count_last_step;
  }
  CHECK(sim.stray_particles().count == 1);
  CHECK(seen_in_a_step == 1);
  CHECK(sim.stray_particles().mass == particle_mass);
  CHECK(sim.particles().size() == count - 1);
  REQUIRE(sim.frozen_particles().size() == 1);
  // Kept as it left: above the grid's top (y = 0.5), moving up, its initial position intact.
  const auto& x = sim.frozen_particles().get<particles::field::Position<2>>();
  const auto& x0 = sim.frozen_particles().get<particles::field::InitialPosition<2>>();
  CHECK(x[0][1] >= 0.5);
  CHECK(x0[0] == Vec<2>(0.06, 0.44));
  // No mass is lost unaccounted.
  CHECK(total_mass(sim) + sim.stray_particles().mass == doctest::Approx(mass).epsilon(1e-14));
}

TEST_CASE("strays: removed particles are dropped and counted") {
  Sim sim = shot_block(StrayParticles::remove);
  const Index count = sim.particles().size();
  const double dt = sim.time_step();
  for (int i = 0; i < 200; ++i) sim.step(dt);
  CHECK(sim.stray_particles().count == 1);
  CHECK(sim.particles().size() == count - 1);
  CHECK(sim.frozen_particles().size() == 0);
}

TEST_CASE("strays: a particle with a non-finite velocity stops the run whatever the policy") {
  Sim sim = shot_block(StrayParticles::freeze);
  sim.particles().get<particles::field::Velocity<2>>()[288] =
      Vec<2>(0.0, std::numeric_limits<double>::infinity());
  CHECK_THROWS_WITH_AS(sim.step(sim.time_step()), doctest::Contains("went unstable"), Error);
}
