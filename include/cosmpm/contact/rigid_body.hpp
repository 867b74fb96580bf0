#pragma once
// A rigid body with prescribed motion: a simple polygon (2D) whose vertices are given relative
// to a reference point, translated with a prescribed velocity V(t) and rotated about the
// reference point with a prescribed angular velocity omega(t). The geometric queries a grid
// contact law needs are exact: signed distance, closest boundary point and outward unit
// normal. On a face the normal is the face normal; outside a corner it points from the corner
// to the query point, so it is continuous around the blade tip.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::contact {

// The closest point of a body's boundary to a query point.
struct BoundaryPoint {
  double signed_distance = 0.0;  // negative inside the body
  Vec<2> point = Vec<2>::Zero();
  Vec<2> normal = Vec<2>::Zero();  // outward unit normal of the body there
  int edge = 0;                    // edge holding the point (edge e runs vertex e -> e + 1)
  double along = 0.0;              // distance of the point from the edge's start vertex
  bool at_vertex = false;
};

// The corners of an axis-aligned box: finite, upper above lower along every axis.
template <int Dim>
void require_box_corners(const char* where, const Vec<Dim>& lower, const Vec<Dim>& upper) {
  for (int d = 0; d < Dim; ++d) {
    require(std::isfinite(lower[d]) && std::isfinite(upper[d]),
            std::string(where) + ": corners must be finite");
    if (!(upper[d] > lower[d])) {
      throw Error(std::string(where) + ": upper corner " + detail::format_number(upper[d]) +
                  " must exceed lower corner " + detail::format_number(lower[d]) + " along axis " +
                  std::to_string(d) + " (valid range (lower, inf))");
    }
  }
}

// 2D: simple polygons (here); 3D: convex polyhedra (rigid_body_3d.hpp).
template <int Dim>
class RigidBody {
  static_assert(Dim == 2 || Dim == 3, "contact::RigidBody: 2D polygons or 3D polyhedra");
};

template <>
class RigidBody<2> {
 public:
  using Point = BoundaryPoint;
  using AngularVelocity = double;
  using VelocityLaw = std::function<Vec<2>(double)>;
  using AngularVelocityLaw = std::function<double(double)>;
  // Checkpoint values per body: the reference point and the angle.
  static constexpr int pose_size = 3;

  // `relative_vertices` in order around the polygon (either orientation), relative to
  // `reference_point`, which is also the centre of rotation. The polygon must be simple.
  RigidBody(std::vector<Vec<2>> relative_vertices, const Vec<2>& reference_point)
      : local_(std::move(relative_vertices)), reference_(reference_point) {
    validate();
    update_world();
  }

  // The axis-aligned rectangle [lower, upper], reference point at its centre. Edges (counter-
  // clockwise from the lower-left corner): 0 bottom (normal -y), 1 right (+x), 2 top (+y),
  // 3 left (-x).
  static RigidBody box(const Vec<2>& lower, const Vec<2>& upper) {
    require_box_corners("contact::RigidBody::box", lower, upper);
    const Vec<2> centre = 0.5 * (lower + upper);
    const Vec<2> half = 0.5 * (upper - lower);
    return RigidBody({Vec<2>(-half[0], -half[1]), Vec<2>(half[0], -half[1]),
                      Vec<2>(half[0], half[1]), Vec<2>(-half[0], half[1])},
                     centre);
  }

  // --- prescribed motion ----------------------------------------------------------------
  RigidBody& set_velocity(const Vec<2>& velocity) {
    require(velocity.allFinite(), "contact::RigidBody::set_velocity: velocity must be finite");
    return set_velocity(VelocityLaw([velocity](double) { return velocity; }));
  }
  RigidBody& set_velocity(VelocityLaw law) {
    require(static_cast<bool>(law), "contact::RigidBody::set_velocity: empty velocity law");
    velocity_ = std::move(law);
    return *this;
  }
  RigidBody& set_angular_velocity(double omega) {
    require(std::isfinite(omega), "contact::RigidBody::set_angular_velocity: omega must be finite");
    return set_angular_velocity(AngularVelocityLaw([omega](double) { return omega; }));
  }
  RigidBody& set_angular_velocity(AngularVelocityLaw law) {
    require(static_cast<bool>(law), "contact::RigidBody::set_angular_velocity: empty law");
    angular_velocity_ = std::move(law);
    return *this;
  }

  // Translational velocity of the reference point at time t (checked: a law may misbehave).
  Vec<2> velocity(double time) const {
    const Vec<2> v = velocity_(time);
    if (!v.allFinite()) {
      throw Error("contact::RigidBody: the velocity law returned a non-finite value at t = " +
                  detail::format_number(time) + " s (valid range: finite)");
    }
    return v;
  }
  double angular_velocity(double time) const {
    const double omega = angular_velocity_(time);
    if (!std::isfinite(omega)) {
      throw Error("contact::RigidBody: the angular velocity law returned " +
                  detail::format_number(omega) + " at t = " + detail::format_number(time) +
                  " s (valid range: finite)");
    }
    return omega;
  }
  // Velocity of the body's material at x for a given translational and angular velocity.
  Vec<2> velocity_at(const Vec<2>& x, const Vec<2>& v, double omega) const {
    const Vec<2> r = x - reference_;
    return v + omega * Vec<2>(-r[1], r[0]);
  }

  // Moves the body over [time, time + dt] with the mid-step velocities (exact for laws linear
  // in time); the contact law uses the same mid-step velocities, so the grid and the body
  // agree on where the face goes.
  void advance(double dt, double time) {
    const double mid = time + 0.5 * dt;
    reference_ += dt * velocity(mid);
    angle_ += dt * angular_velocity(mid);
    update_world();
  }

  // Places the body (restarts): reference point and rotation from the input pose.
  void set_pose(const Vec<2>& reference_point, double angle) {
    require(reference_point.allFinite() && std::isfinite(angle),
            "contact::RigidBody::set_pose: the pose must be finite");
    reference_ = reference_point;
    angle_ = angle;
    update_world();
  }

  std::vector<double> pose_values() const { return {reference_[0], reference_[1], angle_}; }
  void set_pose_values(const double* values) { set_pose(Vec<2>(values[0], values[1]), values[2]); }

  // --- geometry -------------------------------------------------------------------------
  // The contact law's names, shared with the 3D body: a polygon's faces are its edges.
  int face_count() const { return edge_count(); }
  Vec<2> face_normal(int e) const { return edge_normal(e); }
  Vec<2> face_tangent(int e) const { return edge_tangent(e); }
  BoundaryPoint closest_on_face(const Vec<2>& x, int e, bool inside) const {
    return closest_on_edge(x, e, inside);
  }
  bool face_meets_open_box(int e, const Vec<2>& centre, const Vec<2>& half) const {
    return edge_meets_open_box(e, centre, half);
  }
  const Vec<2>& reference_point() const { return reference_; }
  double angle() const { return angle_; }  // radians, counter-clockwise from the input pose
  const std::vector<Vec<2>>& vertices() const { return world_; }
  int edge_count() const { return static_cast<int>(world_.size()); }
  const Vec<2>& edge_start(int e) const { return world_[static_cast<std::size_t>(e)]; }
  const Vec<2>& edge_end(int e) const { return world_[next(e)]; }
  double edge_length(int e) const { return (edge_end(e) - edge_start(e)).norm(); }
  // Unit vector from the edge's start vertex to its end vertex.
  Vec<2> edge_tangent(int e) const { return (edge_end(e) - edge_start(e)).normalized(); }
  Vec<2> edge_normal(int e) const {
    const Vec<2> t = edge_tangent(e);
    // Counter-clockwise polygons have the outside on the right of each edge.
    return orientation_ * Vec<2>(t[1], -t[0]);
  }
  const Vec<2>& lower_bound() const { return lower_; }
  const Vec<2>& upper_bound() const { return upper_; }

  // Even-odd rule; points on the boundary may fall either way (their distance is zero).
  bool contains(const Vec<2>& x) const {
    bool inside = false;
    const std::size_t n = world_.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec<2>& a = world_[i];
      const Vec<2>& b = world_[j];
      if ((a[1] > x[1]) != (b[1] > x[1])) {
        const double cross_x = a[0] + (x[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
        if (x[0] < cross_x) inside = !inside;
      }
    }
    return inside;
  }

  // Closest point of edge e to x; `inside` says on which side of the body x lies.
  BoundaryPoint closest_on_edge(const Vec<2>& x, int e, bool inside) const {
    const Vec<2>& a = edge_start(e);
    const Vec<2> ab = edge_end(e) - a;
    const double length_sq = ab.squaredNorm();
    const double t = std::clamp((x - a).dot(ab) / length_sq, 0.0, 1.0);
    BoundaryPoint p;
    p.point = a + t * ab;
    p.edge = e;
    p.along = t * std::sqrt(length_sq);
    p.at_vertex = (t <= 0.0 || t >= 1.0);
    const Vec<2> offset = x - p.point;
    const double distance = offset.norm();
    p.signed_distance = inside ? -distance : distance;
    const double tiny = 1e-12 * std::sqrt(length_sq);
    if (p.at_vertex && !inside && distance > tiny) {
      p.normal = offset / distance;  // outside a corner: from the corner to the point
    } else if (p.at_vertex && distance <= tiny) {
      // On a vertex: the bisector of the two faces meeting there.
      const int other = t <= 0.0 ? previous(e) : static_cast<int>(next(e));
      p.normal = (edge_normal(e) + edge_normal(other)).normalized();
    } else {
      p.normal = edge_normal(e);
    }
    return p;
  }

  // The closest boundary point over all edges. At a vertex the point is attributed to the
  // adjacent edge whose face normal is closer to the point's normal.
  BoundaryPoint closest(const Vec<2>& x) const {
    const bool inside = contains(x);
    BoundaryPoint best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int e = 0; e < edge_count(); ++e) {
      const BoundaryPoint p = closest_on_edge(x, e, inside);
      const double distance = std::abs(p.signed_distance);
      if (distance < best_distance ||
          (distance == best_distance &&
           p.normal.dot(edge_normal(e)) > best.normal.dot(edge_normal(best.edge)))) {
        best = p;
        best_distance = distance;
      }
    }
    return best;
  }
  double signed_distance(const Vec<2>& x) const { return closest(x).signed_distance; }

  // Whether edge e meets the open box |x - centre| < half (per axis).
  bool edge_meets_open_box(int e, const Vec<2>& centre, const Vec<2>& half) const {
    const Vec<2>& a = edge_start(e);
    const Vec<2> ab = edge_end(e) - a;
    double t0 = 0.0;
    double t1 = 1.0;
    for (int d = 0; d < 2; ++d) {
      const double p = a[d] - centre[d];
      if (ab[d] == 0.0) {
        if (!(std::abs(p) < half[d])) return false;
        continue;
      }
      double ta = (-half[d] - p) / ab[d];
      double tb = (half[d] - p) / ab[d];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 < t1;
  }
  // Whether the body (closed) meets the open box |x - centre| < half: either the box centre
  // is inside or the boundary crosses the box (the box is connected).
  bool meets_open_box(const Vec<2>& centre, const Vec<2>& half) const {
    for (int d = 0; d < 2; ++d) {
      if (centre[d] + half[d] <= lower_[d] || centre[d] - half[d] >= upper_[d]) return false;
    }
    if (contains(centre)) return true;
    for (int e = 0; e < edge_count(); ++e) {
      if (edge_meets_open_box(e, centre, half)) return true;
    }
    return false;
  }

 private:
  std::size_t next(int e) const { return (static_cast<std::size_t>(e) + 1) % world_.size(); }
  int previous(int e) const { return e == 0 ? edge_count() - 1 : e - 1; }

  static double cross(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }

  // Proper or touching intersection of segments [p, q] and [r, s].
  static bool segments_meet(const Vec<2>& p, const Vec<2>& q, const Vec<2>& r, const Vec<2>& s) {
    const double d1 = cross(q - p, r - p);
    const double d2 = cross(q - p, s - p);
    const double d3 = cross(s - r, p - r);
    const double d4 = cross(s - r, q - r);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
      return true;
    auto on_segment = [](const Vec<2>& a, const Vec<2>& b, const Vec<2>& c, double side) {
      return side == 0.0 && c[0] >= std::min(a[0], b[0]) && c[0] <= std::max(a[0], b[0]) &&
             c[1] >= std::min(a[1], b[1]) && c[1] <= std::max(a[1], b[1]);
    };
    return on_segment(p, q, r, d1) || on_segment(p, q, s, d2) || on_segment(r, s, p, d3) ||
           on_segment(r, s, q, d4);
  }

  void validate() {
    const char* where = "contact::RigidBody";
    require(reference_.allFinite(), "contact::RigidBody: reference point must be finite");
    const std::size_t n = local_.size();
    if (n < 3) {
      throw Error(std::string(where) + ": the polygon has " + std::to_string(n) +
                  " vertices (valid range [3, inf))");
    }
    double scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!local_[i].allFinite()) {
        throw Error(std::string(where) + ": vertex " + std::to_string(i) + " is not finite");
      }
      scale = std::max(scale, local_[i].cwiseAbs().maxCoeff());
    }
    require_positive(where, "polygon size (largest vertex coordinate)", scale);
    double twice_area = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<2>& a = local_[i];
      const Vec<2>& b = local_[(i + 1) % n];
      if ((b - a).norm() <= 1e-12 * scale) {
        throw Error(std::string(where) + ": edge " + std::to_string(i) +
                    " has zero length (repeated vertex; valid range: length > 0)");
      }
      twice_area += cross(a, b);
    }
    const double area = 0.5 * twice_area;
    if (!(std::abs(area) > 1e-12 * scale * scale)) {
      throw Error(std::string(where) + ": the polygon's area " + detail::format_number(area) +
                  " is zero (degenerate polygon; valid range: |area| > 0)");
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
        if (adjacent) continue;
        if (segments_meet(local_[i], local_[(i + 1) % n], local_[j], local_[(j + 1) % n])) {
          throw Error(std::string(where) + ": edges " + std::to_string(i) + " and " +
                      std::to_string(j) + " intersect (the polygon must be simple)");
        }
      }
    }
    orientation_ = area > 0.0 ? 1.0 : -1.0;
  }

  void update_world() {
    const double c = std::cos(angle_);
    const double s = std::sin(angle_);
    world_.resize(local_.size());
    lower_ = Vec<2>::Constant(std::numeric_limits<double>::infinity());
    upper_ = -lower_;
    for (std::size_t i = 0; i < local_.size(); ++i) {
      const Vec<2>& r = local_[i];
      world_[i] = reference_ + Vec<2>(c * r[0] - s * r[1], s * r[0] + c * r[1]);
      lower_ = lower_.cwiseMin(world_[i]);
      upper_ = upper_.cwiseMax(world_[i]);
    }
  }

  std::vector<Vec<2>> local_;
  std::vector<Vec<2>> world_;
  Vec<2> reference_;
  double angle_ = 0.0;
  double orientation_ = 1.0;  // +1 counter-clockwise input, -1 clockwise
  Vec<2> lower_ = Vec<2>::Zero();
  Vec<2> upper_ = Vec<2>::Zero();
  VelocityLaw velocity_ = [](double) { return Vec<2>::Zero().eval(); };
  AngularVelocityLaw angular_velocity_ = [](double) { return 0.0; };
};

}  // namespace cosmpm::contact
