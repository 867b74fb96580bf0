#pragma once
// The node records of the particle-to-grid map taken into the node fields: a node's momentum
// from its record, the node arrays written by address, and the pass that takes them all
// (nodes_from_records). The grid update takes them in its own node pass
// (stages/grid_update.hpp) with the same node_from_record.
#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/records.hpp"

namespace cosmpm::stages {

// A node's momentum from its record: the scattered momentum and, for an affine transfer, the
// affine sum times the node's position from the grid origin.
template <class State>
COSMPM_ALWAYS_INLINE Vec<State::dim> nodal_momentum(const State& s, Index n, const double* momentum,
                                                    [[maybe_unused]] const double* affine) {
  constexpr int Dim = State::dim;
  Vec<Dim> out;
  for (int d = 0; d < Dim; ++d) out[d] = momentum[d];
  if constexpr (State::transfer_type::affine) {
    const auto ijk = s.grid.node_ijk(n);
    for (int d = 0; d < Dim; ++d) {
      for (int e = 0; e < Dim; ++e) {
        out[d] += affine[d * Dim + e] * (static_cast<double>(ijk[e]) * s.grid.cell_size()[e]);
      }
    }
  }
  return out;
}

namespace detail {

// The node arrays that node_from_record writes, their addresses taken once per node pass.
// Written through `s.nodes`, each Eigen store (a may-alias packet) made the compiler reload
// every array's address from the state, and a node update that read the values back waited
// on those stores: the grid update's node loop took 14-21 ns per node (docs/performance.md,
// "The grid update's records in registers").
struct NodeRecordTargets {
  double* mass;
  double* momentum;  // Dim doubles per node
  double* force;
  double* rotational_inertia;  // rotational_dofs doubles per node
  double* spin_momentum;
  double* moment;
};

template <class Field>
double* doubles_of(std::vector<Field>& field) {
  if constexpr (std::is_same_v<Field, double>) {
    return field.data();
  } else {
    static_assert(sizeof(Field) == Field::SizeAtCompileTime * sizeof(double));
    return field.empty() ? nullptr : field.data()->data();
  }
}

template <class State>
NodeRecordTargets node_record_targets(State& s) {
  auto& nodes = s.nodes;
  return {doubles_of(nodes.mass),          doubles_of(nodes.momentum),
          doubles_of(nodes.force),         doubles_of(nodes.rotational_inertia),
          doubles_of(nodes.spin_momentum), doubles_of(nodes.moment)};
}

// What node_from_record took from a record, in registers for the node pass that goes on.
template <int Dim>
struct NodeRecordValues {
  double mass;
  Vec<Dim> momentum;
  Vec<Dim> force;
};

// Node n's fields from its record of the particle-to-grid map (mass, momentum and, with
// forces, force and moments), and the record zeroed for the next writer (stages/records.hpp).
template <bool with_forces, class State>
COSMPM_ALWAYS_INLINE NodeRecordValues<State::dim> node_from_record(const State& s,
                                                                   const NodeRecordTargets& to,
                                                                   Index n, double* record) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::scatter_record;
  constexpr int C = with_forces ? Record::all : Record::weighted;
  // Read into registers and zeroed first: the node fields' stores could alias the record.
  // Momentum and force as whole vectors: built from single doubles, the Cosserat grid update
  // spilled both as one 256-bit store and read the force back as its upper half, a load that
  // waited for the store to reach the cache.
  NodeRecordValues<Dim> values;
  values.mass = record[Record::mass];
  values.force.setZero();
  if constexpr (State::transfer_type::affine) {
    values.momentum = nodal_momentum(s, n, record + Record::momentum, record + Record::affine);
  } else {
    values.momentum = Eigen::Map<const Vec<Dim>>(record + Record::momentum);
  }
  if constexpr (with_forces) values.force = Eigen::Map<const Vec<Dim>>(record + Record::force);
  std::array<double, R> inertia, spin_momentum, moment{};
  for (int k = 0; k < R; ++k) {
    inertia[k] = record[Record::inertia + k];
    spin_momentum[k] = record[Record::spin_momentum + k];
    if constexpr (with_forces) moment[k] = record[Record::moment + k];
  }
  // A constant count: a count known at run time took a call per node (USL's step +4 %).
  std::fill(record, record + C, 0.0);
  to.mass[n] = values.mass;
  for (int d = 0; d < Dim; ++d) {
    to.momentum[n * Dim + d] = values.momentum[d];
    if constexpr (with_forces) to.force[n * Dim + d] = values.force[d];
  }
  for (int k = 0; k < R; ++k) {
    to.rotational_inertia[n * R + k] = inertia[k];
    to.spin_momentum[n * R + k] = spin_momentum[k];
    if constexpr (with_forces) to.moment[n * R + k] = moment[k];
  }
  return values;
}

}  // namespace detail

// The node fields from the records of the particle-to-grid map (mass, momentum and, with
// forces, force and moments).
template <class State>
void nodes_from_records(State& s, bool with_forces) {
  using Record = typename State::scatter_record;
  // A grid distributed over several processes would sum the records of the nodes its
  // neighbours share here (halo exchange), before any node pass reads them.
  const NodeRange range = s.node_range;
  const Index size = with_forces ? Record::all : Record::weighted;  // per node
  double* const scattered = s.scatter.data();
  const detail::PendingUpper pending = detail::take_pending_upper(s, size);
  // In the node loops' static shares (as update_grid's): each thread writes the nodes it
  // updates next, where one thread writing them all cost the two-thread step 14-22 us.
  parallel_region(s.threads, range.size(), [&] {
    const Share share = node_share(range);
    const auto targets = detail::node_record_targets(s);
    for (const detail::RecordRun run :
         detail::complete_records(pending, scattered, share.first, share.last)) {
      if (with_forces) {
        for (Index n = run.first; n < run.last; ++n)
          detail::node_from_record<true>(s, targets, n, run.records + n * size);
      } else {
        for (Index n = run.first; n < run.last; ++n)
          detail::node_from_record<false>(s, targets, n, run.records + n * size);
      }
    }
  });
  detail::records_read_and_zeroed(s, range.first * size, range.end * size);
}

}  // namespace cosmpm::stages
