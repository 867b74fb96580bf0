// Particle-to-grid and back at Dim = 3 conserve mass and momentum to round-off, for every
// kernel and both velocity transfers (FlipBlend; APIC with the kernels it takes), with
// particles in every cell including those on the grid's faces, edges and corners.
#include <doctest/doctest.h>

#include <random>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"
#include "cosmpm/transfer/apic.hpp"

namespace {
using namespace cosmpm;
using Elastic3 = material::LinearElastic<double, 3>;

template <class Kernel, class Transfer>
void check_transfer_conservation() {
  using Sim = Simulation<3, Kernel, continuum::Classical<Elastic3>, contact::SingleField,
                         integrator::USL, Transfer>;
  // 6 x 4 x 5 cells, anisotropic, origin off zero.
  const grid::Grid<3> grid(Vec<3>(-0.3, 0.1, 0.2), Vec<3>(0.6, 0.32, 0.45), {6, 4, 5});
  SimulationParameters<3> parameters;
  if constexpr (!Transfer::affine) parameters.flip_fraction = 0.0;  // PIC: the grid's velocity
  Sim sim(grid, Elastic3(1e5, 0.25), parameters);
  const auto seeding =
      particles::seed_box(grid, grid.origin(), Vec<3>(grid.origin() + grid.extent()), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  auto& x = sim.particles().template get<particles::field::Position<3>>();
  auto& v = sim.particles().template get<particles::field::Velocity<3>>();
  auto& stress = sim.particles().template get<particles::field::Stress<Elastic3>>();
  const Vec<3> h = grid.cell_size();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    // Up to 0.2 of a quarter cell (the sub-cell), so every particle stays inside the box.
    x[p] += Vec<3>(jitter(rng), jitter(rng), jitter(rng)).cwiseProduct(h) * 0.25;
    v[p] = Vec<3>(jitter(rng), jitter(rng), jitter(rng));
    for (int c = 0; c < 6; ++c) stress[p][c] = 1e3 * jitter(rng);
  }
  if constexpr (Transfer::affine) {
    // A random affine moment, so APIC's terms are exercised.
    auto& moment = sim.particles().template get<particles::field::AffineMoment<3>>();
    for (Index p = 0; p < sim.particles().size(); ++p) {
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) moment[p](i, j) = 1e-3 * jitter(rng);
      }
    }
  }
  sim.map_to_grid(true);
  const auto& m = sim.particles().template get<particles::field::Mass>();
  double particle_mass = 0.0;
  Vec<3> particle_momentum = Vec<3>::Zero();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    particle_mass += m[p];
    particle_momentum += m[p] * v[p];
  }
  double node_mass = 0.0;
  Vec<3> node_momentum = Vec<3>::Zero();
  Vec<3> node_force = Vec<3>::Zero();
  for (Index n = 0; n < grid.node_count(); ++n) {
    node_mass += sim.nodes().mass[n];
    node_momentum += sim.nodes().momentum[n];
    node_force += sim.nodes().force[n];
  }
  // Partition of unity: the grid holds exactly the particles' mass and momentum (APIC's
  // affine terms sum to zero, sum N_i (x_i - x_p) = 0); the internal forces sum to zero
  // (zero gradient sum). Tolerance: round-off of ~1000 particles x 8-64 nodes.
  CHECK(node_mass == doctest::Approx(particle_mass).epsilon(1e-13));
  CHECK((node_momentum - particle_momentum).norm() <= 1e-13 * particle_mass);
  // Forces: each term is V sigma dN/dx ~ (0.1 m)^3 / 64 * 1e3 Pa / 0.1 m.
  CHECK(node_force.norm() <= 1e-10 * 1e3);

  // A PIC (or APIC) step without gravity or boundaries conserves the momentum too.
  sim.update_grid(1e-5);
  sim.map_to_particles(1e-5);
  Vec<3> after = Vec<3>::Zero();
  for (Index p = 0; p < sim.particles().size(); ++p) after += m[p] * v[p];
  CHECK((after - particle_momentum).norm() <= 1e-12 * particle_mass);
}
}  // namespace

TEST_CASE_TEMPLATE("3D transfers conserve mass and momentum (FlipBlend at PIC)", Kernel,
                   shape::Linear, shape::GIMP, shape::QuadraticBSpline, shape::CubicBSpline) {
  check_transfer_conservation<Kernel, transfer::FlipBlend>();
}
TEST_CASE_TEMPLATE("3D transfers conserve mass and momentum (APIC)", Kernel, shape::GIMP,
                   shape::QuadraticBSpline, shape::CubicBSpline) {
  check_transfer_conservation<Kernel, transfer::APIC>();
}
