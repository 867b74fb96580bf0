#pragma once
// The grid update's conditions on the nodal velocity fields: the contact law's view of a field,
// the boundary conditions (the grid's faces, the continuum's rotation conditions) and a
// velocity phase's order of contact correction and conditions; and, where contact leaves them
// alone, the conditions applied to each thread's share of the nodes (stages/grid_update.hpp).
#include <span>
#include <utility>
#include <vector>

#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::stages {

// The contact law's view of one nodal velocity field (and the rotational rates of the same
// phase).
template <class State>
contact::GridView<State::dim> contact_view(State& s, std::vector<Vec<State::dim>>& velocity,
                                           std::vector<double>& spin, double dt,
                                           contact::Phase phase) {
  constexpr int Dim = State::dim;
  contact::GridView<Dim> view{s.grid,
                              s.nodes.mass,
                              velocity,
                              s.empty_node_mass(),
                              dt,
                              s.clock.time,
                              phase,
                              std::span<double>(spin),
                              contact::node_reach<typename State::kernel_type>()};
  view.particle_positions = s.particles.template get<particles::field::Position<Dim>>();
  view.particle_half_widths = s.particles.template get<particles::field::HalfWidth<Dim>>();
  if constexpr (State::rotational_dofs > 0) view.rotational_inertia = s.nodes.rotational_inertia;
  return view;
}

// The grid's face conditions on a velocity field and the continuum's on its rotational rates.
template <class State>
void apply_conditions(const State& s, std::vector<Vec<State::dim>>& velocity,
                      std::vector<double>& spin) {
  grid::apply_boundary_conditions(s.boundary, s.grid, velocity);
  if constexpr (State::rotational_dofs > 0) s.continuum.apply_rotation_conditions(s.grid, spin);
}

// A velocity phase: the contact law's correction (if it joins the velocity phases), then the
// boundary conditions, whose imposed components win, then the law's reconciliation with the
// components the conditions imposed.
template <class State>
void correct_and_apply_conditions(State& s, std::vector<Vec<State::dim>>& velocity,
                                  std::vector<double>& spin, double dt, contact::Phase phase) {
  using Contact = decltype(s.contact);
  constexpr int Dim = State::dim;
  if constexpr (contact::CorrectsVelocities<Contact, Dim>) {
    auto view = contact_view(s, velocity, spin, dt, phase);
    if constexpr (contact::ReconcilesConditions<Contact, Dim>) {
      // What the face conditions will impose, so friction acts on the slip they leave.
      s.held.assign(static_cast<std::size_t>(s.grid.node_count()), 0);
      s.held_scratch = velocity;
      grid::apply_boundary_conditions(s.boundary, s.grid, s.held_scratch, &s.held);
      view.held = s.held;
    }
    s.contact.correct(view);
  }
  if constexpr (contact::ReconcilesConditions<Contact, Dim>) {
    s.imposed.assign(static_cast<std::size_t>(s.grid.node_count()), 0);
    grid::apply_boundary_conditions(s.boundary, s.grid, velocity, &s.imposed);
    if constexpr (State::rotational_dofs > 0) s.continuum.apply_rotation_conditions(s.grid, spin);
    auto view = contact_view(s, velocity, spin, dt, phase);
    view.imposed = s.imposed;
    s.contact.conditions_applied(view);
  } else {
    apply_conditions(s, velocity, spin);
  }
}

namespace detail {

// Whether the grid update applies the boundary conditions to each thread's share of the nodes
// inside its node pass: where the contact law neither corrects the velocities nor reconciles
// them with the conditions, and the continuum's rotation conditions can be applied to a share.
// Every condition acts on one node's own values, so each node sees what the passes apart gave it;
// the face nodes that no particle reaches keep the values the conditions left them.
template <class State>
inline constexpr bool conditions_in_shares = [] {
  using Contact = decltype(std::declval<State&>().contact);
  constexpr int Dim = State::dim;
  if constexpr (contact::CorrectsVelocities<Contact, Dim> ||
                contact::ReconcilesConditions<Contact, Dim>) {
    return false;
  } else if constexpr (State::rotational_dofs == 0) {
    return true;
  } else {
    return requires(const typename State::continuum_type& c, const grid::Grid<Dim>& g,
                    std::span<double> spin) {
      c.apply_rotation_conditions(g, spin, Index{}, Index{});
    };
  }
}();

// apply_conditions to the start (momentum) and end velocities of the nodes [first, last).
template <class State>
void apply_conditions_in(State& s, Index first, Index last) {
  auto& nodes = s.nodes;
  grid::apply_boundary_conditions(s.boundary, s.grid, nodes.momentum.data(), first, last);
  if constexpr (State::rotational_dofs > 0) {
    s.continuum.apply_rotation_conditions(s.grid, nodes.spin_momentum, first, last);
  }
  grid::apply_boundary_conditions(s.boundary, s.grid, nodes.velocity.data(), first, last);
  if constexpr (State::rotational_dofs > 0) {
    s.continuum.apply_rotation_conditions(s.grid, nodes.spin, first, last);
  }
}

}  // namespace detail

}  // namespace cosmpm::stages
