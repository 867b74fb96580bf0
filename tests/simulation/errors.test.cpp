// Bad input and unstable runs stop with a cosmpm::Error that names the value and the range.
#include <doctest/doctest.h>

#include <limits>
#include <string>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using Sim = Simulation<2, shape::Linear, test::ElasticContinuum>;

Sim block(const SimulationParameters<2>& parameters = {}) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  Sim sim(grid, test::Elastic(1e6, 0.3), parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.2, 0.2), Vec<2>(0.8, 0.5), 2);
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
}  // namespace

TEST_CASE("a time step above the stable one is an error unless overridden") {
  SimulationParameters<2> parameters;
  parameters.time_step = 1.0;  // far above h / c_p = 0.1 / sqrt(1.35e6 / 1000) ~ 2.7e-3 s
  Sim sim = block(parameters);
  const std::string message = error_of([&] { (void)sim.time_step(); });
  CHECK(message.find("time_step = 1") != std::string::npos);
  CHECK(message.find("stable time step") != std::string::npos);
  parameters.allow_unstable_time_step = true;
  Sim overridden = block(parameters);
  CHECK(overridden.time_step() == 1.0);
  // The stable step is h / c_p with c_p = sqrt(M / rho).
  const double expected = 0.1 / std::sqrt(test::Elastic(1e6, 0.3).p_wave_modulus() / 1000.0);
  CHECK(sim.stable_time_step() == doctest::Approx(expected).epsilon(1e-12));
}

TEST_CASE("invalid parameters name themselves") {
  SimulationParameters<2> parameters;
  parameters.damping = 1.0;
  CHECK(error_of([&] { block(parameters); }).find("damping = 1") != std::string::npos);
  parameters = {};
  parameters.flip_fraction = -0.1;
  CHECK(error_of([&] { block(parameters); }).find("flip_fraction = -0.1") != std::string::npos);
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  Sim sim(grid, test::Elastic(1e6, 0.3));
  CHECK(error_of([&] {
          sim.add_particles({Vec<2>(1.5, 0.5)}, 0.01, 1000.0, Vec<2>(0.25, 0.25));
        }).find("outside the grid") != std::string::npos);
  CHECK(error_of([&] {
          sim.add_particles({Vec<2>(0.5, 0.5)}, 0.01, -1.0, Vec<2>(0.25, 0.25));
        }).find("density = -1") != std::string::npos);
  CHECK(error_of([] {
          grid::Grid<2>(Vec<2>(0.0, 0.0), Vec<2>(-1.0, 1.0), {10, 10});
        }).find("extent along axis 0 = -1") != std::string::npos);
}

TEST_CASE("a particle leaving the grid stops the run with its index and position") {
  Sim sim = block();
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  v[3] = Vec<2>(0.0, -500.0);  // crosses the bottom face within one step
  const double dt = sim.time_step();
  std::string message;
  for (int i = 0; i < 10 && message.empty(); ++i) message = error_of([&] { sim.step(dt); });
  CHECK(message.find("left the grid") != std::string::npos);
  // Particle 3 is the second lane of a pack of two: the message names it, not its partner 2,
  // with its real position below the grid.
  CHECK(message.find("particle 3 at") != std::string::npos);
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  CHECK(x[3][1] < 0.0);
  CHECK(message.find("with velocity") != std::string::npos);
}

TEST_CASE("a non-finite stress stops the run") {
  Sim sim = block();
  sim.particles().template get<particles::field::Stress<test::Elastic>>()[5][0] =
      std::numeric_limits<double>::quiet_NaN();
  const std::string message = error_of([&] { sim.step(sim.time_step()); });
  CHECK(message.find("unstable") != std::string::npos);
}
