#pragma once
// MUSL's remap: the particles' updated momenta (and rotational momenta) mapped back to the grid
// at the stencils of the step's first map, as the grid mass was, for the strain rate. The
// per-particle terms and the node velocities are shared with the fused MUSL pass
// (stages/fused_pass.hpp, map_to_particles_and_remap), which sums them in another order.
#include <algorithm>
#include <array>
#include <cstddef>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "cosmpm/stages/grid_update.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/records.hpp"

namespace cosmpm::stages {

namespace detail {

// MUSL's remap record: momentum, the rotational momenta, then an affine transfer's terms.
template <class State>
inline constexpr int remap_terms = State::dim + State::rotational_dofs + State::affine_terms;
// Its width in doubles: three terms (2D Cosserat, 3D classical) padded with a zero to a pack
// of four, one pack per node. Three doubles per node put a pack across two nodes, which met
// part of the last particle's store to a shared node and waited for it to reach the cache
// (docs/performance.md, "The remap record padded").
template <class State>
inline constexpr int remap_components =
    remap_terms<State> == 3 && pack_width == 4 ? 4 : remap_terms<State>;

// Particle p's updated momenta added to the remap records at its start-of-step stencil st.
template <class State>
COSMPM_ALWAYS_INLINE void remap_particle(const State& s, Index p,
                                         const typename State::stencil_type& st,
                                         const shape::StencilGrid<State::dim>& stencil_grid,
                                         double* records) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Continuum = typename State::continuum_type;
  const auto& v = s.particles.template get<particles::field::Velocity<Dim>>();
  const double mass = s.particles.template get<particles::field::Mass>()[p];
  std::array<double, remap_components<State>> weighted{};  // the padding stays +0
  momentum_terms<State>(s.particles, p, mass, v[p], st, s.stencil_cells[p], stencil_grid,
                        weighted.data(), weighted.data() + Dim + R);
  if constexpr (R > 0) {
    const auto inertia = Continuum::rotational_inertia(s.particles, p, mass);
    const auto spin = Continuum::rotational_velocity(s.particles, p);
    for (int k = 0; k < R; ++k) weighted[Dim + k] = inertia[k] * spin[k];
  }
  shape::scatter<remap_components<State>>(st, records, weighted, {});
}

// The remap records of s.scatter, sized for the grid (and for the later maps' records),
// zeroed in the node range (the start-of-step stencils lie in it; no other record is read).
template <class State>
double* clear_remap_records(State& s) {
  const std::size_t nodes = static_cast<std::size_t>(s.grid.node_count());
  constexpr auto all = static_cast<std::size_t>(State::scatter_record::all);
  s.scatter.resize(std::max(s.scatter.size(), all * nodes));
  s.prescattered = false;
  discard_pending_upper(s);
  constexpr Index width = remap_components<State>;
  zero_records_for_writing(s, width * s.node_range.first, width * s.node_range.end);
  return s.scatter.data();
}

// nodes.spin[i] for i in [first, end): the moment of momentum it holds over the rotational
// inertia, 0 at a node without mass. On packs where one dof per node lets the mass be read
// as one (a division per node of its own in the node loop made the Cosserat remap's node pass
// 3 times the classical one); each lane's arithmetic is the scalar loop's.
template <int R, class Nodes>
void spins_from_momenta(Nodes& nodes, Index first, Index end, double empty) {
  const double* const mass = nodes.mass.data();
  const double* const inertia = nodes.rotational_inertia.data();
  double* const spin = nodes.spin.data();
  Index i = first;
  if constexpr (R == 1 && pack_width > 1) {
    constexpr int W = pack_width;
    using P = Pack<W>;
    using cosmpm::detail::load_pack;
    using cosmpm::detail::store_pack;
    for (; i + W <= end; i += W) {
      const auto held = load_pack<W>(mass + i) <= empty;
      const P j = held ? P{} + 1.0 : load_pack<W>(inertia + i);
      store_pack<W>(spin + i, held ? P{} : load_pack<W>(spin + i) / j);
    }
  }
  for (; i < end; ++i) spin[i] = mass[i / R] <= empty ? 0.0 : spin[i] / inertia[i];
}

// The remapped node velocities (and spins) from the remap records, then contact (its
// remapped-velocity phase, with the step's dt) and the boundary conditions.
template <class State>
void velocities_from_remap(State& s, double* records, double dt) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  constexpr int C = remap_components<State>;
  auto& nodes = s.nodes;
  const NodeRange range = s.node_range;
  const double empty = s.empty_node_mass();
  const PendingUpper pending = take_pending_upper(s, C);
  parallel_region(s.threads, range.size(), [&] {
    const Share share = node_share(range);  // the node loops' static shares
    // Locals: the region's shared variables are read through a pointer, reloaded per node.
    const double empty_mass = empty;
    const double* const mass = nodes.mass.data();
    Vec<Dim>* const velocity = nodes.velocity.data();
    double* const spin = nodes.spin.data();
    for (const RecordRun run : complete_records(pending, records, share.first, share.last)) {
      for (Index n = run.first; n < run.last; ++n) {
        double* const record = run.records + n * C;
        if (mass[n] <= empty_mass) {
          velocity[n].setZero();
        } else {
          velocity[n] = nodal_momentum(s, n, record, record + Dim + R) / mass[n];
        }
        for (int k = 0; k < R; ++k) spin[n * R + k] = record[Dim + k];  // divided below
        std::fill(record, record + C, 0.0);  // for the next writer (stages/records.hpp)
      }
    }
    if constexpr (R > 0) spins_from_momenta<R>(nodes, share.first * R, share.last * R, empty);
  });
  records_read_and_zeroed(s, range.first * C, range.end * C);
  correct_and_apply_conditions(s, nodes.velocity, nodes.spin, dt,
                               contact::Phase::remapped_velocity);
}

}  // namespace detail

// MUSL: maps the updated particle momenta back to the grid (with the start-of-step stencils,
// as the grid mass was) into nodes.velocity (and spin), for the strain rate; contact (its
// remapped-velocity phase, with the step's dt) and boundary conditions apply to it.
template <class State>
void remap_momentum(State& s, double dt) {
  require_start_stencils(s, "remap_momentum");
  double* const records = detail::clear_remap_records(s);
  const shape::StencilGrid<State::dim> stencil_grid(s.grid);
  // Inlined: GCC left the Cosserat, 3D, B-spline and GIMP lambdas out of line, a call per
  // particle that reloaded every array's address (docs/performance.md, "The remap inlined").
  s.blocks.for_each_coloured(s.threads, s.particles.size(), [&](Index p) COSMPM_INLINE_LAMBDA {
    typename State::stencil_type st;
    start_stencil(s, p, stencil_grid, st);
    detail::remap_particle(s, p, st, stencil_grid, records);
  });
  detail::velocities_from_remap(s, records, dt);
}

}  // namespace cosmpm::stages
