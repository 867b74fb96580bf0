#pragma once
// Rigid walls of a DEM model: planes (a floor, the sides of a rig, the platens of a biaxial
// cell) and polygons (the blade) that share the geometry of contact::RigidBody with the MPM's
// rigid contact. Walls move with prescribed (or servo-controlled) velocities; the particles'
// force on each wall is recorded every step. Walls may touch but not overlap: a polygon
// reaching into a plane's solid side or into another polygon, or two facing planes with no
// room between them, is a cosmpm::Error when the wall is added.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::dem {

enum class WallKind { plane, polygon };

// Where a point lies relative to a wall's surface.
struct WallPoint {
  double gap = 0.0;                // distance from the surface, negative inside the wall
  Vec<2> normal = Vec<2>::Zero();  // unit, from the wall towards the point
  Vec<2> point = Vec<2>::Zero();   // closest point of the surface
  int edge = -1;                   // polygon edge holding the point (-1 for a plane)
  double along = 0.0;              // distance of the point from the edge's start vertex
};

// An element touching a wall, after a step.
struct WallContact {
  Index element = 0;
  Index wall = 0;
  Vec<2> point = Vec<2>::Zero();   // contact point: the middle of the overlap
  Vec<2> normal = Vec<2>::Zero();  // unit, from the wall to the element
  double overlap = 0.0;            // m; <= 0 when the candidate does not touch
  double normal_force = 0.0;       // N/m on the element along the normal, compression positive
  double shear_force = 0.0;        // N/m on the element along (-n_y, n_x)
  double rolling_moment = 0.0;     // N m/m on the element (rolling resistance)
  int edge = -1;                   // polygon edge of the closest point (-1: plane)
  double along = 0.0;              // its distance from that edge's start vertex, m
};

template <class Material>
class WallSet {
 public:
  struct Wall {
    std::string name;
    WallKind kind = WallKind::plane;
    Vec<2> point = Vec<2>::Zero();              // plane: a point of the surface
    Vec<2> normal = Vec<2>::Zero();             // plane: unit normal into the particles' side
    Vec<2> velocity = Vec<2>::Zero();           // plane: translation velocity (set_velocity)
    std::optional<contact::RigidBody<2>> body;  // polygon
    Material material{};
    bool enabled = true;
    // Velocity of the wall's last move (the leapfrog's half step), used at its contacts.
    Vec<2> contact_velocity = Vec<2>::Zero();
    double contact_spin = 0.0;
    // Results of the last step: force and torque of the particles on the wall (N/m, N m/m;
    // torque about the polygon's reference point or the plane's point) and contact count.
    Vec<2> force = Vec<2>::Zero();
    double torque = 0.0;
    int contacts = 0;
  };

  Index size() const { return static_cast<Index>(walls_.size()); }
  const Wall& operator[](Index w) const { return walls_[static_cast<std::size_t>(w)]; }
  Wall& at(Index w) { return walls_.at(static_cast<std::size_t>(w)); }
  // Changes whenever a wall is added, enabled or disabled: contact lists built before are stale.
  std::uint64_t revision() const { return revision_; }

  // A plane through `point` whose particles lie on the side `normal` points to.
  Index add_plane(std::string name, const Vec<2>& point, const Vec<2>& normal,
                  const Material& material) {
    const std::string where = "dem wall '" + name + "'";
    require(point.allFinite() && normal.allFinite(), where + ": point and normal must be finite");
    require_positive(where, "normal length", normal.norm());
    Wall wall;
    wall.name = std::move(name);
    wall.kind = WallKind::plane;
    wall.point = point;
    wall.normal = normal.normalized();
    wall.material = material;
    return add(std::move(wall));
  }

  // A polygon with the body's prescribed motion; particles lie outside it.
  Index add_polygon(std::string name, contact::RigidBody<2> body, const Material& material) {
    Wall wall;
    wall.name = std::move(name);
    wall.kind = WallKind::polygon;
    wall.contact_velocity = body.velocity(0.0);
    wall.contact_spin = body.angular_velocity(0.0);
    wall.body.emplace(std::move(body));
    wall.material = material;
    return add(std::move(wall));
  }

  void set_enabled(Index w, bool enabled) {
    if (at(w).enabled == enabled) return;
    at(w).enabled = enabled;
    const std::string why = enabled ? find_overlap(w) : std::string();
    if (!why.empty()) {
      at(w).enabled = false;
      throw Error(why);
    }
    ++revision_;
  }
  // A plane's translation velocity from now on (servo control of platens).
  void set_velocity(Index w, const Vec<2>& velocity) {
    require(at(w).kind == WallKind::plane,
            "dem wall '" + at(w).name +
                "': set_velocity is for planes; a polygon moves by its "
                "RigidBody's velocity law");
    require(velocity.allFinite(), "dem wall '" + at(w).name + "': the velocity must be finite");
    at(w).velocity = velocity;
  }

  // Where x lies relative to wall w.
  WallPoint locate(Index w, const Vec<2>& x) const {
    const Wall& wall = (*this)[w];
    WallPoint p;
    if (wall.kind == WallKind::plane) {
      p.gap = (x - wall.point).dot(wall.normal);
      p.normal = wall.normal;
      p.point = x - p.gap * wall.normal;
      return p;
    }
    const contact::BoundaryPoint b = wall.body->closest(x);
    p.gap = b.signed_distance;
    p.normal = b.normal;
    p.point = b.point;
    p.edge = b.edge;
    p.along = b.along;
    return p;
  }

  // Velocity of wall w's surface at x during the last move.
  Vec<2> velocity_at(Index w, const Vec<2>& x) const {
    const Wall& wall = (*this)[w];
    if (wall.kind == WallKind::plane) return wall.contact_velocity;
    return wall.body->velocity_at(x, wall.contact_velocity, wall.contact_spin);
  }

  // Spin of wall w during the last move (0 for planes).
  double spin_of(Index w) const {
    const Wall& wall = (*this)[w];
    return wall.kind == WallKind::plane ? 0.0 : wall.contact_spin;
  }

  // Moves every wall over [time, time + dt] with its mid-step velocity.
  void advance(double dt, double time) {
    for (Wall& wall : walls_) {
      if (wall.kind == WallKind::plane) {
        wall.contact_velocity = wall.velocity;
        wall.point += dt * wall.velocity;
      } else {
        const double mid = time + 0.5 * dt;
        wall.contact_velocity = wall.body->velocity(mid);
        wall.contact_spin = wall.body->angular_velocity(mid);
        wall.body->advance(dt, time);
      }
    }
  }

  // The largest distance any point of an enabled wall surface can have moved from `poses`
  // (taken by poses()): the contact lists' skin must cover it.
  struct Pose {
    Vec<2> point = Vec<2>::Zero();
    double angle = 0.0;
  };
  std::vector<Pose> poses() const {
    std::vector<Pose> out;
    for (const Wall& wall : walls_) {
      out.push_back(wall.kind == WallKind::plane
                        ? Pose{wall.point, 0.0}
                        : Pose{wall.body->reference_point(), wall.body->angle()});
    }
    return out;
  }
  double max_motion_since(const std::vector<Pose>& poses) const {
    double motion = 0.0;
    for (std::size_t w = 0; w < walls_.size() && w < poses.size(); ++w) {
      const Wall& wall = walls_[w];
      if (!wall.enabled) continue;
      if (wall.kind == WallKind::plane) {
        motion = std::max(motion, std::abs((wall.point - poses[w].point).dot(wall.normal)));
      } else {
        double reach = 0.0;
        for (const Vec<2>& v : wall.body->vertices()) {
          reach = std::max(reach, (v - wall.body->reference_point()).norm());
        }
        motion = std::max(motion, (wall.body->reference_point() - poses[w].point).norm() +
                                      std::abs(wall.body->angle() - poses[w].angle) * reach);
      }
    }
    return motion;
  }

 private:
  Index add(Wall wall) {
    walls_.push_back(std::move(wall));
    const std::string why = find_overlap(size() - 1);
    if (!why.empty()) {
      walls_.pop_back();
      throw Error(why);
    }
    ++revision_;
    return size() - 1;
  }

  static std::string point_text(const Vec<2>& x) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "(" + std::string.
    std::string text("(");
    text += cosmpm::detail::format_number(x[0]);
    text += ", ";
    text += cosmpm::detail::format_number(x[1]);
    text += ")";
    return text;
  }

  // Why enabled wall w overlaps another enabled wall (empty if it does not; touching is fine).
  std::string find_overlap(Index w) const {
    for (Index o = 0; o < size(); ++o) {
      if (o == w || !(*this)[o].enabled || !(*this)[w].enabled) continue;
      std::string why = overlap(o, w);
      if (why.empty()) why = overlap(w, o);
      if (!why.empty()) {
        return "dem walls: '" + (*this)[w].name + "' overlaps '" + (*this)[o].name + "': " + why +
               " (walls may touch but not overlap)";
      }
    }
    return "";
  }

  // Why wall b reaches into wall a (empty if it does not).
  std::string overlap(Index a, Index b) const {
    const Wall& wa = (*this)[a];
    const Wall& wb = (*this)[b];
    if (wb.kind == WallKind::polygon) {
      const double scale = (wb.body->upper_bound() - wb.body->lower_bound()).norm();
      const double tolerance = 1e-9 * std::max(scale, 1e-3);
      for (const Vec<2>& v : wb.body->vertices()) {
        const double gap = locate(a, v).gap;
        const bool inside = wa.kind == WallKind::plane ? gap < -tolerance
                                                       : wa.body->contains(v) && gap < -tolerance;
        if (inside) {
          return "vertex " + point_text(v) + " of '" + wb.name + "' lies " +
                 cosmpm::detail::format_number(-gap) + " m inside '" + wa.name + "'";
        }
      }
      if (wa.kind == WallKind::polygon) {
        // Polygons can cross with no vertex inside the other (a thin cross).
        for (int i = 0; i < wa.body->edge_count(); ++i) {
          for (int j = 0; j < wb.body->edge_count(); ++j) {
            if (segments_cross(wa.body->edge_start(i), wa.body->edge_end(i), wb.body->edge_start(j),
                               wb.body->edge_end(j))) {
              return "edge " + std::to_string(j) + " of '" + wb.name + "' crosses edge " +
                     std::to_string(i) + " of '" + wa.name + "'";
            }
          }
        }
      }
      return "";
    }
    if (wa.kind == WallKind::plane && wa.normal.dot(wb.normal) < -1.0 + 1e-12) {
      const double room = (wb.point - wa.point).dot(wa.normal);
      if (room <= 0.0) {
        return "the facing planes leave " + cosmpm::detail::format_number(room) +
               " m between them (valid range (0, inf))";
      }
    }
    return "";
  }

  // Proper crossing of segments [p, q] and [r, s]: each strictly separates the other's ends.
  static bool segments_cross(const Vec<2>& p, const Vec<2>& q, const Vec<2>& r, const Vec<2>& s) {
    auto cross = [](const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; };
    const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
    const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
  }

  std::vector<Wall> walls_;
  std::uint64_t revision_ = 0;
};

}  // namespace cosmpm::dem
