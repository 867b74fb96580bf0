#pragma once
// The shape of a 3D rigid body (RigidBody<3>, rigid_body_3d.hpp): a convex polyhedron given by
// its vertices and faces, checked once (planar faces, a closed surface, convex, a volume) and
// then placed in the world by a translation and a rotation. Each face has an outward unit
// normal and an in-plane frame (u along its first edge, v across it, towards its last vertex),
// in which contact forces are binned. The face planes of a convex body give the exact signed
// distance from inside; outside, the nearest point lies on a face whose plane faces the point.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::contact {

// The closest point of a 3D body's boundary to a query point.
struct FacePoint {
  double signed_distance = 0.0;     // negative inside the body
  Vec<3> point = Vec<3>::Zero();    // on the boundary
  Vec<3> normal = Vec<3>::Zero();   // outward unit normal of the body there
  int face = 0;                     // face holding the point
  Vec<2> on_face = Vec<2>::Zero();  // (u, v) of the point in the face's frame
  bool on_rim = false;              // on an edge or a vertex of the face
};

class ConvexPolyhedron {
 public:
  // `vertices` relative to the body's reference point; each face a loop of vertex indices
  // (either orientation; the outward normal is found from the body's centroid).
  ConvexPolyhedron(std::vector<Vec<3>> vertices, std::vector<std::vector<int>> faces)
      : local_(std::move(vertices)), faces_(std::move(faces)) {
    validate();
    place(Vec<3>::Zero(), Mat<3>::Identity());
  }

  // World placement: x = reference + rotation * x_local.
  void place(const Vec<3>& reference, const Mat<3>& rotation) {
    world_.resize(local_.size());
    lower_ = Vec<3>::Constant(std::numeric_limits<double>::infinity());
    upper_ = -lower_;
    for (std::size_t i = 0; i < local_.size(); ++i) {
      world_[i] = reference + rotation * local_[i];
      lower_ = lower_.cwiseMin(world_[i]);
      upper_ = upper_.cwiseMax(world_[i]);
    }
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      Frame& fr = frames_[f];
      fr.normal = rotation * local_frames_[f].normal;
      fr.u = rotation * local_frames_[f].u;
      fr.v = rotation * local_frames_[f].v;
      fr.offset = fr.normal.dot(world_[static_cast<std::size_t>(faces_[f][0])]);
      fr.inward.resize(faces_[f].size());
      for (std::size_t k = 0; k < faces_[f].size(); ++k) {
        fr.inward[k] = rotation * local_frames_[f].inward[k];
      }
    }
  }

  int face_count() const { return static_cast<int>(faces_.size()); }
  const std::vector<int>& face_vertices(int f) const { return faces_[index(f)]; }
  const std::vector<Vec<3>>& vertices() const { return world_; }
  const Vec<3>& face_normal(int f) const { return frames_[index(f)].normal; }
  const Vec<3>& face_tangent(int f) const { return frames_[index(f)].u; }  // u
  const Vec<3>& face_bitangent(int f) const { return frames_[index(f)].v; }
  const Vec<3>& face_origin(int f) const { return vertex(f, 0); }
  // (u, v) of a point in face f's frame, from the face's first vertex.
  Vec<2> face_coordinates(int f, const Vec<3>& x) const {
    const Vec<3> r = x - face_origin(f);
    return Vec<2>(r.dot(face_tangent(f)), r.dot(face_bitangent(f)));
  }
  const Vec<3>& lower_bound() const { return lower_; }
  const Vec<3>& upper_bound() const { return upper_; }

  double plane_distance(int f, const Vec<3>& x) const {
    const Frame& fr = frames_[index(f)];
    return fr.normal.dot(x) - fr.offset;
  }
  bool contains(const Vec<3>& x) const {
    for (int f = 0; f < face_count(); ++f) {
      if (plane_distance(f, x) > 0.0) return false;
    }
    return true;
  }

  // Closest point of face f to x; `inside` says on which side of the body x lies. Outside an
  // edge or vertex the normal points from there to x (continuous around edges and corners).
  FacePoint closest_on_face(const Vec<3>& x, int f, bool inside) const {
    const Frame& fr = frames_[index(f)];
    const auto& loop = faces_[index(f)];
    FacePoint p;
    p.face = f;
    const Vec<3> projected = x - plane_distance(f, x) * fr.normal;
    bool within = true;
    for (std::size_t k = 0; k < loop.size() && within; ++k) {
      within = fr.inward[k].dot(projected - vertex(f, k)) >= 0.0;
    }
    if (within) {
      p.point = projected;
    } else {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec<3>& a = vertex(f, k);
        const Vec<3> ab = vertex(f, (k + 1) % loop.size()) - a;
        const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        const Vec<3> q = a + t * ab;
        const double d = (x - q).squaredNorm();
        if (d < best) {
          best = d;
          p.point = q;
        }
      }
      p.on_rim = true;
    }
    const Vec<3> offset = x - p.point;
    const double distance = offset.norm();
    p.signed_distance = inside ? -distance : distance;
    p.normal =
        (p.on_rim && !inside && distance > 1e-12 * scale_) ? Vec<3>(offset / distance) : fr.normal;
    p.on_face = face_coordinates(f, p.point);
    return p;
  }

  // The closest boundary point over all faces. A point on an edge or vertex is attributed to
  // the face whose normal is closest to the point's normal.
  FacePoint closest(const Vec<3>& x) const {
    int deepest = 0;
    double largest = -std::numeric_limits<double>::infinity();
    for (int f = 0; f < face_count(); ++f) {
      const double d = plane_distance(f, x);
      if (d > largest) {
        largest = d;
        deepest = f;
      }
    }
    if (largest <= 0.0) return closest_on_face(x, deepest, true);  // inside: nearest plane
    FacePoint best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int f = 0; f < face_count(); ++f) {
      if (plane_distance(f, x) <= 0.0) continue;  // the nearest point faces x
      const FacePoint p = closest_on_face(x, f, false);
      if (p.signed_distance < best_distance ||
          (p.signed_distance == best_distance &&
           p.normal.dot(face_normal(f)) > best.normal.dot(face_normal(best.face)))) {
        best = p;
        best_distance = p.signed_distance;
      }
    }
    return best;
  }

  // Whether face f (closed) meets the open box |y - centre| < half (per axis).
  bool face_meets_open_box(int f, const Vec<3>& centre, const Vec<3>& half) const {
    const auto& loop = faces_[index(f)];
    if (separated_by(face_normal(f), centre, half, true, f)) return false;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec<3> edge = vertex(f, (k + 1) % loop.size()) - vertex(f, k);
      if (separated_by_edge(edge, centre, half, true, f)) return false;
    }
    for (int d = 0; d < 3; ++d) {
      if (separated_by(Vec<3>::Unit(d), centre, half, true, f)) return false;
    }
    return true;
  }
  // Whether the body (closed) meets the open box |y - centre| < half (separating axes).
  bool meets_open_box(const Vec<3>& centre, const Vec<3>& half) const {
    return meets_box(centre, half, true);
  }
  // Whether the boundary crosses the closed box |y - node| <= half: the box meets the body
  // and is not inside it (a convex box lies inside a convex body iff its corners do).
  bool boundary_meets_closed_box(const Vec<3>& node, const Vec<3>& half) const {
    if (!meets_box(node, half, false)) return false;
    for (int corner = 0; corner < 8; ++corner) {
      Vec<3> c = node;
      for (int d = 0; d < 3; ++d) c[d] += ((corner >> d) & 1) ? half[d] : -half[d];
      for (int f = 0; f < face_count(); ++f) {
        if (plane_distance(f, c) >= 0.0) return true;  // a corner on or outside the boundary
      }
    }
    return false;
  }

 private:
  struct Frame {
    Vec<3> normal = Vec<3>::Zero();
    Vec<3> u = Vec<3>::Zero();
    Vec<3> v = Vec<3>::Zero();
    double offset = 0.0;         // normal . (a point of the face)
    std::vector<Vec<3>> inward;  // per face edge k: in-plane normal pointing into the face
  };

  std::size_t index(int f) const { return static_cast<std::size_t>(f); }
  const Vec<3>& vertex(int f, std::size_t k) const {
    return world_[static_cast<std::size_t>(faces_[index(f)][k])];
  }

  bool meets_box(const Vec<3>& centre, const Vec<3>& half, bool open) const {
    for (int d = 0; d < 3; ++d) {
      if (open ? (centre[d] + half[d] <= lower_[d] || centre[d] - half[d] >= upper_[d])
               : (centre[d] + half[d] < lower_[d] || centre[d] - half[d] > upper_[d]))
        return false;
    }
    for (int f = 0; f < face_count(); ++f) {
      if (separated_by(face_normal(f), centre, half, open, all_vertices)) return false;
    }
    for (const auto& [a, b] : edges_) {
      const Vec<3> edge = world_[static_cast<std::size_t>(b)] - world_[static_cast<std::size_t>(a)];
      if (separated_by_edge(edge, centre, half, open, all_vertices)) return false;
    }
    return true;  // the box axes were the bounding-box test
  }
  static constexpr int all_vertices = -1;
  bool separated_by_edge(const Vec<3>& edge, const Vec<3>& centre, const Vec<3>& half, bool open,
                         int f) const {
    for (int d = 0; d < 3; ++d) {
      const Vec<3> axis = Vec<3>::Unit(d).cross(edge);
      if (axis.squaredNorm() <= 1e-24 * edge.squaredNorm()) continue;  // parallel: no axis
      if (separated_by(axis, centre, half, open, f)) return true;
    }
    return false;
  }
  // Whether `axis` separates face f's vertices (all vertices for f < 0) from the box; touching
  // separates an open box, not a closed one.
  bool separated_by(const Vec<3>& axis, const Vec<3>& centre, const Vec<3>& half, bool open,
                    int f) const {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    const auto take = [&](const Vec<3>& p) {
      const double s = axis.dot(p);
      low = std::min(low, s);
      high = std::max(high, s);
    };
    if (f < 0) {
      for (const Vec<3>& p : world_) take(p);
    } else {
      for (int i : faces_[index(f)]) take(world_[static_cast<std::size_t>(i)]);
    }
    const double c = axis.dot(centre);
    const double r = axis.cwiseAbs().dot(half);
    return open ? (high <= c - r || low >= c + r) : (high < c - r || low > c + r);
  }

  void validate();

  std::vector<Vec<3>> local_;
  std::vector<std::vector<int>> faces_;
  std::vector<Frame> local_frames_;
  std::vector<Frame> frames_;
  std::vector<std::pair<int, int>> edges_;  // each once, a < b
  std::vector<Vec<3>> world_;
  Vec<3> lower_ = Vec<3>::Zero();
  Vec<3> upper_ = Vec<3>::Zero();
  double scale_ = 1.0;  // largest vertex coordinate: the length scale of the tolerances
};

}  // namespace cosmpm::contact

#include "cosmpm/contact/detail/polyhedron_checks.hpp"
