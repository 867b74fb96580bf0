// The Cosserat rotation conditions of RigidContact by hand (contact/wall_rotation.hpp): free,
// held at the nodes straddling the face, and the coupled grain-wall friction. A still floor
// [-1.5, 1.5] x [-1, face_y] (outward normal +y, so t = e_z x n = (-1, 0), which is also its
// top edge's tangent), cells of 1 m, dt = 0.1 s, node mass 2 kg, rotational inertia 0.5 kg m^2.
#include <doctest/doctest.h>

#include <vector>

#include "contact_test_support.hpp"
#include "cosmpm/contact/wall_rotation.hpp"

namespace {
using namespace cosmpm;

struct Floor {
  grid::Grid<2> grid{Vec<2>(-2.0, -2.0), Vec<2>(4.0, 4.0), {4, 4}};
  std::vector<double> mass = std::vector<double>(25, 0.0);
  std::vector<Vec<2>> velocity = std::vector<Vec<2>>(25, Vec<2>::Zero());
  std::vector<double> spin = std::vector<double>(25, 0.0);
  std::vector<double> inertia = std::vector<double>(25, 0.5);
  Index node = grid.node_index({2, 2});   // (0, 0)
  Index below = grid.node_index({2, 1});  // (0, -1)
  contact::RigidContact<2> law;

  explicit Floor(const contact::Interface& interface, double face_y = 0.0, double omega = 0.0) {
    law.add_body(contact::RigidBody<2>::box(Vec<2>(-1.5, -1.0), Vec<2>(1.5, face_y))
                     .set_angular_velocity(omega),
                 interface);
    mass[static_cast<std::size_t>(node)] = 2.0;
    // Material above, so the mass grows away from the floor.
    mass[static_cast<std::size_t>(grid.node_index({2, 3}))] = 4.0;
  }
  contact::GridView<2> view() {
    contact::GridView<2> v{grid, mass, velocity, 1e-12, 0.1, 0.0, contact::Phase::end_velocity,
                           spin, 1.0};
    v.rotational_inertia = inertia;
    return v;
  }
  void correct(const Vec<2>& trial, double trial_spin) {
    velocity[static_cast<std::size_t>(node)] = trial;
    spin[static_cast<std::size_t>(node)] = trial_spin;
    auto v = view();
    law.correct(v);
  }
  Vec<2> v() const { return velocity[static_cast<std::size_t>(node)]; }
  double w() const { return spin[static_cast<std::size_t>(node)]; }
  const contact::ContactNode<2>& record() const { return law.contact_nodes().at(0); }
};

}  // namespace

TEST_CASE("wall rotation: free leaves the spin, Coulomb acts on v_t alone") {
  // v = (1, -1), mu = 0.4: v_n = -1, |v_t| = 1 > 0.4 -> v = (0.6, 0); force 2 (-0.4, 1) / 0.1.
  Floor floor(contact::Interface::coulomb(0.4));
  floor.correct(Vec<2>(1.0, -1.0), 0.3);
  CHECK(floor.v().isApprox(Vec<2>(0.6, 0.0)));
  CHECK(floor.w() == 0.3);
  CHECK(floor.record().force_on_material.isApprox(Vec<2>(-8.0, 20.0)));
  CHECK(floor.record().moment_on_material == 0.0);
}

TEST_CASE("wall rotation: held sets the body's spin at a node on the face, with its moment") {
  // The floor turns at 0.4 rad/s; the node (0, 0) lies on its face: held at 0.4. The moment
  // the condition applied: I (0.4 - 0.3) / dt = 0.5 (0.1) / 0.1 = 0.5 N m.
  Floor floor(contact::Interface::coulomb(0.4).with_rotation_held(), 0.0, 0.4);
  floor.correct(Vec<2>(0.0, -1.0), 0.3);
  CHECK(floor.w() == doctest::Approx(0.4));
  CHECK(floor.record().moment_on_material == doctest::Approx(0.5));
  // Separating (v_n = +1): nothing held.
  floor.correct(Vec<2>(0.0, 1.0), 0.3);
  CHECK(floor.w() == 0.3);
  CHECK(floor.record().moment_on_material == 0.0);
}

TEST_CASE("wall rotation: held applies only at nodes straddling the face, not a cell ahead") {
  // Face at y = -0.6: the node (0, 0) is 0.6 m ahead, within its support (1 m) and so a contact
  // node, but its control volume [-0.5, 0.5]^2 does not reach the face: its spin stays. The
  // node (0, -1), 0.4 m inside, straddles the face ([-1.5, -0.5] holds -0.6): held at 0.
  Floor ahead(contact::Interface::coulomb(0.4).with_rotation_held(), -0.6);
  ahead.mass[static_cast<std::size_t>(ahead.below)] = 1.0;
  ahead.velocity[static_cast<std::size_t>(ahead.below)] = Vec<2>(0.0, -1.0);
  ahead.spin[static_cast<std::size_t>(ahead.below)] = 0.2;
  ahead.correct(Vec<2>(0.0, -1.0), 0.3);
  REQUIRE(ahead.law.contact_nodes().size() == 2);
  for (const auto& r : ahead.law.contact_nodes()) CHECK(r.state == contact::NodeState::stick);
  CHECK(ahead.w() == 0.3);
  CHECK(ahead.spin[static_cast<std::size_t>(ahead.below)] == 0.0);
  // Face at y = -0.5, on the border of both control volumes (closed boxes): both held.
  Floor border(contact::Interface::coulomb(0.4).with_rotation_held(), -0.5);
  border.mass[static_cast<std::size_t>(border.below)] = 1.0;
  border.velocity[static_cast<std::size_t>(border.below)] = Vec<2>(0.0, -1.0);
  border.spin[static_cast<std::size_t>(border.below)] = 0.2;
  border.correct(Vec<2>(0.0, -1.0), 0.3);
  CHECK(border.w() == 0.0);
  CHECK(border.spin[static_cast<std::size_t>(border.below)] == 0.0);
}

TEST_CASE("wall rotation: straddling a tilted face is the box test, |d| <= h/2 (|n_x| + |n_y|)") {
  // A triangle whose long edge runs from (2, -2) to (-2, 2): the line x + y = 0, normal
  // (1, 1)/sqrt(2). A unit box straddles it up to a distance 0.5 sqrt(2) = 0.707 m.
  const contact::RigidBody<2> wedge({Vec<2>(-2.0, -2.0), Vec<2>(2.0, -2.0), Vec<2>(-2.0, 2.0)},
                                    Vec<2>::Zero());
  const Vec<2> half(0.5, 0.5);
  const Vec<2> normal = Vec<2>(1.0, 1.0).normalized();
  CHECK(contact::straddles_surface(wedge, 0.70 * normal, half));
  CHECK_FALSE(contact::straddles_surface(wedge, 0.72 * normal, half));
  CHECK(contact::straddles_surface(wedge, -0.70 * normal, half));  // inside, near the face
  CHECK_FALSE(contact::straddles_surface(wedge, Vec<2>(-1.0, -1.0), half));  // deep inside
}

TEST_CASE("wall rotation: coupled, sliding, the friction moment turns the grain") {
  // r = 0.5 m, mu = 0.4, v = (1, -1), spin 0. v_n = -1, v_t = v . t = -1, slip s = v_t - r w
  // = -1. 1 / m_eff = 1/2 + 0.25/0.5 = 1: sticking needs P_t = -m_eff s = 1 > mu m |v_n| = 0.8,
  // so it slides with P_t = 0.8: v_t = -1 + 0.8/2 = -0.6, v = (0.6, 0); spin = -r P_t / I =
  // -0.8 (clockwise, rolling along +x). Force 2 (-0.4, 1) / 0.1 = (-8, 20) N (as plain
  // Coulomb), moment I (-0.8) / dt = -4 N m = -r F_t with F_t = F . t = 8 N.
  Floor floor(contact::Interface::coulomb(0.4).with_grain_rotation_coupled(0.5));
  floor.correct(Vec<2>(1.0, -1.0), 0.0);
  CHECK(floor.v().isApprox(Vec<2>(0.6, 0.0)));
  CHECK(floor.w() == doctest::Approx(-0.8));
  CHECK(floor.record().state == contact::NodeState::slip);
  CHECK(floor.record().force_on_material.isApprox(Vec<2>(-8.0, 20.0)));
  CHECK(floor.record().shear_force == doctest::Approx(8.0));
  CHECK(floor.record().moment_on_material == doctest::Approx(-4.0));
}

TEST_CASE("wall rotation: coupled, sticking, the grain rolls and half the shear is needed") {
  // mu = 2 (limit 4): P_t = 1 sticks: v_t = -1 + 1/2 = -0.5, v = (0.5, 0), spin = -0.5 (1) /
  // 0.5 = -1, so the contact point is at rest: s = -0.5 - 0.5 (-1) = 0. Force 2 (-0.5, 1) /
  // 0.1 = (-10, 20) N, half of plain Coulomb stick's (-20, 20); moment -r 10 = -5 N m.
  Floor floor(contact::Interface::coulomb(2.0).with_grain_rotation_coupled(0.5));
  floor.correct(Vec<2>(1.0, -1.0), 0.0);
  CHECK(floor.v().isApprox(Vec<2>(0.5, 0.0)));
  CHECK(floor.w() == doctest::Approx(-1.0));
  CHECK(floor.record().state == contact::NodeState::stick);
  CHECK(floor.record().force_on_material.isApprox(Vec<2>(-10.0, 20.0)));
  CHECK(floor.record().moment_on_material == doctest::Approx(-5.0));
  Floor plain(contact::Interface::coulomb(2.0));
  plain.correct(Vec<2>(1.0, -1.0), 0.0);
  CHECK(plain.record().force_on_material.isApprox(Vec<2>(-20.0, 20.0)));
  // A grain already rolling (spin -2: s = -1 - 0.5 (-2) = 0) keeps rolling, with no friction.
  floor.correct(Vec<2>(1.0, -1.0), -2.0);
  CHECK(floor.v().isApprox(Vec<2>(1.0, 0.0)));
  CHECK(floor.w() == doctest::Approx(-2.0));
  CHECK(floor.record().force_on_material.isApprox(Vec<2>(0.0, 20.0)));
  CHECK(floor.record().moment_on_material == doctest::Approx(0.0));
}

TEST_CASE("wall rotation: coupled relative to a turning body") {
  // The floor turns at Omega = 0.4 rad/s about its centre (0, -0.5): at the node its material
  // moves at V = 0.4 e_z x (0, 0.5) = (-0.2, 0). The law acts on v - V and spin - Omega:
  // trial v = V + (1, -1) and spin Omega reproduce the sliding case shifted by (V, Omega).
  Floor floor(contact::Interface::coulomb(0.4).with_grain_rotation_coupled(0.5), 0.0, 0.4);
  const Vec<2> body = floor.law.body(0).velocity_at(Vec<2>::Zero(), Vec<2>::Zero(), 0.4);
  CHECK(body.isApprox(Vec<2>(-0.2, 0.0)));
  floor.correct(body + Vec<2>(1.0, -1.0), 0.4);
  CHECK(floor.v().isApprox(body + Vec<2>(0.6, 0.0)));
  CHECK(floor.w() == doctest::Approx(0.4 - 0.8));
}

TEST_CASE("wall rotation: bad input names the value and where it came from") {
  CHECK_THROWS_WITH_AS(contact::Interface::coulomb(0.4).with_grain_rotation_coupled(0.0),
                       doctest::Contains("grain radius"), Error);
  CHECK_THROWS_AS(contact::Interface::coulomb(0.4).with_grain_rotation_coupled(-0.005), Error);
  // A no-slip interface has no friction for the grains to roll against.
  contact::Interface glued = contact::Interface::no_slip();
  glued.rotation = contact::Interface::Rotation::coupled;
  glued.grain_radius = 0.005;
  contact::RigidContact<2> law;
  CHECK_THROWS_AS(law.add_body(contact::RigidBody<2>::box(Vec<2>(0, 0), Vec<2>(1, 1)), glued),
                  Error);
  // A radius set by hand must still be positive.
  contact::Interface unsized = contact::Interface::coulomb(0.4);
  unsized.rotation = contact::Interface::Rotation::coupled;
  CHECK_THROWS_AS(law.add_body(contact::RigidBody<2>::box(Vec<2>(0, 0), Vec<2>(1, 1)), unsized),
                  Error);
  // The coupled law needs the rotational inertia (a Cosserat continuum's view).
  Floor floor(contact::Interface::coulomb(0.4).with_grain_rotation_coupled(0.5));
  floor.inertia.clear();
  CHECK_THROWS_WITH_AS(floor.correct(Vec<2>(1.0, -1.0), 0.0),
                       doctest::Contains("rotational inertias"), Error);
}
