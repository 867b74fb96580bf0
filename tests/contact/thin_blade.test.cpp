// A thin blade (0.67 cells thick, like the flat blade's 10 mm on 15 mm cells) driven into an
// elastic layer under gravity: the robustness the flat-blade case needs from the contact law.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

constexpr double cell = 0.015;      // m
constexpr double back = 0.10;       // blade's back face at the start, m
constexpr double thickness = 0.01;  // m
constexpr double tip = 0.075;       // m, half-way down the 0.15 m layer
constexpr double speed = 0.2;       // m/s

}  // namespace

TEST_CASE("thin blade in a layer: no penetration, positive draft, consistent traction profile") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.6, 0.3), {40, 20});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  contact::RigidContact<2> law;
  law.add_body(contact::RigidBody<2>::box(Vec<2>(back, tip), Vec<2>(back + thickness, 0.28))
                   .set_velocity(Vec<2>(speed, 0.0)),
               contact::Interface::coulomb_angle(14.0));  // the paper's corn on steel
  test::RigidSimOf<shape::Linear, integrator::MUSL> sim(
      grid, test::Elastic(test::youngs_modulus, test::poisson_ratio), parameters, law);
  sim.boundary_conditions().set(2, grid::BoundaryKind::fixed);   // floor
  sim.boundary_conditions().set(1, grid::BoundaryKind::roller);  // far wall
  // Soil in front of the blade only, from its front face to the far wall.
  test::add_at_rest(sim,
                    particles::seed_box(grid, Vec<2>(back + thickness, 0.0), Vec<2>(0.6, 0.15), 2));
  const double dt = sim.time_step();
  double closest = INFINITY;
  double draft_impulse = 0.0;
  int behind = 0;
  int tip_nodes = 0;
  const double end = 0.1;  // s: 20 mm of travel, 1.3 cells
  contact::TractionAverage average;
  std::vector<double> pressure_sum;  // by hand, for the average's check
  while (sim.time() < end) {
    sim.step(dt);
    if (sim.time() > 0.9 * end) {
      const auto profile = sim.contact().traction_profile(0, 1);
      average.add(profile);
      pressure_sum.resize(profile.size(), 0.0);
      for (std::size_t k = 0; k < profile.size(); ++k)
        pressure_sum[k] += profile[k].normal_traction;
    }
    const auto& blade = sim.contact().body(0);
    closest = std::min(closest, test::closest_particle_distance(sim, blade));
    // Particles above the tip must stay in front of the blade's back face.
    const auto& x = sim.particles().get<particles::field::Position<2>>();
    const double back_now = blade.lower_bound()[0];
    for (Index p = 0; p < sim.particles().size(); ++p) {
      if (x[p][1] > tip + cell && x[p][0] < back_now) ++behind;
    }
    if (sim.time() > 0.5 * end) draft_impulse += dt * sim.contact().force_on_material(0)[0];
    for (const auto& r : sim.contact().contact_nodes()) {
      if (r.edge == 0 && r.state != contact::NodeState::separating) ++tip_nodes;
    }
  }
  CHECK(closest >= 0.0);  // zero penetration of particle centres into the blade
  CHECK(behind == 0);
  CHECK(draft_impulse > 0.0);  // the blade pushes the soil along +x
  MESSAGE("mean draft over the second half: " << draft_impulse / (0.5 * end) << " N/m");
  MESSAGE("contact-node-steps on the tip face: " << tip_nodes);

  // The front face (edge 1, tangent +y from the tip) carries the draft: its bins integrate to
  // the nodal forces attributed to it, and the pressure is compressive where nodes press.
  const auto profile = sim.contact().traction_profile(0, 1);
  Vec<2> edge_force = Vec<2>::Zero();
  for (const auto& r : sim.contact().contact_nodes()) {
    if (r.edge == 1) edge_force += r.force_on_material;
  }
  double normal = 0.0;
  double shear = 0.0;
  for (const auto& bin : profile) {
    normal += bin.normal_traction * bin.width;
    shear += bin.shear_traction * bin.width;
    if (bin.nodes > 0) CHECK(bin.normal_traction >= 0.0);
    CHECK(bin.width == doctest::Approx(cell));
  }
  CHECK(normal == doctest::Approx(edge_force[0]).epsilon(1e-12));
  CHECK(-shear == doctest::Approx(edge_force[1]).epsilon(1e-12));

  // The time average over the last 10 % of the run is the mean of the step profiles; the back
  // face's bins sit elsewhere along their edge, so mixing them in is refused.
  const auto mean = average.mean();
  REQUIRE(mean.size() == pressure_sum.size());
  for (std::size_t k = 0; k < mean.size(); ++k) {
    CHECK(std::abs(mean[k].normal_traction - pressure_sum[k] / average.samples()) <=
          1e-12 * (1.0 + std::abs(mean[k].normal_traction)));
  }
  CHECK_THROWS_AS(average.add(sim.contact().traction_profile(0, 3)), Error);
}
