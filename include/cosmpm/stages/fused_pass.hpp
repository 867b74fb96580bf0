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
// Deterministic sums without colours: the particles are cut into two halves by index, and each
// half scatters into its own node records (the first into s.scatter, the second into
// s.scatter_upper), added by the node pass that reads them. Each nodal sum is (its first-half terms
// in index order) + (its second-half terms in index order), on one thread or two; so the pass runs
// on at most two threads. The sums are USL's and MUSL's terms in another order: results differ from
// the unfused schemes' by rounding (tests/simulation/fused.test.cpp bounds it).
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
#include "cosmpm/stages/grid_to_particle.hpp"
#include "cosmpm/stages/grid_update.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/records.hpp"
#include "cosmpm/stages/remap.hpp"
#include "cosmpm/stages/stress_update.hpp"

namespace cosmpm::stages {

namespace detail {

// What one half of a fused pass finds: the first particle of each kind (count for none) and
// the lowest and highest first node of its stencils.
struct alignas(64) FusedHalfReport {
  Index first_outside;
  Index first_bad;
  Index first_moved;
  Index first_invalid;  // no valid stencil at the new position
  Index lowest_node;
  Index highest_node;
};

// The next step's scatter of particle q at its current position into `records`.
template <class State>
COSMPM_ALWAYS_INLINE void scatter_next(State& s, const ScatterSources<State>& from, Index q,
                                       const shape::StencilGrid<State::dim>& stencil_grid,
                                       double* records, FusedHalfReport& report) {
  typename State::stencil_type st;
  if (!st.try_compute(stencil_grid, from.x[q], from.half[q])) [[unlikely]] {
    record_first(report.first_invalid, q);
    return;
  }
  for (int d = 0; d < State::dim; ++d) s.stencil_cells[q][d] = st.position_in_cells[d];
  report.lowest_node = std::min(report.lowest_node, st.first_node);
  report.highest_node = std::max(report.highest_node, st.first_node);
  scatter_particle<true, State>(s.particles, from, q, st, s.stencil_cells[q], stencil_grid,
                                records);
}

// Kernels whose stencils scatter_next_pack computes side by side: those that evaluate whole
// packs (Linear, the B-splines) and need no half-width check.
template <class State>
inline constexpr bool packs_next_stencils = requires(
    const Pack<pack_width>& x, std::array<Pack<pack_width>, State::kernel_type::support>& f) {
  State::kernel_type::evaluate_lanes(x, Index{}, f, f);
}
&&!shape::UsesHalfWidth<typename State::kernel_type>;

// scatter_next for particles p, ..., p + W - 1 in that order, their stencils computed side by
// side with each lane's arithmetic as SeparableStencil::try_compute's, so the same records. A
// pack with a lane outside the valid range goes lane by lane, which reports it.
template <int W, class State>
COSMPM_ALWAYS_INLINE void scatter_next_pack(State& s, const ScatterSources<State>& from, Index p,
                                            const shape::StencilGrid<State::dim>& stencil_grid,
                                            double* records, FusedHalfReport& report) {
  constexpr int Dim = State::dim;
  using K = typename State::kernel_type;
  using P = Pack<W>;
  if constexpr (W > 1 && packs_next_stencils<State> &&
                K::support <= shape::StencilGrid<Dim>::tabled_support) {
    std::array<P, Dim> xi;
    bool valid = true;
    const std::array<P, Dim> x_now =
        load_by_component<W, Dim>([&](int l) { return from.x[p + l].data(); });
    for (int d = 0; d < Dim; ++d) {
      const P x = x_now[d];
      xi[d] = (x - stencil_grid.origin[d]) * stencil_grid.inverse_cell_size[d];
      valid &=
          all_lanes<W>((xi[d] >= 0.0) & (xi[d] <= stencil_grid.upper_for_support[K::support][d]));
    }
    if (valid) [[likely]] {
      std::array<P, Dim> in_cells;
      for (int d = 0; d < Dim; ++d) {
        const P last = P{} + stencil_grid.last[d];
        in_cells[d] = xi[d] < last ? xi[d] : last;
      }
      store_by_component<W, Dim>([&](int l) { return s.stencil_cells[p + l].data(); }, in_cells);
      PackedStencilOf<State, W> st;
      st.compute_from_cell_units(
          stencil_grid, [&](int l) -> const Vec<Dim>& { return s.stencil_cells[p + l]; },
          [&](int l) -> const Vec<Dim>& { return from.half[p + l]; });
      for (int l = 0; l < W; ++l) {
        const Index q = p + l;
        report.lowest_node = std::min(report.lowest_node, st.first_node[l]);
        report.highest_node = std::max(report.highest_node, st.first_node[l]);
        scatter_particle<true, State>(s.particles, from, q, st.lane(l), s.stencil_cells[q],
                                      stencil_grid, records);
      }
      return;
    }
  }
  for (int l = 0; l < W; ++l) scatter_next(s, from, p + l, stencil_grid, records, report);
}

// scatter_next for particles first, ..., last - 1: packs from `first`, the rest one by one. The
// fused USL pass groups its particles the same way; a fresh scatter must too, so that it repeats
// the pass's bits where the compiler contracts multiply-adds (-march=native).
template <class State>
COSMPM_ALWAYS_INLINE void scatter_next_range(State& s, const ScatterSources<State>& from,
                                             Index first, Index last,
                                             const shape::StencilGrid<State::dim>& stencil_grid,
                                             double* records, FusedHalfReport& report) {
  constexpr int W = pack_width;
  Index q = first;
  for (; q + W <= last; q += W) scatter_next_pack<W>(s, from, q, stencil_grid, records, report);
  for (; q < last; ++q) scatter_next(s, from, q, stencil_grid, records, report);
}

// The nodes the stencils of a fused pass's scatter reach, from the report of a scatter of
// every particle: the node range of the step that reads its records.
template <class State>
NodeRange scattered_nodes(const State& s, const FusedHalfReport& all) {
  if (all.highest_node < 0) return {0, 0};
  std::array<Index, State::dim> last_offset;
  last_offset.fill(State::kernel_type::support - 1);
  return {all.lowest_node, all.highest_node + s.grid.node_index(last_offset) + 1};
}

// The next step's node range from the report of a scatter of every particle, which wrote the
// records (C doubles per node, all zeroed before it) only there (stages/records.hpp).
template <int C, class State>
NodeRange note_scattered_nodes(State& s, const FusedHalfReport& all) {
  const NodeRange nodes = scattered_nodes(s, all);
  records_written_within(s, C * nodes.first, C * nodes.end);
  return nodes;
}

// Runs visit(first, last, records, report) over the two halves of the particles, on up to two
// threads: the first half into `lower` (zeroed, in s.scatter, C doubles per node), the second
// into s.scatter_upper, left pending for the node pass that reads the records
// (particle_to_grid.hpp, add_pending_upper). The cut is a multiple of 64 (stress_update.hpp's
// runs, and a whole number of packs), so each half starts a run.
template <int C, class State, class Visit>
FusedHalfReport over_halves(State& s, double* const lower, Visit&& visit) {
  discard_pending_upper(s);  // as the clear of `lower` did
  const Index count = s.particles.size();
  const Index cut = count / 2 / update_run * update_run;
  s.scatter_upper.resize(s.scatter.size(), 0.0);
  double* const upper = s.scatter_upper.data();
  s.stencil_cells.resize(static_cast<std::size_t>(count));
  std::array<FusedHalfReport, 2> reports;
  for (auto& r : reports) {
    r = {count, count, count, count, s.grid.node_count(), -1};
  }
  [[maybe_unused]] const int threads = std::min(s.threads, 2);
  int team = 1;
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads) if (count >= parallel_threshold) \
    reduction(max                                                                               \
              : team)
#endif
  for (int h = 0; h < 2; ++h) {
    team = current_team_size();
    visit(h == 0 ? Index{0} : cut, h == 0 ? cut : count, h == 0 ? lower : upper, reports[h]);
  }
  s.fused_team = team;
  // The second half's nodes: from its lowest first node to its highest one's stencil end.
  const FusedHalfReport& second = reports[1];
  if (second.highest_node >= 0) {
    const NodeRange nodes = scattered_nodes(s, second);
    s.upper_first = nodes.first;
    s.upper_end = nodes.end;
    s.upper_width = C;
  }
  FusedHalfReport all = reports[0];
  all.first_outside = std::min(all.first_outside, second.first_outside);
  all.first_bad = std::min(all.first_bad, second.first_bad);
  all.first_moved = std::min(all.first_moved, second.first_moved);
  all.first_invalid = std::min(all.first_invalid, second.first_invalid);
  all.lowest_node = std::min(all.lowest_node, second.lowest_node);
  all.highest_node = std::max(all.highest_node, second.highest_node);
  return all;
}

template <VelocityUpdate update, class State>
void map_to_particles_and_grid(State& s, double dt) {
  constexpr int W = pack_width;
  require_start_stencils(s, "map_to_particles_and_grid");
  const Index count = s.particles.size();
  const auto pass = map_pass(s, dt);
  const ScatterSources<State> from = scatter_sources(s);
  constexpr int C = State::scatter_record::all;
  const FusedHalfReport all =
      over_halves<C>(s, clear_scatter_records<true>(s, all_nodes(s)),
                     [&](Index first, Index last, double* records, FusedHalfReport& r) {
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
  const auto pass = map_pass(s, dt);
  const auto remap = [&](Index p, const typename State::stencil_type& st, double* records,
                         FusedHalfReport& r) COSMPM_INLINE_LAMBDA {
    r.lowest_node = std::min(r.lowest_node, st.first_node);
    r.highest_node = std::max(r.highest_node, st.first_node);
    remap_particle(s, p, st, pass.stencil_grid, records);
  };
  double* const records = clear_remap_records(s);
  const FusedHalfReport all = over_halves<remap_components<State>>(
      s, records, [&](Index first, Index last, double* half_records, FusedHalfReport& r) {
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
        [&](Index first, Index last, double* records, detail::FusedHalfReport& r) {
          detail::scatter_next_range(s, from, first, last, stencil_grid, records, r);
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
      [&](Index first, Index last, double* records, FusedHalfReport& r) {
        for (Index begin = first; begin < last; begin += update_run) {
          const Index end = std::min(begin + update_run, last);
          // Before the scatter moves the run's stencils to the new positions.
          update_stress_of_run(s, begin, end, dt, stencil_grid, velocity_records, r.first_bad);
          scatter_next_range(s, from, begin, end, stencil_grid, records, r);
        }
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
