// The nodal correction of RigidContact by hand: a single node of material on a rigid floor
// (face y = 0, outward normal +y), one grid cell of 1 m, dt = 0.1 s, node mass 2 kg.
#include <doctest/doctest.h>

#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

struct OneNode {
  grid::Grid<2> grid{Vec<2>(-2.0, -2.0), Vec<2>(4.0, 4.0), {4, 4}};
  std::vector<double> mass = std::vector<double>(25, 0.0);
  std::vector<Vec<2>> velocity = std::vector<Vec<2>>(25, Vec<2>::Zero());
  std::vector<double> spin = std::vector<double>(25, 0.0);
  Index node = grid.node_index({2, 2});  // at the origin, on the floor's face
  contact::RigidContact<2> law;

  OneNode(const contact::Interface& interface, const Vec<2>& body_velocity, double omega = 0.0) {
    // Floor [-1.5, 1.5] x [-1, 0], reference point (0, -0.5).
    law.add_body(contact::RigidBody<2>::box(Vec<2>(-1.5, -1.0), Vec<2>(1.5, 0.0))
                     .set_velocity(body_velocity)
                     .set_angular_velocity(omega),
                 interface);
    mass[static_cast<std::size_t>(node)] = 2.0;
    // Material above the node, so the mass grows upwards (away from the floor).
    mass[static_cast<std::size_t>(grid.node_index({2, 3}))] = 4.0;
  }
  // Particles for the gap check (none unless a test adds them).
  std::vector<Vec<2>> particles;
  std::vector<Vec<2>> half_widths;

  contact::GridView<2> view() {
    contact::GridView<2> v{grid, mass, velocity, 1e-12, 0.1, 0.0, contact::Phase::end_velocity,
                           spin, 1.0};
    v.particle_positions = particles;
    v.particle_half_widths = half_widths;
    return v;
  }
  Vec<2> correct(const Vec<2>& trial) {
    velocity[static_cast<std::size_t>(node)] = trial;
    auto v = view();
    law.correct(v);
    return velocity[static_cast<std::size_t>(node)];
  }
  // A face condition on the node (the floor's face y = 0 here), then the law's look at it.
  void condition(grid::BoundaryKind kind, int axis = 1, double wall_friction = 0.0) {
    grid::BoundaryConditions<2> conditions;
    conditions.set(grid::BoundaryConditions<2>::face(axis, false), kind, wall_friction);
    std::vector<unsigned char> imposed(velocity.size(), 0);
    const unsigned components = grid::BoundaryConditions<2>::apply(
        conditions[grid::BoundaryConditions<2>::face(axis, false)], axis, false,
        velocity[static_cast<std::size_t>(node)]);
    imposed[static_cast<std::size_t>(node)] = static_cast<unsigned char>(components);
    auto v = view();
    v.imposed = imposed;
    law.conditions_applied(v);
  }
};

}  // namespace

TEST_CASE("correction: Coulomb slip reduces the tangential velocity by mu |v_n|") {
  // v = (1, -1): v_n = -1 (approach), v_t = 1 > mu |v_n| = 0.5 -> v = (1 - 0.5, 0) = (0.5, 0).
  OneNode one(contact::Interface::coulomb(0.5), Vec<2>::Zero());
  CHECK(one.correct(Vec<2>(1.0, -1.0)).isApprox(Vec<2>(0.5, 0.0)));
  REQUIRE(one.law.contact_nodes().size() == 1);
  const auto& r = one.law.contact_nodes()[0];
  CHECK(r.state == contact::NodeState::slip);
  CHECK(r.normal.isApprox(Vec<2>(0.0, 1.0)));
  // Force on the material m (v_new - v) / dt = 2 (-0.5, 1) / 0.1 = (-10, 20) N; the normal
  // part 20 N pushes, the shear part along the top edge's tangent (-x, edge 2 runs from the
  // upper-right to the upper-left corner) is +10 N; Coulomb: |shear| = mu * normal.
  CHECK(r.edge == 2);
  CHECK(r.force_on_material.isApprox(Vec<2>(-10.0, 20.0)));
  CHECK(r.normal_force == doctest::Approx(20.0));
  CHECK(r.shear_force == doctest::Approx(10.0));
  CHECK(one.law.force_on_body(0).isApprox(Vec<2>(10.0, -20.0)));
}

TEST_CASE("correction: stick when |v_t| <= mu |v_n|, free separation, no-slip") {
  OneNode stick(contact::Interface::coulomb(2.0), Vec<2>::Zero());
  CHECK(stick.correct(Vec<2>(1.0, -1.0)).isZero());  // 1 <= 2 * 1: stuck to the floor
  CHECK(stick.law.contact_nodes()[0].state == contact::NodeState::stick);
  // Separating (v_n = +1): untouched, zero force.
  CHECK(stick.correct(Vec<2>(1.0, 1.0)).isApprox(Vec<2>(1.0, 1.0)));
  CHECK(stick.law.force_on_material(0).isZero());
  CHECK(stick.law.contact_nodes()[0].state == contact::NodeState::separating);
  // No-slip: the body's velocity whatever the material does, separating included.
  OneNode glued(contact::Interface::no_slip(), Vec<2>(0.3, 0.0));
  CHECK(glued.correct(Vec<2>(1.0, 1.0)).isApprox(Vec<2>(0.3, 0.0)));
}

TEST_CASE("correction: relative to a moving and rotating body") {
  // Floor moving at (0.2, 0) and turning at omega = 0.4 rad/s about (0, -0.5): at the node
  // (0, 0) the body's material moves at (0.2, 0) + 0.4 * (-0.5, 0) = (0, 0). Taking
  // omega = 0 instead, V = (0.2, 0): v = (1, -1) relative (0.8, -1), slip with mu = 0.5 ->
  // relative (0.8 - 0.5, 0) -> v = (0.5, 0).
  OneNode moving(contact::Interface::coulomb(0.5), Vec<2>(0.2, 0.0));
  CHECK(moving.correct(Vec<2>(1.0, -1.0)).isApprox(Vec<2>(0.5, 0.0)));
  OneNode turning(contact::Interface::coulomb(0.5).with_rotation_held(), Vec<2>(0.2, 0.0), 0.4);
  // Relative (1, -1) as for the still floor -> (0.5, 0).
  CHECK(turning.correct(Vec<2>(1.0, -1.0)).isApprox(Vec<2>(0.5, 0.0)));
  // The Cosserat spin of a node in contact is held at the body's angular velocity.
  CHECK(turning.spin[static_cast<std::size_t>(turning.node)] == doctest::Approx(0.4));
}

TEST_CASE("correction: the recorded force is what the node received after the conditions") {
  // Slip as in the first case: corrected velocity (0.5, 0), force on the material (-10, 20) N.
  OneNode fixed(contact::Interface::coulomb(0.5), Vec<2>::Zero());
  fixed.correct(Vec<2>(1.0, -1.0));
  REQUIRE(fixed.law.force_on_material(0).isApprox(Vec<2>(-10.0, 20.0)));
  // A fixed face then holds the node at rest: the face took the node, the body applied
  // nothing there, in the record, its normal and shear parts and the body's total.
  fixed.condition(grid::BoundaryKind::fixed);
  CHECK(fixed.law.contact_nodes()[0].force_on_material.isZero());
  CHECK(fixed.law.contact_nodes()[0].normal_force == 0.0);
  CHECK(fixed.law.contact_nodes()[0].shear_force == 0.0);
  CHECK(fixed.law.force_on_material(0).isZero());
  // A roller on a face normal to x (as if the node were on a side wall) imposes only x: the
  // floor's normal (y) part stays.
  OneNode roller(contact::Interface::coulomb(0.5), Vec<2>::Zero());
  roller.correct(Vec<2>(1.0, -1.0));
  roller.condition(grid::BoundaryKind::roller, 0);
  CHECK(roller.law.force_on_material(0).isApprox(Vec<2>(0.0, 20.0)));
  CHECK(roller.law.contact_nodes()[0].normal_force == doctest::Approx(20.0));
  // A free face imposes nothing: the record is unchanged.
  OneNode free(contact::Interface::coulomb(0.5), Vec<2>::Zero());
  free.correct(Vec<2>(1.0, -1.0));
  free.condition(grid::BoundaryKind::free);
  CHECK(free.law.force_on_material(0).isApprox(Vec<2>(-10.0, 20.0)));
}

TEST_CASE("correction: a body pushing material along a friction wall overcomes its friction") {
  // The blade's tip on a rough floor, turned on its side: the body moves up at 1 m/s (normal
  // +y at the node), a friction wall on the face x = min (outward normal -x, mu_w = 0.5).
  OneNode tip(contact::Interface::coulomb(0.5), Vec<2>(0.0, 1.0));
  // Trial (-1, 0.2): v_rel = (-1, -0.8), approach 0.8, |v_t| = 1 > mu 0.8 = 0.4: slip to
  // (1, 1) + (1 - 0.4) (-1, 0) = (-0.6, 1); force on the material 2 (0.4, 0.8) / 0.1 = (8, 16).
  CHECK(tip.correct(Vec<2>(-1.0, 0.2)).isApprox(Vec<2>(-0.6, 1.0)));
  // The wall removes the approach 0.6 (its normal, x, imposed) and slows the tangential 1 by
  // mu_w 0.6 = 0.3 to 0.7: the material falls behind the body, which pushes it back to 1
  // through y. The body's force: its own 16 N plus 2 (0.3) / 0.1 = 6 N, the wall's friction
  // mu_w (2 (0.6) / 0.1 = 12 N); nothing in x, which the wall imposed.
  tip.condition(grid::BoundaryKind::friction, 0, 0.5);
  CHECK(tip.velocity[static_cast<std::size_t>(tip.node)].isApprox(Vec<2>(0.0, 1.0)));
  CHECK(tip.law.force_on_material(0).isApprox(Vec<2>(0.0, 22.0)));
  CHECK(tip.law.contact_nodes()[0].normal_force == doctest::Approx(22.0));
  // A fixed face imposes both components: it wins, the node stays at rest.
  OneNode held(contact::Interface::coulomb(0.5), Vec<2>(0.0, 1.0));
  held.correct(Vec<2>(-1.0, 0.2));
  held.condition(grid::BoundaryKind::fixed, 0);
  CHECK(held.velocity[static_cast<std::size_t>(held.node)].isZero());
  CHECK(held.law.force_on_material(0).isZero());
  // Material separating from the body that the wall then slows into it is pushed as well:
  // trial (-1, 1.5) separates (nothing corrected); the wall stops x (approach 1) and slows y
  // by 0.5 to 1.0, which is the body's speed: nothing to push.
  OneNode ahead(contact::Interface::coulomb(0.5), Vec<2>(0.0, 1.0));
  CHECK(ahead.correct(Vec<2>(-1.0, 1.5)) == Vec<2>(-1.0, 1.5));
  ahead.condition(grid::BoundaryKind::friction, 0, 0.5);
  CHECK(ahead.velocity[static_cast<std::size_t>(ahead.node)].isApprox(Vec<2>(0.0, 1.0)));
  CHECK(ahead.law.force_on_material(0).isZero());
  // With mu_w = 0.8 the wall slows it to 0.7: pushed back to 1, a force of 2 (0.3) / 0.1.
  OneNode slowed(contact::Interface::coulomb(0.5), Vec<2>(0.0, 1.0));
  slowed.correct(Vec<2>(-1.0, 1.5));
  slowed.condition(grid::BoundaryKind::friction, 0, 0.8);
  CHECK(slowed.velocity[static_cast<std::size_t>(slowed.node)].isApprox(Vec<2>(0.0, 1.0)));
  CHECK(slowed.law.force_on_material(0).isApprox(Vec<2>(0.0, 6.0)));
}

TEST_CASE("correction: node reach per kernel") {
  // Support radius of a node's basis function in cells.
  CHECK(contact::node_reach<shape::Linear>() == 1.0);
  CHECK(contact::node_reach<shape::GIMP>() == 1.0);
  CHECK(contact::node_reach<shape::QuadraticBSpline>() == 1.5);
  CHECK(contact::node_reach<shape::CubicBSpline>() == 2.0);
}

TEST_CASE("correction: the gap check corrects only material that reaches the body in the step") {
  // One particle a quarter cell wide (half-width 0.25 cells of 1 m) centred 0.75 m above the
  // floor's face: its gap is 0.75 - 0.25 = 0.5 m. dt = 0.1 s.
  OneNode one(contact::Interface::coulomb(2.0), Vec<2>::Zero());
  one.law.set_gap_check(true);
  CHECK(one.law.checks_gap());
  one.particles = {Vec<2>(0.25, 0.75)};
  one.half_widths = {Vec<2>(0.25, 0.25)};
  // v_n = -1 m/s closes 0.1 m of the 0.5 m gap: no contact, the velocity stays.
  CHECK(one.correct(Vec<2>(0.5, -1.0)).isApprox(Vec<2>(0.5, -1.0)));
  CHECK(one.law.contact_nodes()[0].state == contact::NodeState::separating);
  CHECK(one.law.force_on_material(0).isZero());
  // v_n = -6 m/s closes 0.6 m: it reaches the floor, stick (|v_t| = 0.5 <= 2 * 6).
  CHECK(one.correct(Vec<2>(0.5, -6.0)).isZero());
  CHECK(one.law.contact_nodes()[0].state == contact::NodeState::stick);
  // With a tolerance of 0.45 cells the slow approach counts (0.4 <= 0.45).
  one.law.set_gap_check(true, 0.45);
  CHECK(one.correct(Vec<2>(0.5, -1.0)).isZero());
  // A particle touching the face (gap 0) makes the node a contact node at any approach speed.
  one.law.set_gap_check(true);
  one.particles.push_back(Vec<2>(-0.25, 0.25));
  one.half_widths.push_back(Vec<2>(0.25, 0.25));
  CHECK(one.correct(Vec<2>(1e-3, -1e-3)).isZero());
  // Without the check the first particle alone is corrected at once: the support reaches it.
  OneNode plain(contact::Interface::coulomb(2.0), Vec<2>::Zero());
  plain.particles = {Vec<2>(0.25, 0.75)};
  plain.half_widths = {Vec<2>(0.25, 0.25)};
  CHECK(plain.correct(Vec<2>(0.5, -1.0)).isZero());
}

TEST_CASE("correction: the gap check refuses a view without particles and a bad tolerance") {
  OneNode one(contact::Interface::coulomb(0.5), Vec<2>::Zero());
  one.law.set_gap_check(true);
  CHECK_THROWS_AS(one.correct(Vec<2>(0.0, -1.0)), Error);
  CHECK_THROWS_AS(one.law.set_gap_check(true, -0.1), Error);
  CHECK_THROWS_AS(one.law.set_gap_check(true, 1.5), Error);
}
