// The Coulomb-friction wall condition on a face of the grid box: the nodal correction by hand,
// and a block sliding on a rough floor against the rigid-block solution.
#include <doctest/doctest.h>

#include <cmath>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/initial/geostatic.hpp"

namespace {
using namespace cosmpm;
using BC = grid::BoundaryConditions<2>;

Vec<2> corrected(int axis, bool upper, double mu, const Vec<2>& v) {
  Vec<2> out = v;
  BC::apply({grid::BoundaryKind::friction, mu}, axis, upper, out);
  return out;
}
}  // namespace

TEST_CASE("friction wall: no penetration, free separation, Coulomb slip and stick (by hand)") {
  // Floor (lower y face), mu = 0.4. Approach v_n = 0.5: the removed normal velocity bounds the
  // tangential reduction by mu v_n = 0.2.
  CHECK(corrected(1, false, 0.4, Vec<2>(1.0, -0.5)).isApprox(Vec<2>(0.8, 0.0)));
  CHECK(corrected(1, false, 0.4, Vec<2>(-1.0, -0.5)).isApprox(Vec<2>(-0.8, 0.0)));
  // |v_t| = 0.1 <= 0.2: stuck.
  CHECK(corrected(1, false, 0.4, Vec<2>(0.1, -0.5)) == Vec<2>(0.0, 0.0));
  // Separating (v_y > 0 at the floor): nothing imposed.
  CHECK(corrected(1, false, 0.4, Vec<2>(1.0, 0.3)) == Vec<2>(1.0, 0.3));
  // Right wall (upper x face): outward normal +x, v_n = 0.5, tangential along y.
  CHECK(corrected(0, true, 0.4, Vec<2>(0.5, 1.0)).isApprox(Vec<2>(0.0, 0.8)));
  // mu = 0 is a roller for approaching material.
  CHECK(corrected(1, false, 0.0, Vec<2>(1.0, -0.5)) == Vec<2>(1.0, 0.0));
}

TEST_CASE("friction wall: a block slides on a rough floor and stops as a rigid block would") {
  // Rigid-block solution: v(t) = v0 - mu g t until v0 / (mu g), distance v0^2 / (2 mu g).
  const double mu = 0.3, g = 9.81, v0 = 1.0, density = 1000.0;
  // MUSL: the block's front crosses cells into nodes of tiny mass, which USL's strain rate
  // amplifies (docs/theory/mpm.md, "Which to use").
  using Sim =
      Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::MUSL>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.2), {50, 10});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -g);
  parameters.threads = 1;
  Sim sim(grid, test::Elastic(1e6, 0.3), parameters);
  const double height = 0.06;
  const auto seeding = particles::seed_box(grid, Vec<2>(0.1, 0.0), Vec<2>(0.3, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  auto& x = sim.particles().get<particles::field::Position<2>>();
  auto& v = sim.particles().get<particles::field::Velocity<2>>();
  auto& stress = sim.particles().get<particles::field::Stress<test::Elastic>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    v[p] = Vec<2>(v0, 0.0);
    // At rest vertically from the start (no lateral stress: the block's sides are free).
    stress[p] = initial::geostatic_stress(density, g, height - x[p][1], 0.0);
  }
  sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::friction, mu);
  const auto mean_velocity = [&] {
    return test::total_momentum(sim)[0] / (density * 0.2 * height);
  };
  const auto mean_x = [&] {
    double sum = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) sum += x[p][0];
    return sum / static_cast<double>(sim.particles().size());
  };
  const double x_start = mean_x();
  const double dt = sim.time_step();
  while (sim.time() < 0.15) sim.step(dt);
  // Decelerating at mu g: tolerance 2 % of v0 (the block's elastic response and the discrete
  // contact at the bottom row of nodes).
  CHECK(mean_velocity() == doctest::Approx(v0 - mu * g * sim.time()).epsilon(0.02 / 0.56));
  while (sim.time() < 0.6) sim.step(dt);
  CHECK(std::abs(mean_velocity()) < 0.01 * v0);  // at rest after v0 / (mu g) = 0.34 s
  CHECK(mean_x() - x_start == doctest::Approx(v0 * v0 / (2.0 * mu * g)).epsilon(0.03));
}
