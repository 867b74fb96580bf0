// Elastic column under self-weight with lateral rollers and a fixed base, relaxed to static
// equilibrium with local damping. Analytic: sigma_yy = -rho g (H - y) and the vertical
// displacement u(y) = -rho g (H y - y^2 / 2) / M, so the top settles by rho g H^2 / (2 M),
// M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) the constrained modulus.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using grid::BoundaryConditions;
using grid::BoundaryKind;

struct ColumnErrors {
  double stress;      // max |sigma_yy - exact| / (rho g H)
  double settlement;  // relative error of the top particle's settlement
};

ColumnErrors column_errors(Index cells_over_height) {
  const double height = 1.0, density = 1000.0, gravity = 9.81;
  const double youngs = 1e6, poisson = 0.3;
  const test::Elastic model(youngs, poisson);
  const double modulus = model.p_wave_modulus();
  const double h = height / static_cast<double>(cells_over_height);
  // Two cells of headroom above the column; one cell wide.
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(h, height + 2.0 * h),
                           {1, cells_over_height + 2});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -gravity);
  parameters.damping = 0.3;
  Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::USL> sim(
      grid, model, parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(h, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  sim.boundary_conditions().set(BoundaryConditions<2>::face(0, false), BoundaryKind::roller);
  sim.boundary_conditions().set(BoundaryConditions<2>::face(0, true), BoundaryKind::roller);
  sim.boundary_conditions().set(BoundaryConditions<2>::face(1, false), BoundaryKind::fixed);

  const double dt = sim.time_step();
  const double wave_transit = height / std::sqrt(modulus / density);
  const int steps = static_cast<int>(std::ceil(120.0 * wave_transit / dt));
  for (int i = 0; i < steps; ++i) sim.step(dt);

  const auto& x0 = sim.particles().template get<particles::field::InitialPosition<2>>();
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  const auto& stress = sim.particles().template get<particles::field::Stress<test::Elastic>>();
  const double scale = density * gravity * height;
  ColumnErrors errors{0.0, 0.0};
  Index top = 0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double exact = -density * gravity * (height - x0[p][1]);
    errors.stress = std::max(errors.stress, std::abs(stress[p][1] - exact) / scale);
    if (x0[p][1] > x0[top][1]) top = p;
  }
  const double y = x0[top][1];
  const double exact_settlement = density * gravity * (height * y - 0.5 * y * y) / modulus;
  errors.settlement = std::abs((x0[top][1] - x[top][1]) - exact_settlement) / exact_settlement;
  return errors;
}
}  // namespace

TEST_CASE("elastic column under self-weight converges to the analytic solution") {
  const ColumnErrors coarse = column_errors(8);
  const ColumnErrors medium = column_errors(16);
  const ColumnErrors fine = column_errors(32);
  MESSAGE("stress errors (8, 16, 32 cells): " << coarse.stress << ", " << medium.stress << ", "
                                              << fine.stress);
  MESSAGE("settlement errors (8, 16, 32 cells): " << coarse.settlement << ", " << medium.settlement
                                                  << ", " << fine.settlement);
  // Issue: within 2 % on the finest mesh, and convergence over the three meshes.
  CHECK(fine.stress <= 0.02);
  CHECK(fine.settlement <= 0.02);
  CHECK(medium.stress < coarse.stress);
  CHECK(fine.stress < medium.stress);
  CHECK(medium.settlement <= coarse.settlement);
  CHECK(fine.settlement <= medium.settlement);
}
