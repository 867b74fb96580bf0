// The nodal correction of RigidContact<3> by hand: a single node of material on a rigid floor
// (the box [-1.5, 1.5]^2 x [-1, 0], top face z = 0, outward normal +z), one grid cell of 1 m,
// dt = 0.1 s, node mass 2 kg: the 2D correction.test.cpp with a tangential velocity that
// has both in-plane components.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

struct OneNode3 {
  grid::Grid<3> grid{Vec<3>(-2.0, -2.0, -2.0), Vec<3>(4.0, 4.0, 4.0), {4, 4, 4}};
  std::vector<double> mass = std::vector<double>(125, 0.0);
  std::vector<Vec<3>> velocity = std::vector<Vec<3>>(125, Vec<3>::Zero());
  Index node = grid.node_index({2, 2, 2});  // at the origin, on the floor's top face
  contact::RigidContact<3> law;

  OneNode3(const contact::Interface& interface, const Vec<3>& body_velocity,
           const Vec<3>& omega = Vec<3>::Zero()) {
    law.add_body(contact::RigidBody<3>::box(Vec<3>(-1.5, -1.5, -1.0), Vec<3>(1.5, 1.5, 0.0))
                     .set_velocity(body_velocity)
                     .set_angular_velocity(omega),
                 interface);
    mass[static_cast<std::size_t>(node)] = 2.0;
    mass[static_cast<std::size_t>(grid.node_index({2, 2, 3}))] = 4.0;  // material above
  }
  Vec<3> correct(const Vec<3>& trial) {
    velocity[static_cast<std::size_t>(node)] = trial;
    contact::GridView<3> view{grid, mass, velocity, 1e-12, 0.1, 0.0, contact::Phase::end_velocity};
    law.correct(view);
    return velocity[static_cast<std::size_t>(node)];
  }
};

}  // namespace

TEST_CASE("correction 3D: Coulomb slip along a diagonal reduces |v_t| by mu |v_n|") {
  // v = (1, 0.5, -1): v_n = -1, v_t = (1, 0.5, 0), |v_t| = sqrt(1.25) = 1.1180 > mu |v_n| = 0.5
  // -> v_t (1 - 0.5 / 1.1180) = (0.55279, 0.27639, 0), the slip keeping its direction.
  OneNode3 one(contact::Interface::coulomb(0.5), Vec<3>::Zero());
  const double keep = 1.0 - 0.5 / std::sqrt(1.25);
  CHECK(one.correct(Vec<3>(1.0, 0.5, -1.0)).isApprox(Vec<3>(keep, 0.5 * keep, 0.0)));
  REQUIRE(one.law.contact_nodes().size() == 1);
  const auto& r = one.law.contact_nodes()[0];
  CHECK(r.state == contact::NodeState::slip);
  CHECK(r.normal.isApprox(Vec<3>::UnitZ()));
  // m (v_new - v) / dt = 2 (keep - 1, 0.5 (keep - 1), 1) / 0.1 = (-8.944, -4.472, 20) N:
  // normal 20 N, shear magnitude 10 N = mu * normal.
  const Vec<3> force(20.0 * (keep - 1.0), 10.0 * (keep - 1.0), 20.0);
  CHECK(r.force_on_material.isApprox(force));
  CHECK(r.normal_force == doctest::Approx(20.0));
  CHECK((r.force_on_material - r.normal_force * r.normal).norm() == doctest::Approx(10.0));
  // The top face is face 2 (as the 2D box's top edge); its u axis runs along -x, so the shear
  // along u is +8.944 N; the foot point (0, 0, 0) is (u, v) = (1.5, 1.5) from the face's
  // first vertex (1.5, -1.5, 0).
  CHECK(r.edge == 2);
  CHECK(r.tangent.isApprox(-Vec<3>::UnitX()));
  CHECK(r.shear_force == doctest::Approx(-force[0]));
  CHECK(r.along == doctest::Approx(1.5));
  CHECK(r.across == doctest::Approx(1.5));
  CHECK(one.law.force_on_body(0).isApprox(-force));
}

TEST_CASE("correction 3D: stick, free separation, no-slip and the fixed interface") {
  OneNode3 stick(contact::Interface::coulomb(2.0), Vec<3>::Zero());
  CHECK(stick.correct(Vec<3>(1.0, -1.0, -1.0)).isZero());  // |v_t| = 1.414 <= 2 * 1
  CHECK(stick.law.contact_nodes()[0].state == contact::NodeState::stick);
  CHECK(stick.correct(Vec<3>(1.0, -1.0, 1.0)).isApprox(Vec<3>(1.0, -1.0, 1.0)));  // separating
  CHECK(stick.law.force_on_material(0).isZero());
  OneNode3 glued(contact::Interface::no_slip(), Vec<3>(0.3, 0.0, 0.0));
  CHECK(glued.correct(Vec<3>(1.0, 1.0, 1.0)).isApprox(Vec<3>(0.3, 0.0, 0.0)));
  // Fixed: the node on the face (its control volume straddles the surface) moves with the
  // body; a node a cell above does not.
  OneNode3 fixed(contact::Interface::fixed(), Vec<3>(0.3, 0.0, 0.0));
  const Index above = fixed.grid.node_index({2, 2, 3});
  fixed.velocity[static_cast<std::size_t>(above)] = Vec<3>(1.0, 1.0, 1.0);
  CHECK(fixed.correct(Vec<3>(1.0, 1.0, 1.0)).isApprox(Vec<3>(0.3, 0.0, 0.0)));
  CHECK(fixed.velocity[static_cast<std::size_t>(above)].isApprox(Vec<3>(1.0, 1.0, 1.0)));
}

TEST_CASE("correction 3D: relative to a body turning about a horizontal axis") {
  // Floor moving at (0, 0.2, 0) and turning at omega = (0.4, 0, 0) about its reference point
  // (0, 0, -0.5): at the node, omega x r = (0.4, 0, 0) x (0, 0, 0.5) = (0, -0.2, 0), so the
  // body's material there is at rest and the correction is the still floor's.
  OneNode3 turning(contact::Interface::coulomb(0.5), Vec<3>(0.0, 0.2, 0.0), Vec<3>(0.4, 0, 0));
  const double keep = 1.0 - 0.5 / std::sqrt(1.25);
  CHECK(turning.correct(Vec<3>(1.0, 0.5, -1.0)).isApprox(Vec<3>(keep, 0.5 * keep, 0.0)));
}

TEST_CASE("correction 3D: a wall's imposed component takes no part in the slip") {
  // The node on the floor also lies on a grid face x = const that will impose v_x (view.held,
  // bit 0). v = (1, 0.5, -1): the slip is (0, 0.5) alone, 0.5 <= mu |v_n| = 0.5: stick, so
  // v_y = 0 and v_x is left to the wall (1 here). Without the wall: slip (1, 0.5), |v_t| =
  // 1.118 > 0.5 -> v_y = 0.5 (1 - 0.5 / 1.118) = 0.276 (the first case).
  OneNode3 one(contact::Interface::coulomb(0.5), Vec<3>::Zero());
  std::vector<unsigned char> held(one.mass.size(), 0);
  held[static_cast<std::size_t>(one.node)] = 1u;
  one.velocity[static_cast<std::size_t>(one.node)] = Vec<3>(1.0, 0.5, -1.0);
  contact::GridView<3> view{
      one.grid, one.mass, one.velocity, 1e-12, 0.1, 0.0, contact::Phase::end_velocity};
  view.held = held;
  one.law.correct(view);
  CHECK(one.velocity[static_cast<std::size_t>(one.node)].isApprox(Vec<3>(1.0, 0.0, 0.0)));
  CHECK(one.law.contact_nodes()[0].state == contact::NodeState::stick);
  // A wall along the normal (z held) leaves the correction to conditions_applied.
  held[static_cast<std::size_t>(one.node)] = 4u;
  one.velocity[static_cast<std::size_t>(one.node)] = Vec<3>(1.0, 0.5, -1.0);
  one.law.correct(view);
  const double keep = 1.0 - 0.5 / std::sqrt(1.25);
  CHECK(one.velocity[static_cast<std::size_t>(one.node)].isApprox(Vec<3>(keep, 0.5 * keep, 0)));
}

TEST_CASE("correction 3D: the traction map of a face sums to the body's force") {
  OneNode3 one(contact::Interface::coulomb(0.5), Vec<3>::Zero());
  one.correct(Vec<3>(1.0, 0.5, -1.0));
  const auto patches = one.law.traction_map(0, 2);
  // Face 2 spans (u, v) in [0, 3]^2; unit patches centred on the grid lines crossing it
  // (u, v = 0.5, 1.5, 2.5, 3.5): 4 x 4, the node's patch centred on its foot point.
  REQUIRE(patches.size() == 16);
  Vec<3> total = Vec<3>::Zero();
  int pressing = 0;
  for (const auto& patch : patches) {
    CHECK(patch.size.isApprox(Vec<2>(1.0, 1.0)));
    const auto& shape = one.law.body(0).shape();
    total -= patch.normal_traction * shape.face_normal(2) * patch.size.prod();
    total += (patch.shear_traction[0] * shape.face_tangent(2) +
              patch.shear_traction[1] * shape.face_bitangent(2)) *
             patch.size.prod();
    if (patch.nodes > 0) {
      ++pressing;
      CHECK(patch.centre.isApprox(Vec<2>(1.5, 1.5)));
      CHECK(patch.normal_traction == doctest::Approx(20.0));  // 20 N on 1 m^2
    }
  }
  CHECK(pressing == 1);
  CHECK(total.isApprox(one.law.force_on_body(0)));
}

TEST_CASE("correction 3D: a Cosserat rotation condition is refused, naming the valid one") {
  contact::RigidContact<3> law;
  const auto box = contact::RigidBody<3>::box(Vec<3>(0, 0, 0), Vec<3>(1, 1, 1));
  try {
    law.add_body(box, contact::Interface::coulomb(0.3).with_rotation_held());
    FAIL("held rotation accepted in 3D");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("is held (valid: free") != std::string::npos);
  }
  OneNode3 one(contact::Interface::coulomb(0.5), Vec<3>::Zero());
  try {
    (void)one.law.traction_map(0, 6);
    FAIL("face 6 of a box accepted");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("face = 6 is outside the valid range [0, 5]") !=
          std::string::npos);
  }
}
