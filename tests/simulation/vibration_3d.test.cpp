// Elastic vibration at Dim = 3 against the analytic frequencies: a single material point in
// one cell (compression along x with roller side faces: the constrained modulus; shear along z
// on a fixed x or y face: the shear modulus, through the xz and yz components that only 3D
// has) and the fixed-free bar's first mode along the vertical axis z.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"
#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using grid::BoundaryKind;
using BC = grid::BoundaryConditions<3>;
using Elastic3 = material::LinearElastic<double, 3>;
template <class Scheme>
using Sim3 =
    Simulation<3, shape::Linear, continuum::Classical<Elastic3>, contact::SingleField, Scheme>;

template <class Sim>
double kinetic_energy(const Sim& sim) {
  const auto& v = sim.particles().template get<particles::field::Velocity<3>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  double energy = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) energy += 0.5 * m[p] * v[p].squaredNorm();
  return energy;
}
// 1/2 sigma : eps V (normal products plus twice the tensor shear products).
template <class Sim>
double strain_energy(const Sim& sim) {
  const auto& s = sim.particles().template get<particles::field::Stress<Elastic3>>();
  const auto& e = sim.particles().template get<particles::field::Strain<Elastic3>>();
  const auto& volume = sim.particles().template get<particles::field::Volume>();
  double energy = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    double work = 0.0;
    for (int c = 0; c < 6; ++c) work += (c < 3 ? 1.0 : 2.0) * s[p][c] * e[p][c];
    energy += 0.5 * work * volume[p];
  }
  return energy;
}

struct PointMode {
  const char* name;
  int fixed_axis;   // the face x_axis = 0 is fixed
  int motion_axis;  // the particle starts moving along this axis
  // Rollers on the faces normal to every axis but the fixed and the motion axes: plane strain
  // in the plane of those two (uniaxial strain when they are the same axis).
};

struct PointResult {
  double period = 0.0;           // measured
  double analytic_period = 0.0;  // 2 pi / omega
  double energy_error = 0.0;     // max |E - E0| / E0
  double off_axis = 0.0;         // max off-axis velocity / v0
  double rotation = 0.0;         // the rotation amplitude v0 / (omega L)
};

constexpr double point_length = 1.0, point_youngs = 100.0, point_poisson = 0.25, v0 = 0.1;

// One particle at the centre of one L x L x L cell, the lower face normal to `fixed_axis`
// fixed and rollers on the faces of the third axis (plane strain, so that each mode has a
// plane-strain twin; with those faces free USL's updated grid velocity would also strain the
// point along the third axis). As in 2D (vibration.test.cpp), the free nodes move with the
// particle and carry half its mass, so v(t) = v0 cos(omega t) with omega = sqrt(K / rho) / L,
// K the constrained modulus M for motion normal to the fixed face and the shear modulus G for
// motion along it.
template <class Scheme>
PointResult single_point(const PointMode& mode) {
  const double length = point_length, density = 1.0;
  const Elastic3 model(point_youngs, point_poisson);
  const double modulus =
      mode.fixed_axis == mode.motion_axis ? model.p_wave_modulus() : model.shear_modulus();
  const double omega = std::sqrt(modulus / density) / length;
  const grid::Grid<3> grid(Vec<3>::Zero(), Vec<3>::Constant(length), {1, 1, 1});
  SimulationParameters<3> parameters;
  parameters.flip_fraction = 1.0;  // pure FLIP, whose answer this is (see vibration.test.cpp)
  Sim3<Scheme> sim(grid, model, parameters);
  sim.add_particles({Vec<3>::Constant(0.5 * length)}, length * length * length, density,
                    Vec<3>::Constant(0.25));
  sim.particles().template get<particles::field::Velocity<3>>()[0] =
      v0 * Vec<3>::Unit(mode.motion_axis);
  sim.boundary_conditions().set(BC::face(mode.fixed_axis, false), BoundaryKind::fixed);
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == mode.fixed_axis || axis == mode.motion_axis) continue;
    sim.boundary_conditions().set(BC::face(axis, false), BoundaryKind::roller);
    sim.boundary_conditions().set(BC::face(axis, true), BoundaryKind::roller);
  }
  PointResult result;
  result.analytic_period = 2.0 * pi / omega;
  result.rotation = v0 / (omega * length);
  const double dt = result.analytic_period / 2000.0;
  const int steps = 3 * 2000;
  std::vector<double> velocity;
  const double energy0 = kinetic_energy(sim);
  for (int i = 0; i < steps; ++i) {
    sim.step(dt);
    const Vec<3> v = sim.particles().template get<particles::field::Velocity<3>>()[0];
    velocity.push_back(v[mode.motion_axis]);
    result.off_axis = std::max(
        result.off_axis, (v - v[mode.motion_axis] * Vec<3>::Unit(mode.motion_axis)).norm() / v0);
    const double energy = kinetic_energy(sim) + strain_energy(sim);
    result.energy_error = std::max(result.energy_error, std::abs(energy - energy0) / energy0);
  }
  result.period = test::period_from_zero_crossings(velocity, dt);
  MESSAGE(std::string(Scheme::name())
          << ", " << mode.name << ": period " << result.period << " s (analytic "
          << result.analytic_period << "), energy error " << result.energy_error
          << ", off-axis velocity " << result.off_axis);
  return result;
}

// The plane-strain single point of vibration.test.cpp with the same material: motion along x
// (rollers on the y faces) or along y (the x face fixed, shear).
template <class Scheme>
PointResult single_point_2d(bool shear) {
  const test::Elastic model(point_youngs, point_poisson);
  const grid::Grid<2> grid(Vec<2>::Zero(), Vec<2>::Constant(point_length), {1, 1});
  SimulationParameters<2> parameters;
  parameters.flip_fraction = 1.0;
  Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, Scheme> sim(
      grid, model, parameters);
  sim.add_particles({Vec<2>::Constant(0.5 * point_length)}, point_length * point_length, 1.0,
                    Vec<2>::Constant(0.25));
  sim.particles().template get<particles::field::Velocity<2>>()[0] =
      shear ? Vec<2>(0.0, v0) : Vec<2>(v0, 0.0);
  using BC2 = grid::BoundaryConditions<2>;
  sim.boundary_conditions().set(BC2::face(0, false), BoundaryKind::fixed);
  if (!shear) {
    sim.boundary_conditions().set(BC2::face(1, false), BoundaryKind::roller);
    sim.boundary_conditions().set(BC2::face(1, true), BoundaryKind::roller);
  }
  const double omega =
      std::sqrt((shear ? model.shear_modulus() : model.p_wave_modulus())) / point_length;
  PointResult result;
  result.analytic_period = 2.0 * pi / omega;
  const double dt = result.analytic_period / 2000.0;
  const double energy0 = test::kinetic_energy(sim);
  std::vector<double> velocity;
  for (int i = 0; i < 3 * 2000; ++i) {
    sim.step(dt);
    const Vec<2> v = sim.particles().template get<particles::field::Velocity<2>>()[0];
    velocity.push_back(shear ? v[1] : v[0]);
    result.off_axis = std::max(result.off_axis, std::abs(shear ? v[0] : v[1]) / v0);
    const double energy = test::kinetic_energy(sim) + test::strain_energy(sim);
    result.energy_error = std::max(result.energy_error, std::abs(energy - energy0) / energy0);
  }
  result.period = test::period_from_zero_crossings(velocity, dt);
  return result;
}

// A bar along z fixed at z = 0 and free at z = L, started in its first mode
// v_z = v0 sin(pi z / 2L), rollers on the four side faces: T = 4 L / c, c = sqrt(M / rho).
template <class Scheme>
void bar_first_mode(double energy_bound) {
  const double length = 25.0, youngs = 100.0, poisson = 0.25, density = 1.0;
  const Elastic3 model(youngs, poisson);
  const double wave_speed = std::sqrt(model.p_wave_modulus() / density);
  const double period = 4.0 * length / wave_speed;
  const grid::Grid<3> grid(Vec<3>::Zero(), Vec<3>(1.0, 1.0, 27.0), {1, 1, 27});
  SimulationParameters<3> parameters;
  parameters.flip_fraction = 1.0;
  Sim3<Scheme> sim(grid, model, parameters);
  const auto seeding =
      particles::seed_box(grid, Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.0, 1.0, length), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  auto& v = sim.particles().template get<particles::field::Velocity<3>>();
  const auto& x = sim.particles().template get<particles::field::Position<3>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    v[p] = Vec<3>(0.0, 0.0, v0 * std::sin(pi * x[p][2] / (2.0 * length)));
  }
  for (int axis = 0; axis < 2; ++axis) {
    sim.boundary_conditions().set(BC::face(axis, false), BoundaryKind::roller);
    sim.boundary_conditions().set(BC::face(axis, true), BoundaryKind::roller);
  }
  sim.boundary_conditions().set(BC::face(2, false), BoundaryKind::fixed);
  const double dt = 0.2 * grid.cell_size()[2] / wave_speed;
  const int steps = static_cast<int>(std::round(3.0 * period / dt));
  std::vector<double> momentum;
  const double energy0 = kinetic_energy(sim);
  double max_energy_error = 0.0;
  const auto& m = sim.particles().template get<particles::field::Mass>();
  for (int i = 0; i < steps; ++i) {
    sim.step(dt);
    double pz = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) pz += m[p] * v[p][2];
    momentum.push_back(pz);
    const double energy = kinetic_energy(sim) + strain_energy(sim);
    max_energy_error = std::max(max_energy_error, std::abs(energy - energy0) / energy0);
  }
  const double measured = test::period_from_zero_crossings(momentum, dt);
  MESSAGE(std::string(Scheme::name()) << " bar along z: period " << measured << " s (analytic "
                                      << period << "), energy error " << max_energy_error);
  CHECK(measured == doctest::Approx(period).epsilon(0.01));  // issue: within 1 %
  CHECK(max_energy_error <= energy_bound);
}

constexpr PointMode compression{"compression along x", 0, 0};
constexpr PointMode shear_xz{"shear along z on the x face", 0, 2};
constexpr PointMode shear_yz{"shear along z on the y face", 1, 2};
}  // namespace

// Period within 1 % (the bound; measured 2e-5). Energy: USL loses omega^2 dt t in
// compression (0.059 over three periods at dt = T / 2000, vibration.test.cpp) and measured
// 0.163 in shear, as the plane-strain point in shear does; MUSL and USF keep it within 0.4 %.
// In shear the Jaumann rotation couples the motion to the normal stresses at first order in
// the rotation amplitude theta = v0 / (omega L) = 0.016: the off-axis velocity is
// 1.07 theta v0 (1.5 theta allowed). Each 3D mode must reproduce its plane-strain twin: the
// xz and yz shear components follow the plane-strain code's xy to round-off (1e-9).
TEST_CASE_TEMPLATE("3D single material point vibration", Scheme, integrator::USL, integrator::MUSL,
                   integrator::USF) {
  const bool usl = std::is_same_v<Scheme, integrator::USL>;
  const PointResult along = single_point<Scheme>(compression);
  const PointResult plane_along = single_point_2d<Scheme>(false);
  CHECK(along.period == doctest::Approx(along.analytic_period).epsilon(0.01));
  CHECK(along.energy_error <= (usl ? 0.065 : 0.005));
  CHECK(along.off_axis == 0.0);
  CHECK(std::abs(along.energy_error - plane_along.energy_error) < 1e-9);
  CHECK(std::abs(along.period - plane_along.period) < 1e-9);
  for (const PointMode& mode : {shear_xz, shear_yz}) {
    CAPTURE(mode.name);
    const PointResult shear = single_point<Scheme>(mode);
    const PointResult plane_shear = single_point_2d<Scheme>(true);
    CHECK(shear.period == doctest::Approx(shear.analytic_period).epsilon(0.01));
    CHECK(shear.energy_error <= (usl ? 0.17 : 0.005));
    CHECK(shear.off_axis <= 1.5 * shear.rotation);
    CHECK(std::abs(shear.energy_error - plane_shear.energy_error) < 1e-9);
    CHECK(std::abs(shear.period - plane_shear.period) < 1e-9);
    CHECK(std::abs(shear.off_axis - plane_shear.off_axis) < 1e-9);
  }
}

// Energy bound: the 2D bar's (measured drift over three periods at dt = 0.2 h / c, rounded up).
TEST_CASE_TEMPLATE("3D fixed-free bar first mode along z", Scheme, integrator::USL,
                   integrator::MUSL) {
  bar_first_mode<Scheme>(0.02);
}
