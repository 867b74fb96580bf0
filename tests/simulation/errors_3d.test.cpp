// Bad input and unstable runs at Dim = 3 stop with a cosmpm::Error naming the value, its valid
// range and where it came from, as in 2D (errors.test.cpp); the stable step uses the 3D
// p-wave modulus.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Elastic3 = material::LinearElastic<double, 3>;
using Sim = Simulation<3, shape::Linear, continuum::Classical<Elastic3>>;

// Cells of 0.1 x 0.05 x 0.08 m: the smallest, 0.05 m, sets the stable step.
const grid::Grid<3> box(Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.0, 0.5, 0.8), {10, 10, 10});

Sim block(const SimulationParameters<3>& parameters = {}) {
  Sim sim(box, Elastic3(1e6, 0.3), parameters);
  const auto seeding = particles::seed_box(box, Vec<3>(0.2, 0.1, 0.0), Vec<3>(0.8, 0.4, 0.4), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  return sim;
}

std::string error_of(auto&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}
bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
}  // namespace

TEST_CASE("3D stable time step: the smallest cell over the 3D p-wave speed") {
  SimulationParameters<3> parameters;
  parameters.time_step = 1.0;
  Sim sim = block(parameters);
  // M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) = 1.346e6 Pa: the same p-wave modulus as plane strain.
  const double modulus = 1e6 * 0.7 / (1.3 * 0.4);
  CHECK(Elastic3(1e6, 0.3).p_wave_modulus() == doctest::Approx(modulus).epsilon(1e-14));
  CHECK(sim.stable_time_step() ==
        doctest::Approx(0.05 / std::sqrt(modulus / 1000.0)).epsilon(1e-12));
  const std::string message = error_of([&] { (void)sim.time_step(); });
  CHECK(contains(message, "time_step = 1"));
  CHECK(contains(message, "above the stable time step"));
  CHECK(contains(message, "valid range (0, "));
}

TEST_CASE("3D bad set-up names the value and its range") {
  Sim sim(box, Elastic3(1e6, 0.3));
  const std::string outside =
      error_of([&] { sim.add_particles({Vec<3>(0.5, 0.25, 0.9)}, 1e-4, 1000.0, Vec<3>::Zero()); });
  // Eigen's formatting pads the components to a common width.
  CHECK(contains(outside, "particle 0 at ( 0.5 0.25  0.9) lies outside the grid box"));
  CHECK(contains(outside, "[0 0 0] + [  1 0.5 0.8]"));
  CHECK(contains(
      error_of([&] { sim.add_particles({Vec<3>(0.5, 0.25, 0.4)}, 1e-4, -1.0, Vec<3>::Zero()); }),
      "density = -1"));
  CHECK(contains(error_of([&] { sim.set_damping(1.0); }), "damping = 1"));
  CHECK(contains(error_of([] { (void)Elastic3(1e6, 0.5); }), "poisson_ratio = 0.5"));
  CHECK(contains(
      error_of([] { (void)material::DruckerPrager<double, 3>(1e6, 0.3, 95.0, 0.0, 0.0); }), "95"));
}

TEST_CASE("3D: a particle leaving the grid and an unstable run stop with their causes") {
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  Sim sim = block(parameters);
  sim.boundary_conditions().set(grid::BoundaryConditions<3>::face(2, false),
                                grid::BoundaryKind::fixed);
  // A lone particle above the block shot out through the top (z = 0.8) at 5 m/s.
  const Index shot = sim.add_particles({Vec<3>(0.55, 0.275, 0.7)}, 1e-4, 1000.0, Vec<3>::Zero());
  sim.particles().get<particles::field::Velocity<3>>()[shot] = Vec<3>(0.0, 0.0, 5.0);
  const std::string last = "particle " + std::to_string(shot) + " at (";
  const double dt = sim.time_step();
  const std::string left = error_of([&] {
    for (int i = 0; i < 1000; ++i) sim.step(dt);
  });
  CAPTURE(left);
  CHECK(contains(left, last));
  CHECK(contains(left, "left the grid box [0 0 0] + [  1 0.5 0.8]"));
  // A step 50 times the stable one tears the block apart.
  SimulationParameters<3> reckless;
  reckless.time_step = 50.0 * block().stable_time_step();
  reckless.allow_unstable_time_step = true;
  Sim unstable = block(reckless);
  unstable.particles().get<particles::field::Velocity<3>>()[5] = Vec<3>(1.0, -2.0, 3.0);
  const std::string blown = error_of([&] {
    for (int i = 0; i < 200; ++i) unstable.step(unstable.time_step());
  });
  CHECK((contains(blown, "went unstable") || contains(blown, "left the grid box")));
}
