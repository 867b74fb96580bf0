#pragma once
// The fused schemes' particle pass (integrator/fused.hpp): the pass that ends a step also
// maps the particles to the grid for the next step. A particle's data is read once where the
// unfused step reads it twice, the next step has no particle-to-grid pass of its own, and the
// particles are visited in index order, as they lie in memory, not block by block in colour
// order (docs/performance.md, "The fused particle pass", has what each buys).
//
// - USL, map_to_particles_and_grid: the grid-to-particle map with the stress update, then the
//   particle's scatter at its new position.
// - MUSL, update_stress_and_map_to_grid: stage 4b (with the nodal fields given, 4a before it),
//   in its runs of 64, then the scatter.
// - MUSL, map_to_particles_and_remap: the grid-to-particle map, then the particle's remap of
//   its new momenta at the same stencil, so the remap is no pass of its own.
//
// The records stay valid while nothing else touches the particles. Simulation drops them when
// a user takes the particles, the continuum or the engine state for writing; every stage that
// writes the records drops them too. map_to_grid_or_reuse then scatters afresh, in the same
// order, so dropping them changes no result.
#include <algorithm>
#include <array>
#include <vector>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/stages/fused_scatter.hpp"
#include "cosmpm/stages/grid_to_particle.hpp"
#include "cosmpm/stages/grid_update.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/records.hpp"
#include "cosmpm/stages/remap.hpp"
#include "cosmpm/stages/stress_update.hpp"

namespace cosmpm::stages {

namespace detail {

template <VelocityUpdate update, class State>
void map_to_particles_and_grid(State& s, double dt) {
  constexpr int W = pack_width;
  require_start_stencils(s, "map_to_particles_and_grid");
  const Index count = s.particles.size();
  const auto shared_pass = map_pass(s, dt);
  const ScatterSources<State> from = scatter_sources(s);
  constexpr int C = State::scatter_record::all;
  const FusedHalfReport all =
      over_halves<C>(s, clear_scatter_records<true>(s, all_nodes(s)),
                     [&](Index first, Index last, double* records, FusedHalfReport r) {
                       // Its own copy: the particles' stores could alias the caller's.
                       const auto pass = shared_pass;
                       Index p = first;
                       for (; p + W <= last; p += W) {
                         PackedStencilOf<State, W> st;
                         map_from_grid<W, true, update>(s, p, pass, st, r.first_outside,
                                                        r.first_bad, r.first_moved);
                         scatter_next_pack<W>(s, from, p, pass.stencil_grid, records, r);
                       }
                       for (; p < last; ++p) {
                         PackedStencilOf<State, 1> st;
                         map_from_grid<1, true, update>(s, p, pass, st, r.first_outside,
                                                        r.first_bad, r.first_moved);
                         scatter_next(s, from, p, pass.stencil_grid, records, r);
                       }
                       return r;
                     });
  finish_map(s, all.first_outside, all.first_bad, all.first_moved);
  s.prescattered = all.first_outside == count && all.first_invalid == count;
  s.prescattered_nodes = note_scattered_nodes<C>(s, all);
}

// Fused MUSL: map_to_particles, then each particle's updated momenta back to the grid at the
// same start-of-step stencil (remap_momentum's terms), in one pass.
template <VelocityUpdate update, class State>
void map_to_particles_and_remap(State& s, double dt) {
  constexpr int W = pack_width;
  require_start_stencils(s, "map_to_particles_and_remap");
  const auto shared_pass = map_pass(s, dt);
  double* const records = clear_remap_records(s);
  const FusedHalfReport all = over_halves<remap_components<State>>(
      s, records, [&](Index first, Index last, double* half_records, FusedHalfReport r) {
        const auto pass = shared_pass;  // its own copy, as map_to_particles_and_grid's
        const auto remap = [&](Index p, const typename State::stencil_type& st, double* to,
                               FusedHalfReport& report) COSMPM_INLINE_LAMBDA {
          report.lowest_node = std::min(report.lowest_node, st.first_node);
          report.highest_node = std::max(report.highest_node, st.first_node);
          remap_particle(s, p, st, pass.stencil_grid, to);
        };
        Index p = first;
        for (; p + W <= last; p += W) {
          PackedStencilOf<State, W> st;
          map_from_grid<W, false, update>(s, p, pass, st, r.first_outside, r.first_bad,
                                          r.first_moved);
          for (int l = 0; l < W; ++l) remap(p + l, st.lane(l), half_records, r);
        }
        for (; p < last; ++p) {
          PackedStencilOf<State, 1> st;
          map_from_grid<1, false, update>(s, p, pass, st, r.first_outside, r.first_bad,
                                          r.first_moved);
          remap(p, st.lane(0), half_records, r);
        }
        return r;
      });
  finish_map(s, all.first_outside, all.first_bad, all.first_moved);
  velocities_from_remap(s, records, dt);
}

}  // namespace detail

// Fused MUSL: map_to_particles(dt) and remap_momentum(dt) in one pass over the particles, the
// remap's sums in the fused pass's order (index order, two halves) instead of colour order.
template <class State>
void map_to_particles_and_remap(State& s, double dt) {
  using detail::VelocityUpdate;
  detail::with_velocity_update(
      s, [&]<VelocityUpdate update>() { detail::map_to_particles_and_remap<update>(s, dt); });
}

namespace detail {
// map_to_grid_or_reuse's records, the node fields not yet taken.
template <class State>
void reuse_or_scatter_records(State& s) {
  constexpr int Dim = State::dim;
  const Index count = s.particles.size();
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  const auto& x = s.particles.template get<particles::field::Position<Dim>>();
  if (s.prescattered && static_cast<Index>(s.stencil_cells.size()) == count) {
    s.blocks.bucket(x, count, stencil_grid);  // the engine noted every change of block
  } else {
    s.blocks.resort(x, count, stencil_grid);  // a user may have moved particles
    const detail::ScatterSources<State> from = detail::scatter_sources(s);
    const detail::FusedHalfReport all = detail::over_halves<State::scatter_record::all>(
        s, detail::clear_scatter_records<true>(s, all_nodes(s)),
        [&](Index first, Index last, double* records, detail::FusedHalfReport r) {
          detail::scatter_next_range(s, from, first, last, stencil_grid, records, r);
          return r;
        });
    if (all.first_invalid < count) {
      typename State::stencil_type st;  // throws, naming the particle's position
      st.compute(stencil_grid, from.x[all.first_invalid], from.half[all.first_invalid]);
    }
    s.prescattered_nodes = detail::note_scattered_nodes<State::scatter_record::all>(s, all);
  }
  // The records were cleared over every node and written within these: the step's node
  // passes skip the rest (its node range set here, as map_to_grid sets it).
  set_node_range(s, s.prescattered_nodes);
  s.prescattered = false;
}
}  // namespace detail

// Fused schemes, first stage: the node fields from the records the last step's fused pass
// scattered, when they are still valid; otherwise the particles are scattered afresh, in the
// fused pass's order (index order, two halves), so a fused run's results do not depend on
// when its records were dropped (a restart, a user's change between steps). Either way the
// particles are sorted into their blocks, for any coloured stage a user's scheme calls next
// (the fused schemes themselves have none).
template <class State>
void map_to_grid_or_reuse(State& s) {
  detail::reuse_or_scatter_records(s);
  nodes_from_records(s, /*with_forces=*/true);
}

// map_to_grid_or_reuse(s), then update_grid(s, dt), the node fields taken in the grid
// update's node pass (as map_and_update_grid).
template <class State>
void map_or_reuse_and_update_grid(State& s, double dt) {
  detail::reuse_or_scatter_records(s);
  detail::update_grid_from_records(s, dt);
}

// Fused USL: map_to_particles(dt, with_stress_update = true), and the particle-to-grid map of
// the next step in the same pass. A continuum that averages the volumetric rate over cells
// (antilocking::FBar) needs every particle's rate before any stress update: it runs unfused.
template <class State>
void map_to_particles_and_grid(State& s, double dt) {
  if constexpr (averages_volume<State>) {
    map_to_particles(s, dt, /*with_stress_update=*/true);
  } else {
    using detail::VelocityUpdate;
    detail::with_velocity_update(
        s, [&]<VelocityUpdate update>() { detail::map_to_particles_and_grid<update>(s, dt); });
  }
}

namespace detail {
// Stage 4b (with 4a first, from these node records, when velocity_records is set), then the
// next step's scatter, run by run.
template <class State>
void update_stress_and_map_to_grid(State& s, double dt, const double* velocity_records) {
  const Index count = s.particles.size();
  const shape::StencilGrid<State::dim> stencil_grid(s.grid);
  const ScatterSources<State> from = scatter_sources(s);
  const FusedHalfReport all = over_halves<State::scatter_record::all>(
      s, clear_scatter_records<true>(s, all_nodes(s)),
      [&](Index first, Index last, double* records, FusedHalfReport r) {
        for (Index begin = first; begin < last; begin += update_run) {
          const Index end = std::min(begin + update_run, last);
          // Before the scatter moves the run's stencils to the new positions.
          RunStresses<State> stresses;
          update_stress_of_run(s, begin, end, dt, stencil_grid, velocity_records, r.first_bad,
                               stresses);
          scatter_next_range(s, from, begin, end, stencil_grid, records, r,
                             stresses.empty() ? nullptr : stresses.data());
        }
        return r;
      });
  if (all.first_bad < count) {
    throw_unstable_stress<State::dim, typename State::model_type>(s.particles, all.first_bad,
                                                                  s.clock);
  }
  s.prescattered = all.first_invalid == count;
  s.prescattered_nodes = note_scattered_nodes<State::scatter_record::all>(s, all);
  if (velocity_records != nullptr) s.rates_stored = false;  // handed over, not stored
}
}  // namespace detail

// Fused MUSL: update_stress(dt), and the particle-to-grid map of the next step in the same
// pass.
template <class State>
void update_stress_and_map_to_grid(State& s, double dt) {
  detail::require_rates(s, "update_stress_and_map_to_grid");
  if constexpr (averages_volume<State>) average_volumetric_rate(s);
  detail::update_stress_and_map_to_grid(s, dt, nullptr);
}

// Fused MUSL: velocity_gradient_from_grid(node_velocity, node_spin), update_stress(dt) and the
// next step's particle-to-grid map in one pass; each particle's arithmetic as in the separate
// stages, so the same bits. A continuum that averages the volumetric rate over cells
// (antilocking::FBar) needs every rate before any stress update: it runs the stages apart.
template <class State>
void update_stress_and_map_to_grid(State& s, double dt,
                                   const std::vector<Vec<State::dim>>& node_velocity,
                                   const std::vector<double>& node_spin) {
  if constexpr (averages_volume<State>) {
    velocity_gradient_from_grid(s, node_velocity, node_spin);
    update_stress_and_map_to_grid(s, dt);
  } else {
    detail::update_stress_and_map_to_grid(
        s, dt, detail::rate_records(s, node_velocity, node_spin, "update_stress_and_map_to_grid"));
  }
}

}  // namespace cosmpm::stages
