// The elastic column under self-weight in 3D: a square column, roller side walls on all four
// vertical faces, a fixed base, gravity along z (the last axis), relaxed to static equilibrium
// with local damping. Analytic (uniaxial strain, as the 2D column.test.cpp):
//   sigma_zz = -rho g (H - z),  sigma_xx = sigma_yy = nu / (1 - nu) sigma_zz,
//   u_z(z) = -rho g (H z - z^2 / 2) / M,  M = E (1 - nu) / ((1 + nu)(1 - 2 nu)).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using grid::BoundaryConditions;
using grid::BoundaryKind;
using Elastic3 = material::LinearElastic<double, 3>;

struct ColumnErrors {
  double vertical;    // max |sigma_zz - exact| / (rho g H)
  double lateral;     // max |sigma_xx,yy - K0 exact| / (rho g H)
  double shear;       // max |shear| / (rho g H)
  double settlement;  // relative error of the top particle's settlement
};

template <class Scheme>
ColumnErrors column_errors(Index cells_over_height) {
  const double height = 1.0, density = 1000.0, gravity = 9.81;
  const double youngs = 1e6, poisson = 0.3;
  const Elastic3 model(youngs, poisson);
  const double modulus = model.p_wave_modulus();
  const double h = height / static_cast<double>(cells_over_height);
  // One cell wide along x and y; two cells of headroom above the column.
  const grid::Grid<3> grid(Vec<3>(0.0, 0.0, 0.0), Vec<3>(h, h, height + 2.0 * h),
                           {1, 1, cells_over_height + 2});
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -gravity);
  parameters.damping = 0.3;
  Simulation<3, shape::Linear, continuum::Classical<Elastic3>, contact::SingleField, Scheme> sim(
      grid, model, parameters);
  const auto seeding = particles::seed_box(grid, Vec<3>(0.0, 0.0, 0.0), Vec<3>(h, h, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  using BC = BoundaryConditions<3>;
  for (int axis = 0; axis < 2; ++axis) {
    sim.boundary_conditions().set(BC::face(axis, false), BoundaryKind::roller);
    sim.boundary_conditions().set(BC::face(axis, true), BoundaryKind::roller);
  }
  sim.boundary_conditions().set(BC::face(2, false), BoundaryKind::fixed);

  const double dt = sim.time_step();
  const double wave_transit = height / std::sqrt(modulus / density);
  const int steps = static_cast<int>(std::ceil(120.0 * wave_transit / dt));
  for (int i = 0; i < steps; ++i) sim.step(dt);

  const auto& x0 = sim.particles().template get<particles::field::InitialPosition<3>>();
  const auto& x = sim.particles().template get<particles::field::Position<3>>();
  const auto& stress = sim.particles().template get<particles::field::Stress<Elastic3>>();
  const double scale = density * gravity * height;
  const double k0 = poisson / (1.0 - poisson);
  ColumnErrors errors{0.0, 0.0, 0.0, 0.0};
  Index top = 0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double exact = -density * gravity * (height - x0[p][2]);
    errors.vertical = std::max(errors.vertical, std::abs(stress[p][2] - exact) / scale);
    for (int c = 0; c < 2; ++c) {
      errors.lateral = std::max(errors.lateral, std::abs(stress[p][c] - k0 * exact) / scale);
    }
    for (int c = 3; c < 6; ++c)
      errors.shear = std::max(errors.shear, std::abs(stress[p][c]) / scale);
    if (x0[p][2] > x0[top][2]) top = p;
  }
  const double z = x0[top][2];
  const double exact_settlement = density * gravity * (height * z - 0.5 * z * z) / modulus;
  errors.settlement = std::abs((x0[top][2] - x[top][2]) - exact_settlement) / exact_settlement;
  return errors;
}

// The plane-strain column of column.test.cpp at the same resolution: the 3D column with
// roller side walls is the same one-dimensional problem.
template <class Scheme>
double column_2d_stress_error(Index cells_over_height) {
  const double height = 1.0, density = 1000.0, gravity = 9.81;
  const material::LinearElastic<double> model(1e6, 0.3);
  const double h = height / static_cast<double>(cells_over_height);
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(h, height + 2.0 * h),
                           {1, cells_over_height + 2});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -gravity);
  parameters.damping = 0.3;
  Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<double>>,
             contact::SingleField, Scheme>
      sim(grid, model, parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(h, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  using BC = BoundaryConditions<2>;
  sim.boundary_conditions().set(BC::face(0, false), BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(0, true), BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(1, false), BoundaryKind::fixed);
  const double dt = sim.time_step();
  const double wave_transit = height / std::sqrt(model.p_wave_modulus() / density);
  const int steps = static_cast<int>(std::ceil(120.0 * wave_transit / dt));
  for (int i = 0; i < steps; ++i) sim.step(dt);
  const auto& x0 = sim.particles().template get<particles::field::InitialPosition<2>>();
  const auto& stress =
      sim.particles().template get<particles::field::Stress<material::LinearElastic<double>>>();
  double error = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double exact = -density * gravity * (height - x0[p][1]);
    error = std::max(error, std::abs(stress[p][1] - exact) / (density * gravity * height));
  }
  return error;
}
}  // namespace

TEST_CASE("3D elastic column under self-weight matches the analytic stress and settlement") {
  // 32 cells over the height: the 2D column's finest mesh, where it is within 2 % (issue 18
  // asks for the 2D tolerances in 3D).
  const ColumnErrors e = column_errors<integrator::USL>(32);
  MESSAGE("USL, 32 cells: sigma_zz " << e.vertical << ", sigma_xx,yy " << e.lateral << ", shear "
                                     << e.shear << ", settlement " << e.settlement);
  CHECK(e.vertical <= 0.02);
  CHECK(e.lateral <= 0.02);
  // Nothing drives shear: round-off of stresses of size rho g H.
  CHECK(e.shear <= 1e-9);
  CHECK(e.settlement <= 0.02);
}

TEST_CASE_TEMPLATE("3D elastic column, every scheme: the plane-strain column's error", Scheme,
                   integrator::USL, integrator::MUSL, integrator::USF) {
  // The same 1D problem, the same particles per cell along the height and the same step: the
  // largest sigma_zz error of the 3D column equals the 2D column's sigma_yy error to round-off
  // accumulated over the run (1e-9 of rho g H). At 16 cells that error is 2.23 % for every
  // scheme (2.5 % allowed; 2 % holds at 32 cells, above), the lateral stress 1.0 %.
  const ColumnErrors e3 = column_errors<Scheme>(16);
  const double e2 = column_2d_stress_error<Scheme>(16);
  MESSAGE(std::string(Scheme::name()) << ", 16 cells: 3D " << e3.vertical << ", 2D " << e2);
  CHECK(std::abs(e3.vertical - e2) < 1e-9);
  CHECK(e3.vertical <= 0.025);
  CHECK(e3.lateral <= 0.025);
  CHECK(e3.shear <= 1e-9);
}
