// A contact law a user writes in one file of their own, joining the force phase before the
// momentum update (contact/concept.hpp): a penalty floor. Checked against a hand calculation
// of one step, and by the equilibrium it reaches under a resting block.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/contact/concept.hpp"

namespace {
using namespace cosmpm;

// A rigid floor at the grid's bottom face (y = origin): each node of the bottom row that holds
// material carries a spring of stiffness k (N/m per m of width), compressed by the node's
// downward motion since contact began and never stretched: the contact force k * penetration
// pushes the material up. Penetration is integrated from the node's start-of-step velocity.
struct PenaltyFloor {
  static constexpr const char* name() { return "penalty floor (test)"; }
  double stiffness = 0.0;
  std::vector<double> penetration;  // per node of the bottom row
  double total_force = 0.0;         // on the material in the last step, N/m

  void add_forces(contact::ForceView<2>& view) {
    const auto& g = view.grid;
    penetration.resize(static_cast<std::size_t>(g.nodes(0)), 0.0);
    total_force = 0.0;
    for (Index i = 0; i < g.nodes(0); ++i) {
      const Index n = g.node_index({i, 0});
      double& depth = penetration[static_cast<std::size_t>(i)];
      if (view.mass[n] <= view.empty_mass) {
        depth = 0.0;
        continue;
      }
      const double vy = view.momentum[n][1] / view.mass[n];
      depth = std::max(0.0, depth - view.dt * vy);
      view.force[n][1] += stiffness * depth;
      total_force += stiffness * depth;
    }
  }
  void advance(double, double) {}
};
static_assert(contact::ContactLaw<PenaltyFloor, 2> && contact::AddsForces<PenaltyFloor, 2>);

using Sim = Simulation<2, shape::Linear, test::ElasticContinuum, PenaltyFloor, integrator::USL>;

Sim make_block(double stiffness, const Vec<2>& velocity, double damping) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.3, 0.3), {15, 15});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.damping = damping;
  parameters.threads = 1;
  Sim sim(grid, test::Elastic(1e5, 0.3), parameters, PenaltyFloor{stiffness, {}, 0.0});
  const auto seeding = particles::seed_box(grid, Vec<2>(0.1, 0.0), Vec<2>(0.2, 0.1), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  for (auto& v : sim.particles().get<particles::field::Velocity<2>>()) v = velocity;
  using BC = grid::BoundaryConditions<2>;
  sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(0, true), grid::BoundaryKind::roller);
  return sim;
}

}  // namespace

TEST_CASE("contact: a penalty law's force enters the momentum update (hand calculation)") {
  const double k = 2e4;  // N/m per m of width
  Sim sim = make_block(k, Vec<2>(0.0, -0.05), 0.0);
  const double dt = sim.time_step();
  sim.step(dt);  // the floor's springs start to compress
  // The next step stage by stage, against the hand calculation at each bottom node:
  //   penetration' = max(0, penetration - dt v_start_y),  f_y' = f_y + k penetration',
  //   v_end = v_start + dt f' / m.
  const std::vector<double> before = sim.contact().penetration;
  sim.map_to_grid(true);
  const auto mass = sim.nodes().mass;
  const auto momentum = sim.nodes().momentum;
  const auto force = sim.nodes().force;
  sim.update_grid(dt);
  int contact_nodes = 0;
  for (Index i = 0; i < sim.grid().nodes(0); ++i) {
    const Index n = sim.grid().node_index({i, 0});
    if (mass[n] <= 0.0) continue;
    ++contact_nodes;
    const Vec<2> v_start = momentum[n] / mass[n];
    const double depth = std::max(0.0, before[static_cast<std::size_t>(i)] - dt * v_start[1]);
    CHECK(sim.contact().penetration[static_cast<std::size_t>(i)] == doctest::Approx(depth));
    CHECK(depth > 0.0);  // the block moves down onto the floor
    const Vec<2> expected = v_start + dt * (force[n] + Vec<2>(0.0, k * depth)) / mass[n];
    CHECK(sim.nodes().velocity[n][0] == doctest::Approx(expected[0]).epsilon(1e-12));
    CHECK(sim.nodes().velocity[n][1] == doctest::Approx(expected[1]).epsilon(1e-12));
  }
  CHECK(contact_nodes == 6);  // the block spans x = 0.1 ... 0.2: nodes 5 ... 10 carry mass
}

TEST_CASE("contact: a block comes to rest on the penalty floor, which then carries its weight") {
  const double k = 2e4;
  Sim sim = make_block(k, Vec<2>::Zero(), 0.2);
  const double dt = sim.time_step();
  const double weight = 1000.0 * 0.1 * 0.1 * 9.81;  // rho A g per m of width, N/m
  while (sim.time() < 2.0) sim.step(dt);
  // At rest: the springs carry the weight (sum of internal forces vanishes), to the residual
  // motion of the damped block (tolerance 0.5 %).
  CHECK(sim.contact().total_force == doctest::Approx(weight).epsilon(5e-3));
  // At rest: kinetic energy below 1e-5 of the block's potential energy scale m g h / 2.
  CHECK(test::kinetic_energy(sim) < 1e-5 * 0.5 * weight * 0.1);
  // The block sank by about weight / (k * contact nodes) at each node, far less than a cell.
  double deepest = 0.0;
  for (const double d : sim.contact().penetration) deepest = std::max(deepest, d);
  CHECK(deepest > 0.0);
  CHECK(deepest < 0.1 * sim.grid().cell_size()[1]);
}
