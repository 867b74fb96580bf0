// The start-of-step correction (Nairn, Hammerquist and Smith 2020) by hand: one particle of
// mass M = 4 kg at the centre of a 1 m cell whose lower edge lies on a rigid floor, falling at
// u = 1 m/s under g = 10 m/s^2, stress-free, one USL step of dt = 0.01 s, no friction limit
// (no-slip would also hold it; Coulomb with mu = 0 keeps the check on the normal part).
//
// Linear shape functions: each of the cell's four nodes gets M/4 = 1 kg and velocity (0, -u);
// the two floor nodes are the contact nodes (the upper ones are a whole cell from the face).
//   without the correction: trial v = -u - g dt = -1.1, corrected to 0; force on the material
//     per floor node = 1 kg * 1.1 / 0.01 = 110 N, 220 N in total = M/2 (u/dt + g);
//   with it: start v = 0 on the floor nodes, trial v = -g dt = -0.1, corrected to 0; force
//     per node = 1 kg * 0.1 / 0.01 = 10 N, 20 N in total = M/2 g: the weight the floor nodes
//     carry, without the particle's incoming velocity.
// FLIP: the particle's velocity change is sum N_i (v_end - v_start): the floor nodes give
// 0.5 * (0 - (-u)) = +0.5 m/s without the correction, 0.5 * (0 - 0) = 0 with it; the upper
// nodes 0.5 * (-g dt) = -0.05 m/s in both. Its position moves by dt sum N_i v_end =
// 0.01 * 0.5 * (-1.1) = -5.5 mm in both.
#include <doctest/doctest.h>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

constexpr double u = 1.0;
constexpr double g = 10.0;
constexpr double dt = 0.01;
constexpr double particle_mass = 4.0;

struct FallingParticle {
  test::RigidSim sim;
  explicit FallingParticle(bool start_correction)
      : sim(grid::Grid<2>(Vec<2>(0.0, 0.0), Vec<2>(4.0, 4.0), {4, 4}),
            test::Elastic(test::youngs_modulus, test::poisson_ratio), parameters(),
            law(start_correction)) {
    // One particle of volume 1 m^2 at density 4 kg/m^3 at the centre of cell (1, 1).
    const std::vector<Vec<2>> position{Vec<2>(1.5, 1.5)};
    sim.add_particles(position, 1.0, particle_mass, Vec<2>(0.5, 0.5));
    sim.particles().get<particles::field::Velocity<2>>()[0] = Vec<2>(0.0, -u);
  }
  static SimulationParameters<2> parameters() {
    SimulationParameters<2> p;
    p.gravity = Vec<2>(0.0, -g);
    p.threads = 1;
    return p;
  }
  static contact::RigidContact<2> law(bool start_correction) {
    contact::RigidContact<2> rigid;
    // The floor's top face on the grid line y = 1.
    rigid.add_body(contact::RigidBody<2>::box(Vec<2>(0.2, 0.2), Vec<2>(3.8, 1.0)),
                   contact::Interface::coulomb(0.0));
    rigid.set_start_of_step_correction(start_correction);
    return rigid;
  }
};

}  // namespace

TEST_CASE("start-of-step contact: off by default, the paper's correction of the updated velocity") {
  FallingParticle fall(false);
  CHECK_FALSE(fall.sim.contact().corrects_start_of_step());
  fall.sim.step(dt);
  REQUIRE(fall.sim.contact().contact_nodes().size() == 2);
  for (const auto& node : fall.sim.contact().contact_nodes()) {
    CHECK(node.mass == doctest::Approx(1.0));
    CHECK(node.force_on_material[1] == doctest::Approx(110.0));
  }
  CHECK(fall.sim.contact().force_on_material(0)[1] == doctest::Approx(220.0));
  const auto& v = fall.sim.particles().get<particles::field::Velocity<2>>()[0];
  CHECK(v[1] == doctest::Approx(-u + 0.5 - 0.05));
  CHECK(fall.sim.particles().get<particles::field::Position<2>>()[0][1] ==
        doctest::Approx(1.5 - 0.0055));
}

TEST_CASE("start-of-step contact: the floor nodes start at rest, the force is the weight alone") {
  FallingParticle fall(true);
  CHECK(fall.sim.contact().corrects_start_of_step());
  fall.sim.step(dt);
  REQUIRE(fall.sim.contact().contact_nodes().size() == 2);
  for (const auto& node : fall.sim.contact().contact_nodes()) {
    CHECK(node.force_on_material[1] == doctest::Approx(10.0));
    CHECK(node.force_on_material[0] == doctest::Approx(0.0).epsilon(1e-12));
  }
  CHECK(fall.sim.contact().force_on_material(0)[1] == doctest::Approx(0.5 * particle_mass * g));
  // The start velocity the grid kept for the floor nodes is the corrected one.
  const Index floor_node = fall.sim.grid().node_index({1, 1});
  CHECK(fall.sim.nodes().momentum[static_cast<std::size_t>(floor_node)].norm() == 0.0);
  const auto& v = fall.sim.particles().get<particles::field::Velocity<2>>()[0];
  CHECK(v[1] == doctest::Approx(-u - 0.05));
  CHECK(fall.sim.particles().get<particles::field::Position<2>>()[0][1] ==
        doctest::Approx(1.5 - 0.0055));
}

TEST_CASE("start-of-step contact: a resting block's recorded force equals its weight at once") {
  // An elastic block at rest on the floor body: from the first step the force the floor
  // applies is close to the weight either way; with the correction it does not carry the
  // re-correction of the particles' FLIP velocity, so over 200 steps its mean is the weight
  // (within 2 %: the block's elastic oscillation averages out).
  for (const bool start_correction : {false, true}) {
    CAPTURE(start_correction);
    const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4), {20, 20});
    contact::RigidContact<2> law;
    law.add_body(contact::RigidBody<2>::box(Vec<2>(0.02, 0.02), Vec<2>(0.38, 0.1)),
                 contact::Interface::coulomb(0.3));
    law.set_start_of_step_correction(start_correction);
    SimulationParameters<2> parameters;
    parameters.gravity = Vec<2>(0.0, -9.81);
    parameters.threads = 1;
    test::RigidSim sim(grid, test::Elastic(test::youngs_modulus, test::poisson_ratio), parameters,
                       std::move(law));
    const auto seeding = particles::seed_box(grid, Vec<2>(0.1, 0.1), Vec<2>(0.3, 0.2), 2);
    test::add_at_rest(sim, seeding);
    const double weight = test::density * 0.2 * 0.1 * 9.81;
    const double step = sim.time_step();
    double sum = 0.0;
    constexpr int steps = 200;
    for (int i = 0; i < steps; ++i) {
      sim.step(step);
      sum += sim.contact().force_on_material(0)[1];
    }
    CHECK(sum / steps == doctest::Approx(weight).epsilon(0.02));
  }
}
