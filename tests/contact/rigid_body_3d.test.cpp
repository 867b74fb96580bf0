// The 3D rigid body (convex polyhedron): exact distances and normals against the closed-form
// distance of a box, separating-axis box tests against per-axis interval tests, prescribed
// motion, poses, and bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cosmpm/contact.hpp"

namespace {
using namespace cosmpm;
using Body = contact::RigidBody<3>;

// Closed-form signed distance of the box [lower, upper]: outside, the norm of the per-axis
// overshoot; inside, minus the smallest distance to a face.
double box_distance(const Vec<3>& x, const Vec<3>& lower, const Vec<3>& upper) {
  const Vec<3> centre = 0.5 * (lower + upper);
  const Vec<3> half = 0.5 * (upper - lower);
  const Vec<3> q = (x - centre).cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  return outside > 0.0 ? outside : q.maxCoeff();
}

void check_throws_with(const std::function<void()>& make, const std::string& text) {
  try {
    make();
    FAIL("no cosmpm::Error for: " << text);
  } catch (const Error& e) {
    CAPTURE(e.what());
    CHECK(std::string(e.what()).find(text) != std::string::npos);
  }
}

// A regular tetrahedron-like convex body given by hand (faces in mixed orientations).
Body tetrahedron() {
  return Body({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0, 0, 1)},
              {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 2, 3}}, Vec<3>::Zero());
}

}  // namespace

TEST_CASE("rigid body 3D: box faces, frames and exact distances on faces, edges and corners") {
  const Vec<3> lower(0.0, 0.0, 0.0);
  const Vec<3> upper(2.0, 1.0, 3.0);
  const Body box = Body::box(lower, upper);
  REQUIRE(box.face_count() == 6);
  // Faces 0-3 are the 2D box's edges (bottom, +x, top, -x), then -y and +y.
  const std::vector<Vec<3>> normals{-Vec<3>::UnitZ(), Vec<3>::UnitX(),  Vec<3>::UnitZ(),
                                    -Vec<3>::UnitX(), -Vec<3>::UnitY(), Vec<3>::UnitY()};
  for (int f = 0; f < 6; ++f) CHECK(box.face_normal(f).isApprox(normals[f]));
  // The +x face runs up its edge like the 2D blade's face (u = +z) and across the width
  // (v = +y); its first vertex is the lower corner (2, 0, 0).
  CHECK(box.face_tangent(1).isApprox(Vec<3>::UnitZ()));
  CHECK(box.shape().face_bitangent(1).isApprox(Vec<3>::UnitY()));
  // Off the +x face: distance 0.5, the face normal, (u, v) = (z, y) of the foot point.
  auto p = box.closest(Vec<3>(2.5, 0.3, 1.2));
  CHECK(p.signed_distance == doctest::Approx(0.5));
  CHECK(p.face == 1);
  CHECK_FALSE(p.on_rim);
  CHECK(p.normal.isApprox(Vec<3>::UnitX()));
  CHECK(p.on_face.isApprox(Vec<2>(1.2, 0.3)));
  // Outside the edge x = 2, z = 3: distance sqrt(0.3^2 + 0.4^2) = 0.5 along (0.6, 0, 0.8).
  p = box.closest(Vec<3>(2.3, 0.5, 3.4));
  CHECK(p.signed_distance == doctest::Approx(0.5));
  CHECK(p.on_rim);
  CHECK(p.normal.isApprox(Vec<3>(0.6, 0.0, 0.8)));
  // Outside the corner (2, 1, 3): offset (1, 2, 2), distance 3.
  p = box.closest(Vec<3>(3.0, 3.0, 5.0));
  CHECK(p.signed_distance == doctest::Approx(3.0));
  CHECK(p.normal.isApprox(Vec<3>(1.0, 2.0, 2.0) / 3.0));
  // Inside, nearest to the -y face (0.1 away).
  p = box.closest(Vec<3>(1.0, 0.1, 1.5));
  CHECK(p.signed_distance == doctest::Approx(-0.1));
  CHECK(p.face == 4);
  CHECK(p.point.isApprox(Vec<3>(1.0, 0.0, 1.5)));
  CHECK(box.contains(Vec<3>(1.0, 0.1, 1.5)));
  CHECK_FALSE(box.contains(Vec<3>(1.0, -0.1, 1.5)));
}

TEST_CASE("rigid body 3D: a box's x-z section is the 2D box's, bit for bit") {
  // The flat blade's box (face at 0.05 + 0.01 m, on a grid line to within 1e-17 m): whether
  // the node column a cell ahead is a contact node in the first cutting step depends on that
  // rounding (the step's force doubles), so a 3D slab follows the 2D run step for step only
  // with the same faces.
  const auto flat = contact::RigidBody<2>::box(Vec<2>(0.05, 0.0), Vec<2>(0.05 + 0.01, 0.35));
  const Body box = Body::box(Vec<3>(0.05, -0.01, 0.0), Vec<3>(0.05 + 0.01, 0.11, 0.35));
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(box.vertices()[k][0] == flat.vertices()[k][0]);
    CHECK(box.vertices()[k][2] == flat.vertices()[k][1]);
  }
}

TEST_CASE("rigid body 3D: property test against the closed-form box distance, 2000 points") {
  const Vec<3> lower(-0.3, 0.1, 0.2);
  const Vec<3> upper(0.5, 0.4, 1.0);
  // Turned about the reference point by a whole number of quarter turns about z the body is
  // again a box (x and y swapped about its centre): the rotation path is exercised too.
  Body turned = Body::box(lower, upper);
  turned.set_angular_velocity(Vec<3>(0.0, 0.0, 0.5 * M_PI));
  turned.advance(1.0, 0.0);  // a quarter turn
  const Vec<3> c = 0.5 * (lower + upper);
  const Vec<3> turned_half(0.5 * (upper[1] - lower[1]), 0.5 * (upper[0] - lower[0]),
                           0.5 * (upper[2] - lower[2]));
  const Body box = Body::box(lower, upper);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.5);
  for (int i = 0; i < 2000; ++i) {
    const Vec<3> x(coordinate(random), coordinate(random), coordinate(random));
    const auto p = box.closest(x);
    REQUIRE(p.signed_distance == doctest::Approx(box_distance(x, lower, upper)).epsilon(1e-12));
    // x = closest point + distance * normal outside; the point lies on the boundary.
    if (p.signed_distance > 0.0) CHECK((p.point + p.signed_distance * p.normal).isApprox(x));
    CHECK(std::abs(box_distance(p.point, lower, upper)) < 1e-12);
    const auto q = turned.closest(x);
    REQUIRE(q.signed_distance ==
            doctest::Approx(box_distance(x, c - turned_half, c + turned_half)).epsilon(1e-9));
  }
}

TEST_CASE("rigid body 3D: separating-axis box tests against per-axis intervals and by hand") {
  const Vec<3> lower(0.0, 0.0, 0.0);
  const Vec<3> upper(1.0, 2.0, 0.5);
  const Body box = Body::box(lower, upper);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-1.0, 3.0);
  std::uniform_real_distribution<double> size(0.01, 0.6);
  for (int i = 0; i < 2000; ++i) {
    const Vec<3> centre(coordinate(random), coordinate(random), coordinate(random));
    const Vec<3> half(size(random), size(random), size(random));
    bool overlap = true;  // the open query box meets the closed box iff every axis overlaps
    for (int d = 0; d < 3; ++d) {
      overlap = overlap && centre[d] - half[d] < upper[d] && centre[d] + half[d] > lower[d];
    }
    REQUIRE(box.meets_open_box(centre, half) == overlap);
  }
  // Touching counts for a closed box, not an open one.
  CHECK_FALSE(box.meets_open_box(Vec<3>(1.5, 1.0, 0.25), Vec<3>(0.5, 0.1, 0.1)));
  CHECK(box.shape().boundary_meets_closed_box(Vec<3>(1.5, 1.0, 0.25), Vec<3>(0.5, 0.1, 0.1)));
  // A box deep inside the body does not straddle the surface; one across a face does.
  CHECK_FALSE(contact::straddles_surface(box, Vec<3>(0.5, 1.0, 0.25), Vec<3>(0.1, 0.1, 0.1)));
  CHECK(contact::straddles_surface(box, Vec<3>(0.5, 1.0, 0.45), Vec<3>(0.1, 0.1, 0.1)));
  // A diamond prism (square turned 45 deg about y): a query box by the vertex-free side of
  // its corner overlaps the bounding box but is separated by the face normal (1, 0, 1)/sqrt2.
  const Body diamond = Body::extruded_xz(
      {Vec<2>(1.0, 0.0), Vec<2>(0.0, 1.0), Vec<2>(-1.0, 0.0), Vec<2>(0.0, -1.0)}, -1.0, 1.0);
  CHECK_FALSE(diamond.meets_open_box(Vec<3>(0.8, 0.0, 0.8), Vec<3>(0.25, 0.25, 0.25)));
  CHECK(diamond.meets_open_box(Vec<3>(0.6, 0.0, 0.6), Vec<3>(0.25, 0.25, 0.25)));
  // A face test: the +x +z face of the diamond meets the box only by its own plane.
  const auto& shape = diamond.shape();
  int upper_right = -1;
  for (int f = 0; f < shape.face_count(); ++f) {
    if (shape.face_normal(f).isApprox(Vec<3>(1.0, 0.0, 1.0).normalized())) upper_right = f;
  }
  REQUIRE(upper_right >= 0);
  CHECK(diamond.face_meets_open_box(upper_right, Vec<3>(0.5, 0.0, 0.5), Vec<3>(0.1, 0.1, 0.1)));
  CHECK_FALSE(
      diamond.face_meets_open_box(upper_right, Vec<3>(0.3, 0.0, 0.3), Vec<3>(0.1, 0.1, 0.1)));
}

TEST_CASE("rigid body 3D: hand-made faces of either orientation, inclined blade normals") {
  const Body tet = tetrahedron();
  // Outward normals whatever the loops' orientation: -z, -y, -x and (1, 1, 1)/sqrt3.
  CHECK(tet.face_normal(0).isApprox(-Vec<3>::UnitZ()));
  CHECK(tet.face_normal(1).isApprox(-Vec<3>::UnitY()));
  CHECK(tet.face_normal(2).isApprox(-Vec<3>::UnitX()));
  CHECK(tet.face_normal(3).isApprox(Vec<3>::Ones().normalized()));
  CHECK(tet.signed_distance(Vec<3>(1.0, 1.0, 1.0)) == doctest::Approx(2.0 / std::sqrt(3.0)));
  CHECK(tet.signed_distance(Vec<3>(0.1, 0.2, 0.3)) == doctest::Approx(-0.1));
  // A blade raked 30 deg from the vertical: the parallelogram's front face has normal
  // (cos 30, 0, -sin 30), pointing forward and down, whatever the polygon's orientation.
  const double t = std::tan(degrees_to_radians(30.0));
  const std::vector<Vec<2>> rake{Vec<2>(0.0, 0.0), Vec<2>(0.02, 0.0), Vec<2>(0.02 + 0.3 * t, 0.3),
                                 Vec<2>(0.3 * t, 0.3)};
  const Body blade = Body::extruded_xz(rake, 0.0, 0.2);
  const Vec<3> front(std::cos(degrees_to_radians(30.0)), 0.0, -std::sin(degrees_to_radians(30.0)));
  CHECK(blade.face_normal(1).isApprox(front));
  const Body reversed = Body::extruded_xz({rake[3], rake[2], rake[1], rake[0]}, 0.0, 0.2);
  CHECK(reversed.face_normal(1).isApprox(front));  // side 1 lies on edge 2 -> 1 there
}

TEST_CASE("rigid body 3D: prescribed translation and rotation by the mid-step velocities") {
  Body box = Body::box(Vec<3>(-1.0, -1.0, -1.0), Vec<3>(1.0, 1.0, 1.0));
  box.set_velocity([](double time) { return Vec<3>(time, 0.0, 0.0); });
  box.set_angular_velocity(Vec<3>(0.0, 0.0, 0.1));
  box.advance(2.0, 0.0);  // mid-step velocity (1, 0, 0): x moves by 2; turned 0.2 rad about z
  CHECK(box.reference_point().isApprox(Vec<3>(2.0, 0.0, 0.0)));
  const Vec<3> corner =
      box.reference_point() + Eigen::AngleAxisd(0.2, Vec<3>::UnitZ()) * Vec<3>(1.0, -1.0, -1.0);
  bool found = false;
  for (const auto& v : box.vertices()) found = found || v.isApprox(corner, 1e-12);
  CHECK(found);
  // The body's material velocity: v + omega x r.
  CHECK(box.velocity_at(Vec<3>(2.0, 1.0, 0.0), Vec<3>(1.0, 0.0, 0.0), Vec<3>(0.0, 0.0, 0.1))
            .isApprox(Vec<3>(0.9, 0.0, 0.0)));
  // The pose round-trips bit for bit (checkpoints).
  Body copy = Body::box(Vec<3>(-1.0, -1.0, -1.0), Vec<3>(1.0, 1.0, 1.0));
  const auto pose = box.pose_values();
  REQUIRE(pose.size() == Body::pose_size);
  copy.set_pose_values(pose.data());
  for (std::size_t i = 0; i < box.vertices().size(); ++i) {
    CHECK(copy.vertices()[i] == box.vertices()[i]);
  }
}

TEST_CASE("rigid body 3D: bad input names the value and its valid range") {
  const auto cube = [] {
    std::vector<Vec<3>> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    return v;
  };
  const std::vector<std::vector<int>> cube_faces{{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                                 {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  CHECK_NOTHROW(Body(cube(), cube_faces, Vec<3>::Zero()));
  // Non-convex: vertex 7 pushed into the cube makes the faces through it non-planar or
  // dented; pulled in along the diagonal it dents three faces.
  check_throws_with(
      [&] {
        auto v = cube();
        v[7] = Vec<3>(0.6, 0.6, 0.6);
        Body(v, cube_faces, Vec<3>::Zero());
      },
      "off the plane of");
  // A dart: a square pyramid whose apex is pulled below its base is not convex.
  check_throws_with(
      [] {
        Body({Vec<3>(0, 0, 0), Vec<3>(2, 0, 0), Vec<3>(2, 2, 0), Vec<3>(0, 2, 0), Vec<3>(1, 1, 1),
              Vec<3>(1, 1, 0.5)},
             {{0, 1, 4}, {1, 2, 4}, {2, 3, 5}, {3, 0, 5}, {0, 5, 4}, {2, 5, 4}, {0, 3, 2, 1}},
             Vec<3>::Zero());
      },
      "must be convex");
  check_throws_with(
      [&] {
        auto faces = cube_faces;
        faces.pop_back();
        Body(cube(), faces, Vec<3>::Zero());
      },
      "belongs to 1 faces (valid: 2");
  check_throws_with(
      [&] {
        auto faces = cube_faces;
        faces[0][1] = 9;
        Body(cube(), faces, Vec<3>::Zero());
      },
      "names vertex 9 (valid range [0, 7])");
  check_throws_with(
      [] {
        Body({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(0, 1, 0)}, {{0, 1, 2}}, Vec<3>::Zero());
      },
      "3 vertices (valid range [4, inf))");
  check_throws_with(
      [] {
        // Four points in a plane: every "face" has no area or the body no volume.
        Body({Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), Vec<3>(1, 1, 0), Vec<3>(0, 1, 0)},
             {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}}, Vec<3>::Zero());
      },
      "valid range: volume > 0");
  check_throws_with([] { Body::box(Vec<3>(0, 0, 0), Vec<3>(1, -1, 1)); },
                    "upper corner -1 must exceed lower corner 0 along axis 1");
  check_throws_with(
      [] {
        Body::extruded_xz({Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(0, 1)}, 0.5, 0.5);
      },
      "y_upper 0.5 must exceed y_lower 0.5");
  check_throws_with(
      [] {
        Body b = Body::box(Vec<3>(0, 0, 0), Vec<3>(1, 1, 1));
        Mat<3> shear = Mat<3>::Identity();
        shear(0, 1) = 0.1;
        b.set_pose(Vec<3>::Zero(), shear);
      },
      "a proper rotation");
  check_throws_with(
      [] {
        Body b = Body::box(Vec<3>(0, 0, 0), Vec<3>(1, 1, 1));
        b.set_velocity([](double) { return Vec<3>(NAN, 0.0, 0.0); });
        b.advance(0.1, 0.0);
      },
      "velocity law returned a non-finite value");
}
