// A free elastic block (no gravity, free grid faces) pushed by a rigid wall moving at constant
// velocity: no particle centre ever enters the wall, and the recorded contact force equals the
// block's rate of change of momentum.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

constexpr double cell = 0.02;  // m

struct PushRun {
  double closest = INFINITY;   // smallest particle distance from the wall over the run
  double worst_balance = 0.0;  // max_step |F_contact - dP/dt| / max_step |F_contact|
  double largest_force = 0.0;  // N per m width
  double impulse_error = 0.0;  // |sum F dt - (P_end - P_0)| / |P_end - P_0|
  Vec<2> final_momentum = Vec<2>::Zero();
  double block_mass = 0.0;
  double profile_balance = 0.0;  // |sum traction * width - edge force| / |edge force|
  double energy_ratio = 0.0;     // max over the run of E / E_0 in the wall's frame
};

// Kinetic energy relative to the wall plus elastic strain energy 1/2 sigma : eps V (the
// stress starts at zero). In the frame of a wall moving at constant velocity the wall is
// still, so contact can only take energy out: E <= E_0 = 1/2 M |V|^2.
template <class Sim>
double energy_in_wall_frame(const Sim& sim, const Vec<2>& wall_velocity) {
  const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  const auto& s = sim.particles().template get<particles::field::Stress<test::Elastic>>();
  const auto& e = sim.particles().template get<particles::field::Strain<test::Elastic>>();
  const auto& vol = sim.particles().template get<particles::field::Volume>();
  double energy = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double work =
        s[p][0] * e[p][0] + s[p][1] * e[p][1] + s[p][2] * e[p][2] + 2.0 * s[p][3] * e[p][3];
    energy += 0.5 * m[p] * (v[p] - wall_velocity).squaredNorm() + 0.5 * work * vol[p];
  }
  return energy;
}

// Relative mismatch between the traction profile of the wall's front face (edge 1 of the box:
// normal +x, tangent +y), integrated over its bins, and the forces of the nodes on that edge.
double profile_mismatch(const contact::RigidContact<2>& law) {
  Vec<2> edge_force = Vec<2>::Zero();
  for (const auto& r : law.contact_nodes()) {
    if (r.edge == 1) edge_force += r.force_on_material;
  }
  double normal = 0.0;
  double shear = 0.0;
  for (const auto& bin : law.traction_profile(0, 1)) {
    normal += bin.normal_traction * bin.width;
    shear += bin.shear_traction * bin.width;
  }
  // Pressure on the wall = force on the material along +x; shear on the wall along +y = minus
  // the force on the material along +y.
  return (Vec<2>(normal, -shear) - edge_force).norm() / edge_force.norm();
}

// Block [0.2, 0.4] x [0.1, 0.3] (10 x 10 cells, 2 x 2 particles per cell); the wall's front
// face starts on the block's left face (the first particle centres are a quarter cell ahead) at x =
// 0.2 and moves with `velocity` for 300 steps (0.08 s: 0.04 m, two cells, at 0.5 m/s). `thickness`
// of the wall in cells.
template <class Kernel, class Scheme>
PushRun push(const Vec<2>& velocity, const contact::Interface& interface, double thickness,
             double flip_fraction) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.4), {50, 20});
  SimulationParameters<2> parameters;
  parameters.flip_fraction = flip_fraction;
  contact::RigidContact<2> law;
  const double face = 0.2;
  law.add_body(contact::RigidBody<2>::box(Vec<2>(face - thickness * cell, 0.05), Vec<2>(face, 0.35))
                   .set_velocity(velocity),
               interface);
  test::RigidSimOf<Kernel, Scheme> sim(
      grid, test::Elastic(test::youngs_modulus, test::poisson_ratio), parameters, law);
  test::add_at_rest(sim, particles::seed_box(grid, Vec<2>(0.2, 0.1), Vec<2>(0.4, 0.3), 2));
  const double dt = sim.time_step();
  PushRun run;
  run.block_mass = test::total_mass(sim);
  const Vec<2> p0 = test::momentum(sim);
  const double e0 = energy_in_wall_frame(sim, velocity);
  Vec<2> impulse = Vec<2>::Zero();
  double worst_mismatch = 0.0;
  for (int step = 0; step < 300; ++step) {
    const Vec<2> before = test::momentum(sim);
    sim.step(dt);
    const Vec<2> rate = (test::momentum(sim) - before) / dt;
    const Vec<2> force = sim.contact().force_on_material(0);
    impulse += dt * force;
    worst_mismatch = std::max(worst_mismatch, (force - rate).norm());
    run.largest_force = std::max(run.largest_force, force.norm());
    run.closest =
        std::min(run.closest, test::closest_particle_distance(sim, sim.contact().body(0)));
    run.energy_ratio = std::max(run.energy_ratio, energy_in_wall_frame(sim, velocity) / e0);
    if (force.norm() > 0.0) {
      run.profile_balance = std::max(run.profile_balance, profile_mismatch(sim.contact()));
    }
  }
  run.worst_balance = worst_mismatch / run.largest_force;
  run.final_momentum = test::momentum(sim);
  run.impulse_error =
      (impulse - (run.final_momentum - p0)).norm() / (run.final_momentum - p0).norm();
  return run;
}

}  // namespace

TEST_CASE("pushed block: no penetration, contact force = rate of change of momentum") {
  // With free faces and no gravity the only external force on the block is the contact force,
  // and the grid transfers conserve momentum (partition of unity), so the identity holds per
  // step to round-off for FLIP and PIC alike: tolerance 1e-9 of the largest force.
  const Vec<2> velocity(0.5, 0.0);
  for (double flip : {1.0, 0.0}) {
    CAPTURE(flip);
    const PushRun run = push<shape::Linear, integrator::MUSL>(
        velocity, contact::Interface::coulomb(0.3), 2.0, flip);
    CHECK(run.closest >= 0.0);  // no particle centre inside the wall at any step (zero penetration)
    CHECK(run.worst_balance < 1e-9);
    CHECK(run.impulse_error < 1e-9);
    CHECK(run.profile_balance < 1e-12);
    // The push is real and bounded: a block hit by a wall moving at V leaves with a mean
    // velocity between V (perfectly plastic impact) and 2 V (perfectly elastic: in the wall's
    // frame its speed cannot grow).
    const double mean_velocity = run.final_momentum[0] / run.block_mass;
    CAPTURE(mean_velocity);
    CHECK(mean_velocity >= 0.5);
    CHECK(mean_velocity <= 2.0 * 0.5);
  }
}

TEST_CASE("pushed block: oblique wall motion, the Coulomb friction drags the block along") {
  // Wall velocity (0.5, 0.3) m/s, mu = 0.4: the tangential force is bounded by mu times the
  // normal force over the run (impulses), and the identity F = dP/dt holds for both components.
  const PushRun run = push<shape::Linear, integrator::MUSL>(
      Vec<2>(0.5, 0.3), contact::Interface::coulomb(0.4), 2.0, 1.0);
  CHECK(run.closest >= 0.0);
  CHECK(run.worst_balance < 1e-9);
  CHECK(run.impulse_error < 1e-9);
  CHECK(run.final_momentum[1] > 0.0);  // dragged upwards by friction
  CHECK(run.final_momentum[1] <= 0.4 * run.final_momentum[0] * (1.0 + 1e-9));
}

TEST_CASE("pushed block: a wall thinner than a cell does not let the block through") {
  // The flat blade is 10 mm thick on 15 mm cells; here the wall is 0.3 cells thick, so nodes
  // inside and behind it see the block's mass and must take the face the block touches.
  for (double flip : {1.0, 0.0}) {
    CAPTURE(flip);
    const PushRun run = push<shape::Linear, integrator::MUSL>(
        Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 0.3, flip);
    CHECK(run.closest >= 0.0);
    CHECK(run.worst_balance < 1e-9);
  }
  // The block never touches the back face, so its motion must not depend on the thickness:
  // same run with a wall 2 cells thick, to round-off. (Taking the nearest face's normal at the
  // nodes inside and behind the thin wall instead, the two runs differ by 0.1 m/s in the mean
  // velocity and the energy in the wall's frame triples; checked by hand.)
  const PushRun thin = push<shape::Linear, integrator::MUSL>(
      Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 0.3, 1.0);
  const PushRun thick = push<shape::Linear, integrator::MUSL>(
      Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 2.0, 1.0);
  CHECK((thin.final_momentum - thick.final_momentum).norm() <= 1e-9 * thick.final_momentum.norm());
}

TEST_CASE("pushed block: contact does no work in the wall's frame") {
  // E <= E_0 (tolerance 1e-9 relative) for frictionless and frictional walls. The runs use
  // FLIP 0.99 with the linear kernel: pure FLIP there gains up to 15 % (V = 0.5 m/s) by itself
  // from cell-crossing noise, which PIC, FLIP 0.99 and GIMP all remove (with them the maximum
  // is below 0.96 E_0).
  for (double mu : {0.0, 0.3}) {
    CAPTURE(mu);
    for (double thickness : {0.3, 2.0}) {
      CAPTURE(thickness);
      const PushRun run = push<shape::Linear, integrator::MUSL>(
          Vec<2>(0.5, 0.0), contact::Interface::coulomb(mu), thickness, 0.99);
      CHECK(run.energy_ratio <= 1.0 + 1e-9);
    }
  }
  const PushRun gimp = push<shape::GIMP, integrator::USL>(
      Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 0.3, 1.0);
  CHECK(gimp.energy_ratio <= 1.0 + 1e-9);
}

TEST_CASE("pushed block: USF keeps the same guarantees (FLIP)") {
  // USF also corrects the start-of-step velocity it strains with; FLIP moves the particles by
  // the change from that corrected start, so the recorded end-of-step force is still the
  // whole impulse. (PIC would add the unrecorded start correction; see docs/theory/mpm.md.)
  const PushRun usf = push<shape::Linear, integrator::USF>(
      Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 0.3, 1.0);
  CHECK(usf.closest >= 0.0);
  CHECK(usf.worst_balance < 1e-9);
}

TEST_CASE("pushed block: USL with GIMP keeps the same guarantees") {
  // (USL with the linear kernel blows up when the block's stressed free corner crosses a grid
  // line, contact law or not; see inclined_plane.test.cpp.)
  const PushRun gimp = push<shape::GIMP, integrator::USL>(
      Vec<2>(0.5, 0.0), contact::Interface::coulomb(0.3), 0.3, 1.0);
  CHECK(gimp.closest >= 0.0);
  CHECK(gimp.worst_balance < 1e-9);
}
