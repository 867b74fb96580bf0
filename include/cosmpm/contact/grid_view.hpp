#pragma once
// What a contact law sees of the grid in each phase of a step it joins (contact/concept.hpp).
#include <span>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"

namespace cosmpm::contact {

// The nodal velocity fields a law can correct.
enum class Phase {
  start_velocity,     // v^t from the particles' momenta (USF strains with it)
  end_velocity,       // v^{t+dt} after the momentum update: the contact impulse of the step
  remapped_velocity,  // MUSL's v^{t+dt} remapped from the updated particles
};

// The velocity phases: node masses and one velocity field to correct.
template <int Dim>
struct GridView {
  const grid::Grid<Dim>& grid;
  const std::vector<double>& mass;
  std::vector<Vec<Dim>>& velocity;
  double empty_mass;  // nodes at or below it hold no material
  double dt;
  double time;  // at the start of the step
  Phase phase;
  // The nodal rates of the continuum's rotational degrees of freedom in the same phase
  // (Cosserat 2D: the micro-spin, one per node), so a law can hold the rotation at a body;
  // empty for a classical continuum.
  std::span<double> spin = {};
  // Radius, in cells, of a node's shape-function support: a body whose material comes closer
  // than this (per axis) puts mass on the node. The simulation passes node_reach<Kernel>().
  double node_reach = 1.0;
  // After the boundary conditions (conditions_applied): per node, bit d set where a face
  // condition imposed velocity component d kinematically (grid::BoundaryConditions::apply);
  // empty in the correction itself.
  std::span<const unsigned char> imposed = {};
  // In the correction itself: per node, the components the face conditions will impose on
  // this field (the same bits, found by applying them to a copy of it); empty if unknown.
  std::span<const unsigned char> held = {};
  // The particles where the field was mapped from (the engine's positions at the start of the
  // step; MUSL's remapped phase: at its end) and their half-widths in cell units, for laws
  // that look at the material's own geometry (RigidContact's gap check).
  std::span<const Vec<Dim>> particle_positions = {};
  std::span<const Vec<Dim>> particle_half_widths = {};
  // The nodal rotational inertia sum_p N_ip m_p J_p beside `spin` (Cosserat 2D), for laws that
  // apply moments at a body (Interface::Rotation::coupled); empty for a classical continuum.
  std::span<const double> rotational_inertia = {};
};

// The force phase, before the momentum update: a law adds its contact forces (penalty laws)
// to the nodal forces, which then act like any other force (damping included).
template <int Dim>
struct ForceView {
  const grid::Grid<Dim>& grid;
  const std::vector<double>& mass;
  const std::vector<Vec<Dim>>& momentum;  // at the start of the step
  std::vector<Vec<Dim>>& force;           // internal and external so far
  // Moments on the continuum's rotational degrees of freedom (empty for a classical one).
  std::span<double> moment;
  double empty_mass;
  double dt;
  double time;  // at the start of the step
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

}  // namespace cosmpm::contact
