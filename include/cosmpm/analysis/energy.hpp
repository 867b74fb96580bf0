#pragma once
// Kinetic energy from the grid nodes and from the particles, and the gravitational potential
// energy of the particles. In 2D plane strain every energy is per unit thickness (J/m).
//
// The two kinetic energies differ, and near fixed nodes the particles' one misleads
// (docs/theory/analysis.md): FLIP adds the nodal velocity *change* to a particle's velocity,
// while the particle moves with the nodal velocity itself. At a fixed node both the start and
// the end velocity are zero, so a particle next to it keeps whatever velocity it carries
// while it does not move: its kinetic energy never decays although nothing moves. The grid's
// kinetic energy is that of the velocity field the particles actually move with.
#include <cstddef>
#include <span>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

// Sum over nodes of m v^2 / 2; nodes without mass contribute nothing.
template <int Dim>
double grid_kinetic_energy(std::span<const double> node_mass,
                           std::span<const Vec<Dim>> node_velocity) {
  detail::require_same_size("analysis::grid_kinetic_energy", "node_mass", node_mass.size(),
                            "node_velocity", node_velocity.size());
  double energy = 0.0;
  for (std::size_t n = 0; n < node_mass.size(); ++n) {
    if (node_mass[n] > 0.0) energy += 0.5 * node_mass[n] * node_velocity[n].squaredNorm();
  }
  return energy;
}

// The grid kinetic energy of a simulation's last step: node mass and the nodal velocity the
// particles moved with (the updated velocity after contact and boundary conditions; MUSL:
// the remapped one).
template <class Sim>
requires requires(const Sim& sim) {
  sim.nodes().mass;
  sim.nodes().velocity;
}
double grid_kinetic_energy(const Sim& sim) {
  constexpr int Dim = Sim::dim;
  return grid_kinetic_energy<Dim>(std::span<const double>(sim.nodes().mass),
                                  std::span<const Vec<Dim>>(sim.nodes().velocity));
}

// Sum over particles of m v^2 / 2.
template <int Dim>
double particle_kinetic_energy(std::span<const double> mass, std::span<const Vec<Dim>> velocity) {
  detail::require_same_size("analysis::particle_kinetic_energy", "mass", mass.size(), "velocity",
                            velocity.size());
  double energy = 0.0;
  for (std::size_t p = 0; p < mass.size(); ++p) energy += 0.5 * mass[p] * velocity[p].squaredNorm();
  return energy;
}

// The particles' kinetic energy of a store or a simulation.
template <class Source>
double particle_kinetic_energy(const Source& source) {
  constexpr int Dim = detail::dimension_of<Source>;
  const auto& store = detail::particles_of(source);
  return particle_kinetic_energy<Dim>(
      std::span<const double>(store.template get<particles::field::Mass>()),
      std::span<const Vec<Dim>>(store.template get<particles::field::Velocity<Dim>>()));
}

// -sum m g . x: the gravitational potential energy relative to the origin (only its changes
// mean something). `gravity` is the acceleration vector, e.g. (0, -9.81).
template <class Source>
double potential_energy(const Source& source, const Vec<detail::dimension_of<Source>>& gravity) {
  constexpr int Dim = detail::dimension_of<Source>;
  const auto& store = detail::particles_of(source);
  const auto& mass = store.template get<particles::field::Mass>();
  const auto& x = store.template get<particles::field::Position<Dim>>();
  double energy = 0.0;
  for (std::size_t p = 0; p < mass.size(); ++p) energy -= mass[p] * gravity.dot(x[p]);
  return energy;
}

}  // namespace cosmpm::analysis
