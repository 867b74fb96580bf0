// The deterministic parallel scatter at Dim = 3 (2^3 block colours): a 3D run on two threads
// equals the one-thread run bit for bit, and the coloured scatter really ran on two threads.
#include <doctest/doctest.h>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Soil3 = material::MohrCoulomb<double, 3>;
using Sim = Simulation<3, shape::QuadraticBSpline, continuum::Classical<Soil3>,
                       contact::SingleField, integrator::MUSL>;

Sim collapsing_block(int threads) {
  // 64 x 8 x 8 cells: 4 blocks of 16 x 4 x 4 cells along x, 2 along y and z, so every colour
  // holds two blocks that can run side by side.
  const grid::Grid<3> grid(Vec<3>::Zero(), Vec<3>(1.6, 0.2, 0.2), {64, 8, 8});
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  parameters.threads = threads;
  Sim sim(grid,
          Soil3({.youngs_modulus = 2.76e6,
                 .poisson_ratio = 0.2,
                 .friction_angle_deg = 26.0,
                 .dilatancy_angle_deg = 2.0}),
          parameters);
  // A soil layer over three blocks along x (blocks 0 and 2 share a colour) that slumps
  // towards its free end: particles change cells.
  const auto seeding = particles::seed_box(grid, Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.2, 0.2, 0.05), 2);
  sim.add_particles(seeding.positions, seeding.volume, 778.0, seeding.half_width);
  using BC = grid::BoundaryConditions<3>;
  sim.boundary_conditions().set(BC::face(2, false), grid::BoundaryKind::friction, 0.4);
  sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(1, true), grid::BoundaryKind::roller);
  return sim;
}
}  // namespace

TEST_CASE("3D runs do not depend on the thread count, bit for bit") {
  Sim one = collapsing_block(1);
  Sim two = collapsing_block(2);
  REQUIRE(one.particles().size() >= cosmpm::parallel_threshold);
  const double dt = one.time_step();
  for (int i = 0; i < 15; ++i) {
    one.step(dt);
    two.step(dt);
  }
  CHECK(one.last_team_size() == 1);
#if defined(_OPENMP)
  CHECK(two.last_team_size() == 2);
#endif
  const auto& x1 = one.particles().get<particles::field::Position<3>>();
  const auto& x2 = two.particles().get<particles::field::Position<3>>();
  const auto& x0 = one.particles().get<particles::field::InitialPosition<3>>();
  const auto& s1 = one.particles().get<particles::field::Stress<Soil3>>();
  const auto& s2 = two.particles().get<particles::field::Stress<Soil3>>();
  bool identical = true;
  double moved = 0.0;
  for (Index p = 0; p < one.particles().size(); ++p) {
    identical = identical && x1[p] == x2[p] && s1[p] == s2[p];
    moved = std::max(moved, (x1[p] - x0[p]).norm());
  }
  CHECK(identical);
  CHECK(moved > 0.0);  // the run did something
}
