#pragma once
// A 3D rigid body with prescribed motion: a convex polyhedron (convex_polyhedron.hpp) whose
// vertices are given relative to a reference point, translated with a prescribed velocity V(t)
// and rotated about the reference point with a prescribed angular velocity vector omega(t).
// Same interface as the 2D polygon (rigid_body.hpp) with faces for edges, so RigidContact and
// its records serve both.
//
//   auto blade = contact::RigidBody<3>::box({0.0, 0.0, 0.0}, {0.02, 0.1, 0.3});
//   blade.set_velocity(Vec<3>(0.01, 0.0, 0.0));
//   auto tine = contact::RigidBody<3>::extruded_xz({{0, 0.05}, {0.03, 0}, {0.03, 0.3},
//                                                   {0, 0.3}}, 0.04, 0.06);
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "cosmpm/contact/convex_polyhedron.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::contact {

template <>
class RigidBody<3> {
 public:
  using Point = FacePoint;
  using AngularVelocity = Vec<3>;
  using VelocityLaw = std::function<Vec<3>(double)>;
  using AngularVelocityLaw = std::function<Vec<3>(double)>;
  // Checkpoint values per body: the reference point, then the rotation matrix row by row.
  static constexpr int pose_size = 12;

  // `relative_vertices` relative to `reference_point`, the centre of rotation; each face a
  // loop of vertex indices. The polyhedron must be convex and closed.
  RigidBody(std::vector<Vec<3>> relative_vertices, std::vector<std::vector<int>> faces,
            const Vec<3>& reference_point)
      : shape_(std::move(relative_vertices), std::move(faces)), reference_(reference_point) {
    require(reference_.allFinite(), "contact::RigidBody<3>: reference point must be finite");
    shape_.place(reference_, rotation_);
  }

  // A convex polygon of the x-z plane ((x, z) vertices in order, either orientation; x along
  // the travel, z up) extruded across y in [y_lower, y_upper]: a blade of any rake angle or a
  // tine across the rig. Faces 0 .. n-1 are the sides on the polygon's edges (side k on edge
  // k, its u axis along the edge, its v axis along +y), then the y_lower (-y) and y_upper (+y)
  // ends. The reference point is the polygon's vertex mean at mid-width.
  static RigidBody extruded_xz(const std::vector<Vec<2>>& polygon_xz, double y_lower,
                               double y_upper) {
    const char* where = "contact::RigidBody<3>::extruded_xz";
    require(std::isfinite(y_lower) && std::isfinite(y_upper),
            std::string(where) + ": y range must be finite");
    if (!(y_upper > y_lower)) {
      throw Error(std::string(where) + ": y_upper " + detail::format_number(y_upper) +
                  " must exceed y_lower " + detail::format_number(y_lower) +
                  " (valid range (y_lower, inf))");
    }
    const auto n = static_cast<int>(polygon_xz.size());
    if (n < 3) {
      throw Error(std::string(where) + ": the polygon has " + std::to_string(n) +
                  " vertices (valid range [3, inf))");
    }
    Vec<2> mean = Vec<2>::Zero();
    for (const auto& p : polygon_xz) mean += p / static_cast<double>(n);
    std::vector<Vec<2>> relative;
    for (const auto& p : polygon_xz) relative.push_back(p - mean);
    return extrusion(relative, 0.5 * (y_upper - y_lower),
                     Vec<3>(mean[0], 0.5 * (y_lower + y_upper), mean[1]));
  }

  // The axis-aligned box [lower, upper]: the extruded rectangle, so faces 0-3 are the 2D
  // box's edges (0 bottom -z, 1 +x, 2 top +z, 3 -x), then 4 (-y) and 5 (+y).
  static RigidBody box(const Vec<3>& lower, const Vec<3>& upper) {
    require_box_corners("contact::RigidBody<3>::box", lower, upper);
    // Vertices at centre +- half, as RigidBody<2>::box: the same faces to the last bit.
    const Vec<3> centre = 0.5 * (lower + upper);
    const Vec<3> half = 0.5 * (upper - lower);
    return extrusion({Vec<2>(-half[0], -half[2]), Vec<2>(half[0], -half[2]),
                      Vec<2>(half[0], half[2]), Vec<2>(-half[0], half[2])},
                     half[1], centre);
  }

  // --- prescribed motion ----------------------------------------------------------------
  RigidBody& set_velocity(const Vec<3>& velocity) {
    require(velocity.allFinite(), "contact::RigidBody<3>::set_velocity: velocity must be finite");
    return set_velocity(VelocityLaw([velocity](double) { return velocity; }));
  }
  RigidBody& set_velocity(VelocityLaw law) {
    require(static_cast<bool>(law), "contact::RigidBody<3>::set_velocity: empty velocity law");
    velocity_ = std::move(law);
    return *this;
  }
  RigidBody& set_angular_velocity(const Vec<3>& omega) {
    require(omega.allFinite(), "contact::RigidBody<3>::set_angular_velocity: omega must be finite");
    return set_angular_velocity(AngularVelocityLaw([omega](double) { return omega; }));
  }
  RigidBody& set_angular_velocity(AngularVelocityLaw law) {
    require(static_cast<bool>(law), "contact::RigidBody<3>::set_angular_velocity: empty law");
    angular_velocity_ = std::move(law);
    return *this;
  }
  Vec<3> velocity(double time) const { return checked(velocity_(time), "velocity", time); }
  Vec<3> angular_velocity(double time) const {
    return checked(angular_velocity_(time), "angular velocity", time);
  }
  Vec<3> velocity_at(const Vec<3>& x, const Vec<3>& v, const Vec<3>& omega) const {
    return v + omega.cross(x - reference_);
  }

  // Moves the body over [time, time + dt] with the mid-step velocities: the translation is
  // exact for laws linear in time, the rotation exact for a constant axis (Rodrigues).
  void advance(double dt, double time) {
    const double mid = time + 0.5 * dt;
    reference_ += dt * velocity(mid);
    const Vec<3> turn = dt * angular_velocity(mid);
    const double angle = turn.norm();
    if (angle > 0.0) {
      const Eigen::AngleAxisd step(angle, turn / angle);
      rotation_ = step.toRotationMatrix() * rotation_;
      // Re-orthonormalise so round-off does not accumulate over millions of steps.
      const Eigen::Quaterniond q(rotation_);
      rotation_ = q.normalized().toRotationMatrix();
    }
    shape_.place(reference_, rotation_);
  }

  // Places the body (restarts): reference point and rotation from the input pose.
  void set_pose(const Vec<3>& reference_point, const Mat<3>& rotation) {
    require(reference_point.allFinite() && rotation.allFinite(),
            "contact::RigidBody<3>::set_pose: the pose must be finite");
    const double error = (rotation * rotation.transpose() - Mat<3>::Identity()).norm();
    if (!(error <= 1e-9) || rotation.determinant() <= 0.0) {
      throw Error("contact::RigidBody<3>::set_pose: |R R^T - I| = " + detail::format_number(error) +
                  " (valid range [0, 1e-9] with det R > 0: a proper rotation)");
    }
    reference_ = reference_point;
    rotation_ = rotation;
    shape_.place(reference_, rotation_);
  }
  std::vector<double> pose_values() const {
    std::vector<double> values(reference_.data(), reference_.data() + 3);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) values.push_back(rotation_(r, c));
    }
    return values;
  }
  void set_pose_values(const double* values) {
    Mat<3> rotation;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rotation(r, c) = values[3 + 3 * r + c];
    }
    set_pose(Vec<3>(values[0], values[1], values[2]), rotation);
  }

  // --- geometry (convex_polyhedron.hpp) -------------------------------------------------
  const Vec<3>& reference_point() const { return reference_; }
  const Mat<3>& rotation() const { return rotation_; }
  const ConvexPolyhedron& shape() const { return shape_; }
  const std::vector<Vec<3>>& vertices() const { return shape_.vertices(); }
  int face_count() const { return shape_.face_count(); }
  const Vec<3>& face_normal(int f) const { return shape_.face_normal(f); }
  const Vec<3>& face_tangent(int f) const { return shape_.face_tangent(f); }
  const Vec<3>& lower_bound() const { return shape_.lower_bound(); }
  const Vec<3>& upper_bound() const { return shape_.upper_bound(); }
  bool contains(const Vec<3>& x) const { return shape_.contains(x); }
  FacePoint closest(const Vec<3>& x) const { return shape_.closest(x); }
  FacePoint closest_on_face(const Vec<3>& x, int f, bool inside) const {
    return shape_.closest_on_face(x, f, inside);
  }
  double signed_distance(const Vec<3>& x) const { return closest(x).signed_distance; }
  bool face_meets_open_box(int f, const Vec<3>& centre, const Vec<3>& half) const {
    return shape_.face_meets_open_box(f, centre, half);
  }
  bool meets_open_box(const Vec<3>& centre, const Vec<3>& half) const {
    return shape_.meets_open_box(centre, half);
  }

 private:
  // The polygon (x, z relative to the reference point) extruded over y = +-half_width about it.
  static RigidBody extrusion(const std::vector<Vec<2>>& relative, double half_width,
                             const Vec<3>& reference) {
    const auto n = static_cast<int>(relative.size());
    std::vector<Vec<3>> vertices;
    for (const auto& p : relative) vertices.emplace_back(p[0], -half_width, p[1]);
    for (const auto& p : relative) vertices.emplace_back(p[0], half_width, p[1]);
    std::vector<std::vector<int>> faces;
    for (int k = 0; k < n; ++k) faces.push_back({k, (k + 1) % n, n + (k + 1) % n, n + k});
    std::vector<int> lower_end;
    std::vector<int> upper_end;
    for (int k = 0; k < n; ++k) {
      lower_end.push_back(k);
      upper_end.push_back(n + k);
    }
    faces.push_back(lower_end);
    faces.push_back(upper_end);
    return RigidBody(std::move(vertices), std::move(faces), reference);
  }

  static Vec<3> checked(const Vec<3>& value, const char* what, double time) {
    if (!value.allFinite()) {
      throw Error(std::string("contact::RigidBody<3>: the ") + what +
                  " law returned a non-finite value at t = " + detail::format_number(time) +
                  " s (valid range: finite)");
    }
    return value;
  }

  ConvexPolyhedron shape_;
  Vec<3> reference_;
  Mat<3> rotation_ = Mat<3>::Identity();
  VelocityLaw velocity_ = [](double) { return Vec<3>::Zero().eval(); };
  AngularVelocityLaw angular_velocity_ = [](double) { return Vec<3>::Zero().eval(); };
};

// Whether the body's boundary crosses the closed box |y - node| <= half_cell (per axis): the
// nodes a grid face's condition would hold (Interface::fixed).
inline bool straddles_surface(const RigidBody<3>& body, const Vec<3>& node,
                              const Vec<3>& half_cell) {
  return body.shape().boundary_meets_closed_box(node, half_cell);
}

}  // namespace cosmpm::contact
