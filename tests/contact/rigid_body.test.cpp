// Geometry of rigid polygons (distances, normals on faces and around corners, motion) and the
// errors raised by bad contact input.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;
using contact::RigidBody;

// A thin blade like the flat blade's: 10 mm x 350 mm, lower-left corner at the origin.
RigidBody<2> blade() {
  return RigidBody<2>::box(Vec<2>(0.0, 0.0), Vec<2>(0.01, 0.35));
}

}  // namespace

TEST_CASE("rigid body: exact distance and face normal on the faces") {
  const RigidBody<2> b = blade();
  // Hand values: 5 mm in front of the front face (x = 0.01), at mid-height.
  const auto front = b.closest(Vec<2>(0.015, 0.2));
  CHECK(front.signed_distance == doctest::Approx(0.005));
  CHECK(front.edge == 1);
  CHECK(front.normal.isApprox(Vec<2>(1.0, 0.0)));
  CHECK(front.along == doctest::Approx(0.2));  // edge 1 runs upwards from (0.01, 0)
  // Inside, 1 mm behind the front face: negative distance, the nearest face's normal.
  const auto inside = b.closest(Vec<2>(0.009, 0.2));
  CHECK(inside.signed_distance == doctest::Approx(-0.001));
  CHECK(inside.normal.isApprox(Vec<2>(1.0, 0.0)));
  // Below the tip: the bottom face, normal -y.
  const auto tip = b.closest(Vec<2>(0.004, -0.003));
  CHECK(tip.signed_distance == doctest::Approx(0.003));
  CHECK(tip.normal.isApprox(Vec<2>(0.0, -1.0)));
}

TEST_CASE("rigid body: the normal turns continuously around the blade tip's corner") {
  // Around the corner (0.01, 0) at radius r the normal is (cos a, sin a) for a in the corner's
  // quadrant [-90, 0] deg, and the distance is r: no jump between the two faces.
  const RigidBody<2> b = blade();
  const Vec<2> corner(0.01, 0.0);
  const double r = 0.004;
  Vec<2> previous = Vec<2>(0.0, -1.0);
  for (int k = 0; k <= 90; ++k) {
    const double a = degrees_to_radians(-90.0 + k);
    const Vec<2> direction(std::cos(a), std::sin(a));
    const auto p = b.closest(corner + r * direction);
    CHECK(p.signed_distance == doctest::Approx(r));
    CHECK((p.normal - direction).norm() < 1e-9);
    // One-degree steps: consecutive normals differ by 2 sin(0.5 deg) = 0.01745.
    CHECK((p.normal - previous).norm() < 0.0175);
    previous = p.normal;
  }
}

TEST_CASE("rigid body: property test, x = closest point + signed distance * normal") {
  // Random points around a convex pentagon (fixed seed), clockwise input; the identity holds on
  // faces and around corners, and the normal is a unit vector.
  const std::vector<Vec<2>> pentagon = {Vec<2>(0.0, 1.0), Vec<2>(0.95, 0.31), Vec<2>(0.59, -0.81),
                                        Vec<2>(-0.59, -0.81), Vec<2>(-0.95, 0.31)};
  const RigidBody<2> b(pentagon, Vec<2>(0.3, -0.2));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 2000; ++i) {
    const Vec<2> x(0.3 + u(rng), -0.2 + u(rng));
    const auto p = b.closest(x);
    CHECK(std::abs(p.normal.norm() - 1.0) < 1e-12);
    CHECK((p.point + p.signed_distance * p.normal - x).norm() < 1e-12);
    CHECK((p.signed_distance < 0.0) == b.contains(x));
  }
}

TEST_CASE("rigid body: prescribed motion by the mid-step velocity, rotation about the reference") {
  // v(t) = (2 t, 0): over [0.1, 0.3] the exact travel is t^2 |_{0.1}^{0.3} = 0.08 m, which the
  // midpoint rule reproduces for a law linear in t.
  RigidBody<2> b = RigidBody<2>::box(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0));
  b.set_velocity([](double t) { return Vec<2>(2.0 * t, 0.0); });
  b.advance(0.2, 0.1);
  CHECK(b.reference_point()[0] == doctest::Approx(0.5 + 0.08));
  CHECK(b.vertices()[0].isApprox(Vec<2>(0.08, 0.0)));
  // A quarter turn about the centre (0.58, 0.5) in 1 s at pi/2 rad/s maps the lower-left
  // corner (0.08, 0) to the lower-right position (1.08, 0).
  b.set_velocity(Vec<2>(0.0, 0.0)).set_angular_velocity(pi / 2.0);
  b.advance(1.0, 0.3);
  CHECK((b.vertices()[0] - Vec<2>(1.08, 0.0)).norm() < 1e-12);
  // Material velocity at a point: omega x r; at the centre + (0.5, 0): (0, 0.5 omega).
  const Vec<2> v = b.velocity_at(b.reference_point() + Vec<2>(0.5, 0.0), Vec<2>::Zero(), 2.0);
  CHECK(v.isApprox(Vec<2>(0.0, 1.0)));
}

TEST_CASE("rigid body: the support test puts the face on one row of linear-kernel nodes") {
  // A floor whose top is the grid line y = 0 reaches the nodes on that line (support box
  // |y| < h) but not those one cell above (the open box (0, 2h) does not contain y = 0).
  const RigidBody<2> floor = RigidBody<2>::box(Vec<2>(-1.0, -1.0), Vec<2>(1.0, 0.0));
  const Vec<2> h(0.02, 0.02);
  CHECK(floor.meets_open_box(Vec<2>(0.1, 0.0), h));
  CHECK(floor.meets_open_box(Vec<2>(0.1, 0.0199), h));
  CHECK_FALSE(floor.meets_open_box(Vec<2>(0.1, 0.02), h));
  CHECK(floor.meets_open_box(Vec<2>(0.1, -0.5), h));  // deep inside: the centre is inside
  CHECK_FALSE(floor.meets_open_box(Vec<2>(1.02, 0.01), h));
}

TEST_CASE("contact: bad input raises cosmpm::Error") {
  using contact::Interface;
  CHECK_THROWS_AS(Interface::coulomb(-0.1), Error);
  CHECK_THROWS_AS(Interface::coulomb(std::nan("")), Error);
  CHECK_THROWS_AS(Interface::coulomb_angle(90.0), Error);
  CHECK_THROWS_AS(Interface::coulomb_angle(-1.0), Error);
  CHECK(Interface::coulomb_angle(45.0).friction_coefficient == doctest::Approx(1.0));
  Interface negative;
  negative.friction_coefficient = -0.2;  // set by hand, bypassing the factory
  contact::RigidContact<2> law;
  CHECK_THROWS_AS(law.add_body(blade(), negative), Error);
  // Degenerate polygons: too few vertices, collinear, a repeated vertex, a bow tie.
  CHECK_THROWS_AS(RigidBody<2>({Vec<2>(0, 0), Vec<2>(1, 0)}, Vec<2>::Zero()), Error);
  CHECK_THROWS_AS(RigidBody<2>({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(2, 0)}, Vec<2>::Zero()), Error);
  CHECK_THROWS_AS(
      RigidBody<2>({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 0), Vec<2>(0, 1)}, Vec<2>::Zero()),
      Error);
  CHECK_THROWS_AS(
      RigidBody<2>({Vec<2>(0, 0), Vec<2>(1, 1), Vec<2>(1, 0), Vec<2>(0, 1)}, Vec<2>::Zero()),
      Error);
  CHECK_THROWS_AS(RigidBody<2>::box(Vec<2>(0, 0), Vec<2>(0, 1)), Error);
  CHECK_THROWS_AS(blade().set_velocity(Vec<2>(std::nan(""), 0.0)), Error);
  CHECK_THROWS_AS(law.body(0), Error);  // no body yet
  CHECK_THROWS_AS(law.traction_profile(0, 0), Error);
}

TEST_CASE("contact: a rigid body outside the grid or with a broken velocity law stops the run") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4), {20, 20});
  const auto run_with = [&](contact::RigidBody<2> body) {
    contact::RigidContact<2> law;
    law.add_body(std::move(body), contact::Interface::coulomb(0.3));
    test::RigidSim sim(grid, test::Elastic(test::youngs_modulus, test::poisson_ratio), {}, law);
    test::add_at_rest(sim, particles::seed_box(grid, Vec<2>(0.1, 0.1), Vec<2>(0.2, 0.2), 2));
    sim.step(sim.time_step());
    CHECK_THROWS_AS(sim.contact().traction_profile(0, 4), Error);  // a box has edges 0..3
  };
  // Entirely to the right of the grid box [0, 0.4]^2 (a unit slip, say mm for m).
  CHECK_THROWS_AS(run_with(RigidBody<2>::box(Vec<2>(10.0, 0.1), Vec<2>(10.35, 0.3))), Error);
  CHECK_THROWS_AS(
      run_with(RigidBody<2>::box(Vec<2>(0.3, 0.1), Vec<2>(0.31, 0.3)).set_velocity([](double) {
        return Vec<2>(std::nan(""), 0.0);
      })),
      Error);
  CHECK_NOTHROW(run_with(RigidBody<2>::box(Vec<2>(0.3, 0.1), Vec<2>(0.31, 0.3))));
}
