// Kinetic energy from the grid and from the particles, and potential energy, on known fields.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/energy.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Elastic = material::LinearElastic<>;

TEST_CASE("kinetic energy of given masses and velocities: sum of m v^2 / 2") {
  const std::vector<double> mass{2.0, 0.0, 3.0};
  const std::vector<Vec<2>> velocity{Vec<2>(1.0, 0.0), Vec<2>(5.0, 5.0), Vec<2>(3.0, 4.0)};
  // 2 * 1 / 2 + 0 + 3 * 25 / 2 = 38.5 (hand calculation); a massless node adds nothing.
  CHECK(analysis::grid_kinetic_energy<2>(mass, velocity) == doctest::Approx(38.5));
  CHECK(analysis::particle_kinetic_energy<2>(mass, velocity) == doctest::Approx(38.5));
  const std::vector<double> short_mass{1.0};
  CHECK_THROWS_AS(analysis::grid_kinetic_energy<2>(short_mass, velocity), Error);
}

TEST_CASE("potential energy of a seeded block: M g times the height of its centroid") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  const auto store =
      test::seeded(particles::seed_box(grid, Vec<2>(0.2, 0.0), Vec<2>(0.6, 0.3), 2), 1500.0);
  // M = 1500 kg/m^3 x 0.4 m x 0.3 m = 180 kg/m, centroid at y = 0.15 m.
  CHECK(analysis::potential_energy(store, Vec<2>(0.0, -9.81)) ==
        doctest::Approx(180.0 * 9.81 * 0.15).epsilon(1e-12));
}

template <class Kernel>
void check_grid_and_particle_energy() {
  using Sim = Simulation<2, Kernel, continuum::Classical<Elastic>>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  Sim sim(grid, Elastic(1e5, 0.25));
  // Away from the edges, so every weight is positive (the boundary-modified splines fold a
  // ghost node with a negative weight onto the inner node next to an edge).
  const auto block = particles::seed_box(grid, Vec<2>(0.3, 0.3), Vec<2>(0.7, 0.7), 2);
  sim.add_particles(block.positions, block.volume, 1000.0, block.half_width);
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  const double dt = 1e-6;  // short: the stress-free block gets no force

  // A uniform velocity is carried to the nodes exactly (partition of unity): both energies
  // equal M |v|^2 / 2 = 160 kg/m x 13 / 2 (M = 1000 x 0.4 x 0.4).
  for (auto& velocity : v) velocity = Vec<2>(2.0, -3.0);
  sim.map_to_grid(true);
  sim.update_grid(dt);
  CHECK(analysis::particle_kinetic_energy(sim) == doctest::Approx(0.5 * 160.0 * 13.0));
  CHECK(analysis::grid_kinetic_energy(sim) == doctest::Approx(0.5 * 160.0 * 13.0).epsilon(1e-10));

  // Any other field loses energy on the way to the nodes: at a node, |sum N m v|^2 / sum N m
  // <= sum N m |v|^2 (Cauchy-Schwarz, weights >= 0), so the grid's energy is at most the
  // particles'. A spinning block loses what varies inside a cell.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  for (std::size_t p = 0; p < v.size(); ++p) {
    v[p] = Vec<2>(-(x[p][1] - 0.5), x[p][0] - 0.5) * 4.0 + 0.1 * Vec<2>(noise(rng), noise(rng));
  }
  sim.map_to_grid(true);
  sim.update_grid(dt);
  const double particles = analysis::particle_kinetic_energy(sim);
  const double nodes = analysis::grid_kinetic_energy(sim);
  CHECK(nodes < particles);
  CHECK(nodes > 0.5 * particles);  // a rotation resolved by 4 cells keeps most of its energy
}

TEST_CASE("grid kinetic energy equals the particles' for a translation and is less otherwise") {
  check_grid_and_particle_energy<shape::Linear>();
  check_grid_and_particle_energy<shape::GIMP>();
  check_grid_and_particle_energy<shape::QuadraticBSpline>();
  check_grid_and_particle_energy<shape::CubicBSpline>();
}

// The mechanism docs/theory/analysis.md describes: in a cell whose nodes are all fixed, the
// nodal velocity is zero at the start and the end of the step, so pure FLIP adds nothing to a
// particle's velocity and the particle does not move; its kinetic energy stays, the grid's is
// zero. A FLIP fraction f keeps f^n of the velocity after n steps.
TEST_CASE("particle kinetic energy misleads next to fixed nodes; the grid's does not") {
  using Sim = Simulation<2, shape::Linear, continuum::Classical<Elastic>>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.1), {1, 1});
  for (const double flip : {1.0, 0.99}) {
    SimulationParameters<2> parameters;
    parameters.flip_fraction = flip;
    Sim sim(grid, Elastic(1e5, 0.25), parameters);
    const auto block = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.1), 2);
    sim.add_particles(block.positions, block.volume, 1000.0, block.half_width);
    for (int face = 0; face < 4; ++face) {
      sim.boundary_conditions().set(face, grid::BoundaryKind::fixed);
    }
    for (auto& velocity : sim.particles().template get<particles::field::Velocity<2>>()) {
      velocity = Vec<2>(0.5, 0.0);
    }
    const auto start = sim.particles().template get<particles::field::Position<2>>();
    const double energy = analysis::particle_kinetic_energy(sim);  // 10 kg/m x 0.25 / 2
    CHECK(energy == doctest::Approx(1.25));
    const int steps = 100;
    for (int n = 0; n < steps; ++n) sim.step(1e-5);
    CHECK((sim.particles().template get<particles::field::Position<2>>() == start));
    CHECK(analysis::grid_kinetic_energy(sim) == 0.0);
    // Pure FLIP: nothing moves and the energy is all still there; 0.99: 0.99^200 of it.
    CHECK(analysis::particle_kinetic_energy(sim) ==
          doctest::Approx(energy * std::pow(flip, 2 * steps)).epsilon(1e-12));
  }
}

}  // namespace
