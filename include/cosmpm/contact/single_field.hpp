#pragma once
// The MPM default: one velocity field on the grid, so bodies stick where they touch.
// It is also the reference for the contact-policy interface the simulation calls:
//   correct(view)   adjusts nodal velocities after they are computed (and records forces
//                   when view.phase == Phase::end_velocity),
//   advance(dt, t)  moves whatever the law owns (rigid bodies) at the end of a step.
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"

namespace cosmpm::contact {

enum class Phase {
  start_velocity,     // v^t from the particles' momenta (USF strains with it)
  end_velocity,       // v^{t+dt} after the momentum update: the contact impulse of the step
  remapped_velocity,  // MUSL's v^{t+dt} remapped from the updated particles
};

// What a contact law sees of the grid: node masses and one velocity field to correct.
template <int Dim>
struct GridView {
  const grid::Grid<Dim>& grid;
  const std::vector<double>& mass;
  std::vector<Vec<Dim>>& velocity;
  double empty_mass;  // nodes at or below it hold no material
  double dt;
  double time;  // at the start of the step
  Phase phase;
  // Cosserat runs: the nodal micro-spin of the same phase (nullptr otherwise), so a law can
  // hold the rotation at a rigid body.
  std::vector<double>* spin = nullptr;
  // Radius, in cells, of a node's shape-function support: a body whose material comes closer
  // than this (per axis) puts mass on the node. The simulation passes node_reach<Kernel>().
  double node_reach = 1.0;
};

// The support radius of a node's basis function in cells: support / 2 for the hat and the
// B-splines; GIMP's node function is the hat (its wider stencil comes from particle size).
template <shape::Kernel K>
constexpr double node_reach() {
  if constexpr (shape::UsesHalfWidth<K>) {
    return 1.0;
  } else {
    return 0.5 * static_cast<double>(K::support);
  }
}

struct SingleField {
  static constexpr const char* name() { return "single-field no-slip"; }
  template <int Dim>
  void correct(GridView<Dim>& /*view*/) {}
  void advance(double /*dt*/, double /*time*/) {}
};

}  // namespace cosmpm::contact
