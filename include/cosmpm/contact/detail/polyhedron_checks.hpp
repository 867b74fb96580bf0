#pragma once
// The input checks of ConvexPolyhedron (convex_polyhedron.hpp) and its per-face frames: every
// failure names the vertex, face or edge, the value and what is valid.
#include <map>
#include <string>
#include <utility>

#include "cosmpm/contact/convex_polyhedron.hpp"
#include "cosmpm/core/error.hpp"

namespace cosmpm::contact {

inline void ConvexPolyhedron::validate() {
  const std::string where = "contact::ConvexPolyhedron";
  const std::size_t n = local_.size();
  if (n < 4) {
    throw Error(where + ": " + std::to_string(n) + " vertices (valid range [4, inf))");
  }
  Vec<3> lo = Vec<3>::Constant(std::numeric_limits<double>::infinity());
  Vec<3> hi = -lo;
  Vec<3> centroid = Vec<3>::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!local_[i].allFinite()) {
      throw Error(where + ": vertex " + std::to_string(i) + " is not finite");
    }
    lo = lo.cwiseMin(local_[i]);
    hi = hi.cwiseMax(local_[i]);
    centroid += local_[i] / static_cast<double>(n);
  }
  scale_ = (hi - lo).norm();
  require_positive(where, "size (bounding-box diagonal)", scale_);
  const double tolerance = 1e-9 * scale_;
  if (faces_.size() < 4) {
    throw Error(where + ": " + std::to_string(faces_.size()) +
                " faces (valid range [4, inf): a closed surface)");
  }
  std::map<std::pair<int, int>, int> edge_uses;
  std::vector<bool> used(n, false);
  local_frames_.assign(faces_.size(), Frame{});
  frames_.assign(faces_.size(), Frame{});
  double volume = 0.0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const auto& loop = faces_[f];
    const std::string face = "face " + std::to_string(f);
    if (loop.size() < 3) {
      throw Error(where + ": " + face + " has " + std::to_string(loop.size()) +
                  " vertices (valid range [3, inf))");
    }
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int i = loop[k];
      if (i < 0 || static_cast<std::size_t>(i) >= n) {
        throw Error(where + ": " + face + " names vertex " + std::to_string(i) +
                    " (valid range [0, " + std::to_string(n - 1) + "])");
      }
      for (std::size_t l = 0; l < k; ++l) {
        if (loop[l] == i) {
          throw Error(where + ": " + face + " names vertex " + std::to_string(i) +
                      " twice (valid: each vertex once per face)");
        }
      }
      used[static_cast<std::size_t>(i)] = true;
    }
    // Newell's normal: twice the area along the loop's own (right-hand) normal.
    Vec<3> newell = Vec<3>::Zero();
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec<3>& a = local_[static_cast<std::size_t>(loop[k])];
      const Vec<3>& b = local_[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
      if ((b - a).norm() <= 1e-12 * scale_) {
        throw Error(where + ": " + face + " has a zero-length edge at vertex " +
                    std::to_string(loop[k]) + " (valid: distinct vertices)");
      }
      newell += (a - centroid).cross(b - centroid);
      const auto key = std::minmax(loop[k], loop[(k + 1) % loop.size()]);
      ++edge_uses[{key.first, key.second}];
    }
    const double area = 0.5 * newell.norm();
    if (!(area > 1e-12 * scale_ * scale_)) {
      throw Error(where + ": " + face + " has area " + detail::format_number(area) +
                  " (degenerate face; valid range: area > 0)");
    }
    const Vec<3>& origin = local_[static_cast<std::size_t>(loop[0])];
    Frame& fr = local_frames_[f];
    fr.normal = newell.normalized();
    for (int i : loop) {
      const double off_plane = fr.normal.dot(local_[static_cast<std::size_t>(i)] - origin);
      if (std::abs(off_plane) > tolerance) {
        throw Error(where + ": vertex " + std::to_string(i) + " lies " +
                    detail::format_number(off_plane) + " off the plane of " + face +
                    " (valid range [-" + detail::format_number(tolerance) + ", " +
                    detail::format_number(tolerance) + "]: faces must be planar)");
      }
    }
    const double loop_sign = fr.normal.dot(origin - centroid) < 0.0 ? -1.0 : 1.0;
    fr.normal *= loop_sign;  // outward: away from the centroid
    for (std::size_t i = 0; i < n; ++i) {
      const double outside = fr.normal.dot(local_[i] - origin);
      if (outside > tolerance) {
        throw Error(where + ": vertex " + std::to_string(i) + " lies " +
                    detail::format_number(outside) + " outside the plane of " + face +
                    " (valid range (-inf, " + detail::format_number(tolerance) +
                    "]: the polyhedron must be convex)");
      }
    }
    volume += area * fr.normal.dot(origin - centroid) / 3.0;
    fr.u = (local_[static_cast<std::size_t>(loop[1])] - origin).normalized();
    fr.v = fr.normal.cross(fr.u);
    if (fr.v.dot(local_[static_cast<std::size_t>(loop.back())] - origin) < 0.0) fr.v = -fr.v;
    fr.inward.resize(loop.size());
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec<3> edge = local_[static_cast<std::size_t>(loop[(k + 1) % loop.size()])] -
                          local_[static_cast<std::size_t>(loop[k])];
      // A loop counter-clockwise about its Newell normal has its inside on the left.
      fr.inward[k] = (loop_sign * fr.normal).cross(edge).normalized();
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) {
      throw Error(where + ": vertex " + std::to_string(i) +
                  " belongs to no face (valid: every vertex on the surface)");
    }
  }
  for (const auto& [edge, uses] : edge_uses) {
    if (uses != 2) {
      throw Error(where + ": edge (" + std::to_string(edge.first) + ", " +
                  std::to_string(edge.second) + ") belongs to " + std::to_string(uses) +
                  " faces (valid: 2; the faces must close the surface)");
    }
    edges_.push_back(edge);
  }
  if (!(volume > 1e-9 * scale_ * scale_ * scale_)) {
    throw Error(where + ": the volume " + detail::format_number(volume) +
                " is zero (flat polyhedron; valid range: volume > 0)");
  }
}

}  // namespace cosmpm::contact
