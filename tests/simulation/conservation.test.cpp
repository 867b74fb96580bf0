// Particle-to-grid and back conserve mass and momentum to round-off, for every kernel.
#include <doctest/doctest.h>

#include <random>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;

template <class Kernel>
void check_transfer_conservation() {
  using Sim = Simulation<2, Kernel, test::ElasticContinuum, contact::SingleField, integrator::USL>;
  const grid::Grid<2> grid(Vec<2>(-0.3, 0.1), Vec<2>(1.2, 0.8), {12, 8});
  Sim sim(grid, test::Elastic(1e5, 0.25));
  // Particles in every cell, including those next to the grid edges.
  const auto seeding = particles::seed_box(grid, Vec<2>(-0.3, 0.1), Vec<2>(0.9, 0.9), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  auto& x = sim.particles().template get<particles::field::Position<2>>();
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  auto& stress = sim.particles().template get<particles::field::Stress<test::Elastic>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    x[p] += Vec<2>(jitter(rng), jitter(rng)) * 0.04;  // up to 0.08 of a 0.1 m cell
    v[p] = Vec<2>(jitter(rng), jitter(rng));
    stress[p] = SymTensor2D<>(jitter(rng), jitter(rng), jitter(rng), jitter(rng)) * 1e3;
  }
  sim.map_to_grid(true);
  double particle_mass = 0.0;
  for (double m : sim.particles().template get<particles::field::Mass>()) particle_mass += m;
  double node_mass = 0.0;
  Vec<2> node_momentum = Vec<2>::Zero();
  Vec<2> node_force = Vec<2>::Zero();
  for (Index n = 0; n < grid.node_count(); ++n) {
    node_mass += sim.nodes().mass[n];
    node_momentum += sim.nodes().momentum[n];
    node_force += sim.nodes().force[n];
  }
  const Vec<2> particle_momentum = test::total_momentum(sim);
  // Partition of unity: the grid holds exactly the particles' mass and momentum; the
  // internal forces sum to zero (zero gradient sum). Tolerance: round-off of ~400 terms.
  CHECK(node_mass == doctest::Approx(particle_mass).epsilon(1e-13));
  CHECK((node_momentum - particle_momentum).norm() <= 1e-13 * particle_mass);
  CHECK(node_force.norm() <= 1e-10 * 1e3);

  // A full PIC step without gravity or boundaries conserves the particles' momentum too.
  sim.update_grid(1e-5);
  sim.map_to_particles(1e-5);
  const Vec<2> after = test::total_momentum(sim);
  CHECK((after - particle_momentum).norm() <= 1e-12 * particle_mass);
}
}  // namespace

TEST_CASE("particle-grid transfer conserves mass and momentum: linear") {
  check_transfer_conservation<shape::Linear>();
}
TEST_CASE("particle-grid transfer conserves mass and momentum: GIMP") {
  check_transfer_conservation<shape::GIMP>();
}
TEST_CASE("particle-grid transfer conserves mass and momentum: quadratic B-spline") {
  check_transfer_conservation<shape::QuadraticBSpline>();
}
TEST_CASE("particle-grid transfer conserves mass and momentum: cubic B-spline") {
  check_transfer_conservation<shape::CubicBSpline>();
}
