#pragma once
// Where the rig lies in the grid. By default its floor is the grid's bottom face and its sides
// are the grid's side faces (the paper's set-up). With --rig-angle the whole rig is turned
// against the grid (the paper's mesh-orientation study, its Sect. 3.3: a mesh turned 35 deg):
// gravity, the blade and its motion are turned with it, and the floor and side walls, no
// longer grid faces, become rigid bodies. Rig coordinates: x along the floor from the rig's
// left wall, y up from the floor; world = origin + R(angle) rig.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "case.hpp"
#include "cosmpm/contact/interface.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace flat_blade {

class Rig {
 public:
  using Vec2 = cosmpm::Vec<2>;

  explicit Rig(const Case& c)
      : angle_(c.rig_angle_deg * std::numbers::pi / 180.0),
        cos_(std::cos(angle_)),
        sin_(std::sin(angle_)),
        cell_(c.grid_length / static_cast<double>(c.cells_x),
              c.grid_height / static_cast<double>(c.cells_y)) {
    if (!turned()) {
      cells_ = {c.cells_x, c.cells_y};
      extent_ = Vec2(c.grid_length, c.grid_height);
      return;
    }
    // The turned rig with its walls, one cell of margin around it: the walls must be thicker
    // than a node's reach so that no node meets a wall's far side.
    wall_ = 2.0 * cell_.maxCoeff();
    Vec2 lower = Vec2::Constant(1e300);
    Vec2 upper = Vec2::Constant(-1e300);
    for (const Vec2& corner :
         {Vec2(-wall_, -wall_), Vec2(c.grid_length + wall_, -wall_),
          Vec2(c.grid_length + wall_, c.grid_height), Vec2(-wall_, c.grid_height)}) {
      const Vec2 w = direction(corner);
      lower = lower.cwiseMin(w);
      upper = upper.cwiseMax(w);
    }
    origin_ = cell_ - lower;
    for (int d = 0; d < 2; ++d) {
      cells_[static_cast<std::size_t>(d)] =
          static_cast<cosmpm::Index>(std::ceil((upper[d] - lower[d]) / cell_[d])) + 2;
      extent_[d] = static_cast<double>(cells_[static_cast<std::size_t>(d)]) * cell_[d];
    }
  }

  bool turned() const { return angle_ != 0.0; }
  const Vec2& origin() const { return origin_; }
  cosmpm::grid::Grid<2> grid() const { return {Vec2(0.0, 0.0), extent_, cells_}; }

  // A vector given in rig axes, in world axes.
  Vec2 direction(const Vec2& rig) const {
    return Vec2(cos_ * rig[0] - sin_ * rig[1], sin_ * rig[0] + cos_ * rig[1]);
  }
  Vec2 to_world(const Vec2& rig) const { return origin_ + direction(rig); }
  Vec2 to_rig(const Vec2& world) const { return in_rig_axes(world - origin_); }
  // A vector's components in rig axes (a force: draft along the floor, vertical normal to it).
  Vec2 in_rig_axes(const Vec2& world) const {
    return Vec2(cos_ * world[0] + sin_ * world[1], -sin_ * world[0] + cos_ * world[1]);
  }
  // A stress with principal axes along the rig's (s_xx, s_yy in rig axes, no shear), in world
  // axes: R diag(s_xx, s_yy) R^T.
  void turn_stress(double s_xx, double s_yy, double& xx, double& yy, double& xy) const {
    xx = s_xx * cos_ * cos_ + s_yy * sin_ * sin_;
    yy = s_xx * sin_ * sin_ + s_yy * cos_ * cos_;
    xy = (s_xx - s_yy) * cos_ * sin_;
  }

  // The rectangle [lower, upper] given in rig coordinates, with the edge order of
  // RigidBody::box (0 bottom, 1 right, 2 top, 3 left in rig axes). At angle 0 exactly box().
  cosmpm::contact::RigidBody<2> box(const Vec2& lower, const Vec2& upper) const {
    if (!turned()) return cosmpm::contact::RigidBody<2>::box(lower, upper);
    const Vec2 half = 0.5 * (upper - lower);
    std::vector<Vec2> vertices;
    for (const Vec2& v : {Vec2(-half[0], -half[1]), Vec2(half[0], -half[1]), Vec2(half[0], half[1]),
                          Vec2(-half[0], half[1])}) {
      vertices.push_back(direction(v));
    }
    return cosmpm::contact::RigidBody<2>(std::move(vertices), to_world(0.5 * (lower + upper)));
  }
  // The floor and the two side walls of a turned rig, as rigid bodies in rig coordinates.
  std::vector<cosmpm::contact::RigidBody<2>> walls(const Case& c) const {
    const double l = c.grid_length;
    const double h = c.grid_height;
    return {box(Vec2(-wall_, -wall_), Vec2(l + wall_, 0.0)), box(Vec2(-wall_, 0.0), Vec2(0.0, h)),
            box(Vec2(l, 0.0), Vec2(l + wall_, h))};
  }
  // The blade, a thin rectangle standing on the floor, still while the layer settles, then
  // moving at the blade speed, its edge 1 the face that cuts; before it, a turned rig's floor
  // and side walls (bodies 0-2). The blade comes last so that where it and the floor share a
  // node its correction stands and the force it records is applied. Returns its index.
  int add_bodies(const Case& c, bool polar, cosmpm::contact::RigidContact<2>& law) const {
    using cosmpm::contact::Interface;
    if (turned()) {
      const auto bodies = walls(c);
      for (std::size_t w = 0; w < bodies.size(); ++w) {
        Interface wall = w > 0                ? Interface::frictionless()
                         : c.floor == "fixed" ? Interface::fixed()
                                              : Interface::coulomb_angle(c.floor_friction_deg);
        if (polar) wall.with_rotation_held();  // as on the unturned rig's grid faces
        law.add_body(bodies[w], wall);
      }
    }
    const double face_x = c.blade_start + c.blade_thickness;
    auto blade = box(Vec2(c.blade_start, 0.0), Vec2(face_x, c.blade_height));
    const double start_time = c.equilibrium_time;
    const Vec2 velocity = direction(Vec2(c.blade_speed, 0.0));
    blade.set_velocity(cosmpm::contact::RigidBody<2>::VelocityLaw([start_time, velocity](double t) {
      return t < start_time ? Vec2(Vec2::Zero()) : velocity;
    }));
    Interface interface = Interface::coulomb_angle(c.wall_friction_deg);
    if (polar && c.blade_rotation == "held") interface.with_rotation_held();
    if (polar && c.blade_rotation == "coupled")
      interface.with_grain_rotation_coupled(c.grain_radius);
    return law.add_body(std::move(blade), interface);
  }
  // The soil layer's outline (rig x from x_start to the right wall, y from 0 to the depth).
  std::vector<Vec2> layer(const Case& c, double x_start) const {
    return {to_world(Vec2(x_start, 0.0)), to_world(Vec2(c.grid_length, 0.0)),
            to_world(Vec2(c.grid_length, c.soil_depth)), to_world(Vec2(x_start, c.soil_depth))};
  }

 private:
  double angle_;
  double cos_, sin_;
  Vec2 cell_;
  Vec2 origin_ = Vec2::Zero();
  Vec2 extent_ = Vec2::Zero();
  std::array<cosmpm::Index, 2> cells_{};
  double wall_ = 0.0;
};

}  // namespace flat_blade
