#pragma once
// Stage 2, the grid update: nodal velocity and acceleration from momentum and force (lumped
// mass), local damping, the contact law's phases and the boundary conditions (those two in
// stages/grid_conditions.hpp).
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/stages/grid_conditions.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/records.hpp"

namespace cosmpm::stages {

// USF: the start-of-step velocity (and spin) from the momentum the particles mapped, in
// place; contact and boundary conditions apply to it.
template <class State>
void grid_velocity_from_momentum(State& s, double dt) {
  constexpr int R = State::rotational_dofs;
  const double empty = s.empty_node_mass();
  auto& nodes = s.nodes;
  for (Index n = s.node_range.first; n < s.node_range.end; ++n) {
    if (nodes.mass[n] <= empty) {
      nodes.momentum[n].setZero();
      for (int k = 0; k < R; ++k) nodes.spin_momentum[n * R + k] = 0.0;
      continue;
    }
    nodes.momentum[n] /= nodes.mass[n];
    for (int k = 0; k < R; ++k)
      nodes.spin_momentum[n * R + k] /= nodes.rotational_inertia[n * R + k];
  }
  correct_and_apply_conditions(s, nodes.momentum, nodes.spin_momentum, dt,
                               contact::Phase::start_velocity);
}

namespace detail {

// The grid update's momentum update of one node, its constants and node arrays held by value.
// Made inside each thread's region, they stay in registers; the region's shared variables (and
// a lambda's captures) are read through a pointer, and were reloaded per node.
template <int Dim>
struct NodeMomentumUpdate {
  double dt;
  double damping;
  const Vec<Dim>* force;
  Vec<Dim>* momentum;
  Vec<Dim>* velocity;

  // Cundall: oppose the motion with a fraction of the unbalanced force, per component.
  COSMPM_ALWAYS_INLINE static double damped(double damping, double force, double rate) {
    const double sign = rate > 0.0 ? 1.0 : (rate < 0.0 ? -1.0 : 0.0);
    return force - damping * std::abs(force) * sign;
  }
  // From the start velocity v_start: momentum becomes v_start, velocity the trial end velocity.
  COSMPM_ALWAYS_INLINE void operator()(Index n, double inverse_mass,
                                       const Vec<Dim>& v_start) const {
    (*this)(n, inverse_mass, v_start, force[n]);
  }
  // ... with the node's force f at hand.
  COSMPM_ALWAYS_INLINE void operator()(Index n, double inverse_mass, const Vec<Dim>& v_start,
                                       Vec<Dim> f) const {
    if (damping > 0.0) {
      for (int d = 0; d < Dim; ++d) f[d] = damped(damping, f[d], v_start[d]);
    }
    momentum[n] = v_start;
    velocity[n] = v_start + (dt * inverse_mass) * f;
  }
  COSMPM_ALWAYS_INLINE void clear(Index n) const {
    momentum[n].setZero();
    velocity[n].setZero();
  }
};

template <int Dim, class Nodes>
NodeMomentumUpdate<Dim> node_momentum_update(Nodes& nodes, double dt, double damping) {
  return {dt, damping, nodes.force.data(), nodes.momentum.data(), nodes.velocity.data()};
}

// The accelerations of the nodes [first, last) and their records for the grid-to-particle map,
// which reads each node's velocity and acceleration as one record.
template <class State>
COSMPM_ALWAYS_INLINE void write_gather_records(State& s, double inverse_dt, Index first,
                                               Index last) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::gather_record;
  auto& nodes = s.nodes;
  // Locals, as the momentum update's.
  double* const gathered = s.gather.data();
  const Vec<Dim>* const velocity = nodes.velocity.data();
  const Vec<Dim>* const start_velocity = nodes.momentum.data();
  Vec<Dim>* const acceleration = nodes.acceleration.data();
  const double* const spin = nodes.spin.data();
  const double* const start_spin = nodes.spin_momentum.data();
  double* const spin_acceleration = nodes.spin_acceleration.data();
  for (Index n = first; n < last; ++n) {
    acceleration[n] = (velocity[n] - start_velocity[n]) * inverse_dt;
    double* const record = gathered + n * Record::all;
    for (int d = 0; d < Dim; ++d) {
      record[Record::velocity + d] = velocity[n][d];
      record[Record::acceleration + d] = acceleration[n][d];
    }
    for (int k = 0; k < R; ++k) {
      const auto i = n * R + k;
      spin_acceleration[i] = (spin[i] - start_spin[i]) * inverse_dt;
      record[Record::spin + k] = spin[i];
      record[Record::spin_acceleration + k] = spin_acceleration[i];
    }
  }
}

// update_grid; from_records: the node fields first taken from the particle-to-grid records
// (nodes_from_records) in the same node pass, where contact neither adds forces nor corrects
// the start velocity (map_and_update_grid checks).
template <bool from_records, class State>
void update_grid_pass(State& s, double dt) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::gather_record;
  auto& nodes = s.nodes;
  const double empty = s.empty_node_mass();
  const Index count = s.grid.node_count();
  const Index first = s.node_range.first;  // the node passes skip nodes no particle reaches
  const Index end = s.node_range.end;
  if constexpr (contact::AddsForces<decltype(s.contact), Dim>) {
    contact::ForceView<Dim> view{s.grid,
                                 nodes.mass,
                                 nodes.momentum,
                                 nodes.force,
                                 std::span<double>(nodes.moment),
                                 empty,
                                 dt,
                                 s.clock.time,
                                 contact::node_reach<typename State::kernel_type>()};
    s.contact.add_forces(view);
  }
  const double damping = s.parameters.damping;
  s.gather.resize(static_cast<std::size_t>(Record::all * count));
  const double shared_inverse_dt = 1.0 / dt;
  // The rotational rates of nodes [first_node, end_node) likewise, from their start spins in
  // spin_momentum (as rates when spin_is_rate, else as moments of momentum); a node without
  // mass takes zero rates. A loop of its own, on packs where one dof per node and no damping
  // let it (the scalar loop's three divisions per node made the Cosserat grid update take 1.8
  // times the classical one); each lane's arithmetic is the scalar loop's.
  const auto update_rotations = [&](Index first_node, Index end_node, bool spin_is_rate) {
    const double step = dt, empty_mass = empty, spin_damping = damping;  // in registers
    const double* const mass = nodes.mass.data();
    const double* const inertia = nodes.rotational_inertia.data();
    const double* const moment = nodes.moment.data();
    double* const spin_momentum = nodes.spin_momentum.data();
    double* const spin = nodes.spin.data();
    Index i = first_node * R;
    if constexpr (R == 1 && pack_width > 1) {
      constexpr int W = pack_width;
      using P = Pack<W>;
      using cosmpm::detail::load_pack;
      using cosmpm::detail::store_pack;
      for (; spin_damping == 0.0 && i + W <= end_node; i += W) {
        const auto live = load_pack<W>(mass + i) > empty_mass;
        const P j = live ? load_pack<W>(inertia + i) : P{} + 1.0;
        const P momentum = load_pack<W>(spin_momentum + i);
        const P start = spin_is_rate ? momentum : momentum / j;
        store_pack<W>(spin_momentum + i, live ? start : P{});
        store_pack<W>(spin + i, live ? start + step * load_pack<W>(moment + i) / j : P{});
      }
    }
    for (; i < end_node * R; ++i) {
      if (mass[i / R] <= empty_mass) {
        spin_momentum[i] = spin[i] = 0.0;
        continue;
      }
      const double spin_start = spin_is_rate ? spin_momentum[i] : spin_momentum[i] / inertia[i];
      double m = moment[i];
      if (spin_damping > 0.0) m = NodeMomentumUpdate<Dim>::damped(spin_damping, m, spin_start);
      spin_momentum[i] = spin_start;
      spin[i] = spin_start + step * m / inertia[i];
    }
  };
  if (contact::corrects_start_of_step(s.contact)) {
    // Nairn, Hammerquist and Smith (2020): contact corrects the start velocity as well, so
    // the trial velocity, and the impulse recorded at the end, start from a field that does
    // not penetrate. The correction is not an acceleration: FLIP particles do not receive it.
    grid_velocity_from_momentum(s, dt);
    parallel_region(s.threads, end - first, [&] {
      const Share share = node_share(s.node_range);
      const auto update_node = node_momentum_update<Dim>(nodes, dt, damping);
      const double* const mass = nodes.mass.data();
      const double empty_mass = empty;
      for (Index n = share.first; n < share.last; ++n) {
        if (mass[n] <= empty_mass) {
          update_node.clear(n);
          continue;
        }
        update_node(n, 1.0 / mass[n], Vec<Dim>(update_node.momentum[n]));
      }
      if constexpr (R > 0) update_rotations(share.first, share.last, /*spin_is_rate=*/true);
    });
  } else {
    constexpr Index size = State::scatter_record::all;
    double* const scattered = s.scatter.data();
    const PendingUpper pending = from_records ? take_pending_upper(s, size) : PendingUpper{};
    parallel_region(s.threads, end - first, [&] {
      const Share share = node_share(s.node_range);
      const auto update_node = node_momentum_update<Dim>(nodes, dt, damping);
      const double* const mass = nodes.mass.data();
      const double empty_mass = empty;
      const auto targets = node_record_targets(s);
      const auto update_nodes = [&](Index run_first, Index run_last,
                                    double* records) COSMPM_INLINE_LAMBDA {
        for (Index n = run_first; n < run_last; ++n) {
          if constexpr (from_records) {
            // The node's fields from its record, and on in registers: one node pass less.
            const auto taken = node_from_record<true>(s, targets, n, records + n * size);
            if (taken.mass <= empty_mass) {
              update_node.clear(n);
              continue;
            }
            const double inverse_mass = 1.0 / taken.mass;  // one division per node, not 2 Dim
            update_node(n, inverse_mass, Vec<Dim>(taken.momentum * inverse_mass), taken.force);
          } else {
            const double m = mass[n];
            if (m <= empty_mass) {
              update_node.clear(n);
              continue;
            }
            const double inverse_mass = 1.0 / m;
            update_node(n, inverse_mass, Vec<Dim>(update_node.momentum[n] * inverse_mass));
          }
        }
      };
      if constexpr (from_records) {
        for (const RecordRun run : complete_records(pending, scattered, share.first, share.last))
          update_nodes(run.first, run.last, run.records);
      } else {
        update_nodes(share.first, share.last, scattered);
      }
      if constexpr (R > 0) update_rotations(share.first, share.last, /*spin_is_rate=*/false);
      if constexpr (conditions_in_shares<State>) {
        // No barrier and no serial pass between: each node's own values, in its thread.
        apply_conditions_in(s, share.first, share.last);
        write_gather_records(s, shared_inverse_dt, share.first, share.last);
      }
    });
    if constexpr (from_records) records_read_and_zeroed(s, first * size, end * size);
    if constexpr (conditions_in_shares<State>) return;
  }
  // Contact corrects the updated velocity, so the acceleration (and through FLIP the
  // particles) carries the step's impulse; boundary conditions come last and win.
  apply_conditions(s, nodes.momentum, nodes.spin_momentum);
  correct_and_apply_conditions(s, nodes.velocity, nodes.spin, dt, contact::Phase::end_velocity);
  parallel_region(s.threads, end - first, [&] {
    const Share share = node_share(s.node_range);
    write_gather_records(s, shared_inverse_dt, share.first, share.last);
  });
}

}  // namespace detail

// The grid update proper. Afterwards nodes.momentum holds the start velocity v^t,
// nodes.velocity the end velocity v^{t+dt} and nodes.acceleration (v^{t+dt} - v^t) / dt; the
// gather records of the grid-to-particle map are filled.
template <class State>
void update_grid(State& s, double dt) {
  detail::update_grid_pass</*from_records=*/false>(s, dt);
}

namespace detail {

// update_grid after a particle-to-grid pass with forces left its sums in the records: the node
// fields taken from them in the grid update's own node pass, or first in a pass of their own
// where contact needs every node's fields before the update (added forces, a corrected start
// velocity).
template <class State>
void update_grid_from_records(State& s, double dt) {
  constexpr bool adds_forces = contact::AddsForces<decltype(s.contact), State::dim>;
  if (adds_forces || contact::corrects_start_of_step(s.contact)) {
    nodes_from_records(s, /*with_forces=*/true);
    update_grid_pass</*from_records=*/false>(s, dt);
  } else {
    update_grid_pass</*from_records=*/true>(s, dt);
  }
}

}  // namespace detail

// map_to_grid(s, true), then update_grid(s, dt), with the same results; the node fields are
// taken from the particle-to-grid records in the grid update's node pass, one node pass less
// (docs/performance.md, "The node fields in the grid update").
template <class State>
void map_and_update_grid(State& s, double dt) {
  detail::scatter_to_records(s, /*with_forces=*/true);
  detail::update_grid_from_records(s, dt);
}

}  // namespace cosmpm::stages
