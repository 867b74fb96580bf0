#pragma once
// A clump: a rigid union of disks (PFC's clump), described once as a shape and scaled per
// particle. The shape's area, centroid and polar moment are those of the UNION of its disks,
// computed exactly with Green's theorem along the boundary arcs that no other disk covers
// (each arc traversed counter-clockwise about its own centre keeps the union on its left, holes
// included), so overlapping disks are not counted twice (PFC2D's older clumps summed them).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::dem {

struct ClumpMember {
  Vec<2> offset = Vec<2>::Zero();  // centre relative to the shape's centroid (after construction)
  double radius = 0.0;
};

namespace detail {

// Integrals over the union of disks: area, first moments and the polar moment about the origin.
struct UnionIntegrals {
  double area = 0.0;
  Vec<2> first_moment = Vec<2>::Zero();
  double polar_moment = 0.0;
};

// Angular intervals [start, end] of circle i covered by the other circles, merged, in [0, 2 pi).
inline std::vector<std::pair<double, double>> covered_arcs(const std::vector<ClumpMember>& m,
                                                           std::size_t i, bool& fully_covered) {
  std::vector<std::pair<double, double>> raw;
  fully_covered = false;
  const double two_pi = 2.0 * pi;
  for (std::size_t j = 0; j < m.size(); ++j) {
    if (j == i) continue;
    const Vec<2> d = m[j].offset - m[i].offset;
    const double distance = d.norm();
    const double ri = m[i].radius, rj = m[j].radius;
    const double tiny = 1e-14 * (ri + rj);
    const bool identical = distance <= tiny && std::abs(ri - rj) <= tiny;
    if (identical) {
      if (j < i) fully_covered = true;  // the first of identical disks keeps the boundary
      continue;
    }
    if (distance + ri <= rj) {
      fully_covered = true;
      continue;
    }
    if (distance >= ri + rj || distance + rj <= ri) continue;
    const double centre = std::atan2(d[1], d[0]);
    const double half = std::acos(
        std::clamp((distance * distance + ri * ri - rj * rj) / (2.0 * distance * ri), -1.0, 1.0));
    double start = std::fmod(centre - half + 2.0 * two_pi, two_pi);
    const double end = start + 2.0 * half;
    if (end > two_pi) {
      raw.emplace_back(start, two_pi);
      raw.emplace_back(0.0, end - two_pi);
    } else {
      raw.emplace_back(start, end);
    }
  }
  std::sort(raw.begin(), raw.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& interval : raw) {
    if (!merged.empty() && interval.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, interval.second);
    } else {
      merged.push_back(interval);
    }
  }
  return merged;
}

// Green's theorem along the arc t in [a, b] of circle (c, r):
//   A = 1/2 (x dy - y dx), S_x = x^2/2 dy, S_y = -y^2/2 dx, J = (x^3 dy - y^3 dx)/3.
// The integrands are trigonometric polynomials of degree <= 4: 8-point Gauss-Legendre on pieces
// of at most pi/4 is exact to rounding.
inline void integrate_arc(const Vec<2>& c, double r, double a, double b, UnionIntegrals& out) {
  static constexpr std::array<double, 4> nodes{0.1834346424956498, 0.5255324099163290,
                                               0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> weights{0.3626837833783620, 0.3137066458778873,
                                                 0.2223810344533745, 0.1012285362903763};
  const int pieces = std::max(1, static_cast<int>(std::ceil((b - a) / (0.25 * pi))));
  const double width = (b - a) / pieces;
  for (int k = 0; k < pieces; ++k) {
    const double mid = a + (k + 0.5) * width;
    for (std::size_t q = 0; q < 8; ++q) {
      const double node = (q < 4 ? -1.0 : 1.0) * nodes[q % 4];
      const double t = mid + 0.5 * width * node;
      const double w = 0.5 * width * weights[q % 4];
      const double x = c[0] + r * std::cos(t), y = c[1] + r * std::sin(t);
      const double dx = -r * std::sin(t), dy = r * std::cos(t);
      out.area += w * 0.5 * (x * dy - y * dx);
      out.first_moment[0] += w * 0.5 * x * x * dy;
      out.first_moment[1] -= w * 0.5 * y * y * dx;
      out.polar_moment += w * (x * x * x * dy - y * y * y * dx) / 3.0;
    }
  }
}

inline UnionIntegrals union_integrals(const std::vector<ClumpMember>& members) {
  UnionIntegrals out;
  for (std::size_t i = 0; i < members.size(); ++i) {
    bool fully_covered = false;
    const auto covered = covered_arcs(members, i, fully_covered);
    if (fully_covered) continue;
    double from = 0.0;
    for (const auto& [start, end] : covered) {
      if (start > from) integrate_arc(members[i].offset, members[i].radius, from, start, out);
      from = std::max(from, end);
    }
    if (from < 2.0 * pi) integrate_arc(members[i].offset, members[i].radius, from, 2.0 * pi, out);
  }
  return out;
}

}  // namespace detail

// A clump shape at unit scale. A particle made from it with scale s has its offsets and radii
// multiplied by s, its area by s^2 and its polar moment by s^4.
class ClumpShape {
 public:
  explicit ClumpShape(std::vector<ClumpMember> members) : members_(std::move(members)) {
    const char* where = "dem::ClumpShape";
    if (members_.empty()) {
      throw Error(std::string(where) + ": a clump needs at least one disk (valid range [1, inf))");
    }
    for (std::size_t i = 0; i < members_.size(); ++i) {
      require_positive(where, "radius of disk " + std::to_string(i), members_[i].radius);
      require(members_[i].offset.allFinite(),
              std::string(where) + ": the centre of disk " + std::to_string(i) + " is not finite");
    }
    const detail::UnionIntegrals integrals = detail::union_integrals(members_);
    area_ = integrals.area;
    const Vec<2> centroid = integrals.first_moment / area_;
    polar_moment_ = integrals.polar_moment - area_ * centroid.squaredNorm();
    for (auto& member : members_) {
      member.offset -= centroid;
      bounding_radius_ = std::max(bounding_radius_, member.offset.norm() + member.radius);
      smallest_radius_ = std::min(smallest_radius_, member.radius);
    }
  }

  // Two equal disks side by side: overall `length` along the body's x axis, `width` across
  // (the disks' diameter). length == width gives a single disk.
  static ClumpShape two_disks(double length, double width) {
    const char* where = "dem::ClumpShape::two_disks";
    require_positive(where, "width", width);
    require_in_range(where, "length", length, width, 1e300, Bounds::left_closed);
    const double r = 0.5 * width;
    const double half_distance = 0.5 * (length - width);
    if (half_distance == 0.0) return ClumpShape({{Vec<2>::Zero(), r}});
    return ClumpShape({{Vec<2>(-half_distance, 0.0), r}, {Vec<2>(half_distance, 0.0), r}});
  }

  const std::vector<ClumpMember>& members() const { return members_; }
  double area() const { return area_; }                  // m^2 at unit scale
  double polar_moment() const { return polar_moment_; }  // m^4 about the centroid, unit scale
  double bounding_radius() const { return bounding_radius_; }
  double smallest_radius() const { return smallest_radius_; }

 private:
  std::vector<ClumpMember> members_;
  double area_ = 0.0;
  double polar_moment_ = 0.0;
  double bounding_radius_ = 0.0;
  double smallest_radius_ = 1e300;
};

}  // namespace cosmpm::dem
