// Issue 13, item 3: no particle crosses a fixed or roller face of the grid, with every kernel
// and scheme, when the flow drives particles hard against the faces.
//
// An elastic block is thrown diagonally into a corner of the grid at 4 m/s, with gravity
// pressing it on: one face of the corner is fixed, the other a roller, and the corners are
// swapped between the two throws (lower-left: fixed floor, roller wall; upper-right: fixed
// wall, roller ceiling). Why it must hold: next to a face whose nodes are held, every kernel's
// interpolant along the normal is linear in the distance y from the face in the first cell (the
// B-splines fold their ghost nodes onto it), so a step moves a particle towards the face by
// at most dt (y / h) |v_node| and it crosses only if a node moves faster than h / dt =
// c / cfl (73 m/s here, 18 times the impact speed); docs/validation.md, "Why the failing
// compositions fail", item 4.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/initial/geostatic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"

namespace {
using namespace cosmpm;
using BC = grid::BoundaryConditions<2>;

constexpr double cell = 0.05;  // m
constexpr double speed = 1.0;  // m/s along each axis, towards the corner
constexpr double push = 50.0;  // m/s^2 along each axis, towards the corner
constexpr double density = 1000.0;

struct CornerRun {
  double closest_fixed = INFINITY;   // smallest particle distance from the fixed face, m
  double closest_roller = INFINITY;  // ... from the roller face
};

// `lower`: the lower-left corner (fixed floor y = 0, roller wall x = 0); otherwise the
// upper-right one (fixed wall x = 1, roller ceiling y = 1).
template <class Kernel, class Scheme>
CornerRun throw_into_corner(bool lower) {
  using Sim = Simulation<2, Kernel, test::ElasticContinuum, contact::SingleField, Scheme>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {20, 20});
  const Vec<2> towards = lower ? Vec<2>(-1.0, -1.0) : Vec<2>(1.0, 1.0);
  SimulationParameters<2> parameters;
  parameters.gravity = push * towards;
  // E = 1 MPa, nu = 0.3: p-wave speed 36.7 m/s; the impact strain 1 / 36.7 = 0.03, the
  // body force's 1000 x 50 x 0.3 / 1e6 = 0.015.
  Sim sim(grid, test::Elastic(1e6, 0.3), parameters);
  // A 0.3 m block against both faces of the corner (its first particles a quarter cell off).
  const Vec<2> from = lower ? Vec<2>(0.0, 0.0) : Vec<2>(1.0 - 6.0 * cell, 1.0 - 6.0 * cell);
  const auto seeding =
      particles::seed_box(grid, from, Vec<2>(from + Vec<2>::Constant(6.0 * cell)), 2);
  const Index first =
      sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  for (Index p = first; p < sim.particles().size(); ++p) v[p] = speed * towards;
  // Fixed: axis 1 (floor) at the lower corner, axis 0 (wall) at the upper one.
  const int fixed_axis = lower ? 1 : 0;
  const int roller_axis = 1 - fixed_axis;
  sim.boundary_conditions().set(BC::face(fixed_axis, !lower), grid::BoundaryKind::fixed);
  sim.boundary_conditions().set(BC::face(roller_axis, !lower), grid::BoundaryKind::roller);
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  const auto distance = [&](Index p, int axis) { return lower ? x[p][axis] : 1.0 - x[p][axis]; };
  CornerRun run;
  const double dt = sim.time_step();
  // 0.1 s: the impact and about a dozen wave periods of the block pressed into the corner
  // (4 x 0.3 m / 36.7 m/s = 33 ms).
  while (sim.time() < 0.1) {
    sim.step(dt);  // a particle outside the grid box would stop the run (StrayParticles::stop)
    for (Index p = 0; p < sim.particles().size(); ++p) {
      run.closest_fixed = std::min(run.closest_fixed, distance(p, fixed_axis));
      run.closest_roller = std::min(run.closest_roller, distance(p, roller_axis));
    }
  }
  return run;
}

template <class Kernel, class Scheme>
void check_corners() {
  for (bool lower : {true, false}) {
    CAPTURE(lower);
    const CornerRun run = throw_into_corner<Kernel, Scheme>(lower);
    MESSAGE(std::string(Kernel::name())
            << " " << std::string(Scheme::name()) << (lower ? " lower" : " upper")
            << " corner: closest to the fixed face " << run.closest_fixed
            << " m, to the roller face " << run.closest_roller << " m");
    // No particle centre reached, let alone crossed, either face...
    CHECK(run.closest_fixed > 0.0);
    CHECK(run.closest_roller > 0.0);
    // ...although the flow drove the block's first particles onto them: closer than where they
    // started, a quarter cell (0.0125 m) off the faces.
    CHECK(run.closest_fixed < 0.25 * cell);
    CHECK(run.closest_roller < 0.25 * cell);
  }
}
}  // namespace

TEST_CASE("no particle crosses a fixed or roller face: linear") {
  check_corners<shape::Linear, integrator::USL>();
  check_corners<shape::Linear, integrator::MUSL>();
  check_corners<shape::Linear, integrator::USF>();
}

TEST_CASE("no particle crosses a fixed or roller face: GIMP") {
  check_corners<shape::GIMP, integrator::USL>();
  check_corners<shape::GIMP, integrator::MUSL>();
  check_corners<shape::GIMP, integrator::USF>();
}

TEST_CASE("no particle crosses a fixed or roller face: quadratic and cubic B-splines") {
  check_corners<shape::QuadraticBSpline, integrator::USL>();
  check_corners<shape::QuadraticBSpline, integrator::MUSL>();
  check_corners<shape::QuadraticBSpline, integrator::USF>();
  check_corners<shape::CubicBSpline, integrator::USL>();
  check_corners<shape::CubicBSpline, integrator::MUSL>();
  check_corners<shape::CubicBSpline, integrator::USF>();
}

namespace {
struct CollapseRun {
  double closest_floor = INFINITY;  // fixed, y = 0
  double closest_left = INFINITY;   // roller, x = 0
  double closest_right = INFINITY;  // roller, x = 0.1
};

// A column of dry soil (the rods of example 04: phi = 19.8 deg, E = 0.84 MPa, nu = 0.3,
// rho = 2650 kg/m^3), 50 mm x 50 mm, collapses in a box 100 mm long: it flows along the fixed
// floor and runs into the far roller wall (its runout in the open, 0.12 m, is longer than
// the box), with 5 mm cells and the default velocity transfer.
template <class Kernel, class Scheme>
CollapseRun collapse_in_box() {
  using Soil = material::MohrCoulomb<>;
  using Sim = Simulation<2, Kernel, continuum::Classical<Soil>, contact::SingleField, Scheme>;
  const double soil_density = 2650.0, column = 0.05, h = 0.005;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.07), {20, 14});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = 1;
  Sim sim(grid,
          Soil({.youngs_modulus = 0.84e6,
                .poisson_ratio = 0.3,
                .friction_angle_deg = 19.8,
                .dilatancy_angle_deg = 0.0}),
          parameters);
  const auto block = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(column, column), 2);
  sim.add_particles(block.positions, block.volume, soil_density, block.half_width);
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  auto& stress = sim.particles().template get<particles::field::Stress<Soil>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    stress[p] =
        initial::geostatic_stress(soil_density, 9.81, column - x[p][1], initial::jaky_k0(19.8));
  }
  sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::fixed);
  sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(0, true), grid::BoundaryKind::roller);
  CollapseRun run;
  const double dt = sim.time_step();
  // 0.4 s: the front reaches the far wall at about 0.2 s; the heap settles against it.
  while (sim.time() < 0.4) {
    sim.step(dt);
    for (Index p = 0; p < sim.particles().size(); ++p) {
      run.closest_floor = std::min(run.closest_floor, x[p][1]);
      run.closest_left = std::min(run.closest_left, x[p][0]);
      run.closest_right = std::min(run.closest_right, 0.1 - x[p][0]);
    }
  }
  MESSAGE(std::string(Kernel::name())
          << " " << std::string(Scheme::name()) << ": closest to the floor " << run.closest_floor
          << " m, the left wall " << run.closest_left << " m, the right wall " << run.closest_right
          << " m");
  CHECK(run.closest_floor > 0.0);
  CHECK(run.closest_left > 0.0);
  CHECK(run.closest_right > 0.0);
  // The flow pressed on the floor (its particles started a quarter cell above it) and reached
  // the far wall (they started 10 cells from it): a particle came within a cell of it.
  CHECK(run.closest_floor < 0.25 * h);
  CHECK(run.closest_right < h);
  return run;
}
}  // namespace

TEST_CASE("no particle crosses a fixed or roller face: a soil column flows into the far wall") {
  collapse_in_box<shape::Linear, integrator::MUSL>();
  collapse_in_box<shape::GIMP, integrator::MUSL>();
  collapse_in_box<shape::QuadraticBSpline, integrator::USL>();
  collapse_in_box<shape::QuadraticBSpline, integrator::MUSL>();
  collapse_in_box<shape::QuadraticBSpline, integrator::USF>();
  collapse_in_box<shape::CubicBSpline, integrator::MUSL>();
}
