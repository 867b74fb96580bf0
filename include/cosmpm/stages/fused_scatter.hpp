#pragma once
// The fused passes' scatter of the next step's records (stages/fused_pass.hpp): a particle's
// stencil at its new position and its terms in the node records, one particle or one pack at
// a time, and the cut of the particles into two halves that makes the sums deterministic.
//
// Deterministic sums without colours: the particles are cut into two halves by index, and each
// half scatters into its own node records (the first into s.scatter, the second into
// s.scatter_upper), added by the node pass that reads them. Each nodal sum is (its first-half terms
// in index order) + (its second-half terms in index order), on one thread or two; so the pass runs
// on at most two threads. The sums are USL's and MUSL's terms in another order: results differ from
// the unfused schemes' by rounding (tests/simulation/fused.test.cpp bounds it).
#include <algorithm>
#include <array>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/stages/grid_to_particle.hpp"  // PackedStencilOf
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/records.hpp"
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

// A continuum whose particle-to-grid terms take packs of particles (force_contribution and
// rotational_terms of stages/particle_to_grid.hpp on packs).
template <class State, int W>
concept ScatterTermsOfPacks = requires(
    const typename State::store_type& particles,
    const std::array<Pack<W>, State::model_type::stress_type::SizeAtCompileTime>& stress,
    const Pack<W>& volume, Pack<W>* weighted, std::array<Pack<W>, State::dim>* by_gradient) {
  State::continuum_type::internal_force_coefficients(stress, volume);
  State::continuum_type::rotational_force_terms(stress, volume, weighted, by_gradient);
  State::continuum_type::rotational_inertia(particles, Index{}, volume);
  State::continuum_type::template rotational_velocity<W>(particles, Index{});
};

// Compositions whose packs scatter_next_pack scatters across the particles (shape::scatter_lanes):
// stencils of at most four nodes (bilinear, 2D), at most one rotational degree of freedom (the 2D
// Cosserat record of eight doubles), no affine terms, and a continuum whose terms take packs. The
// others scatter a pack particle by particle: with the 2D quadratic (9 nodes) and 3D linear (8)
// stencils the pack's terms spill from the registers, and the fused USL step measured 14 % and 4 %
// slower (docs/performance.md, "The scatter across particles").
template <class State, int W>
inline constexpr bool scatters_packs =
    W == 4 && State::rotational_dofs <= 1 && !State::transfer_type::affine &&
    ScatterTermsOfPacks<State, W> &&
    PackedStencilOf<State, W>::rows * State::kernel_type::support <= 4 &&
    cosmpm::detail::transposes_records;

// The stresses of W particles, one pack per component.
template <class State, int W>
using StressOfPack = std::array<Pack<W>, State::model_type::stress_type::SizeAtCompileTime>;

// scatter_particle's terms with forces for particles p, ..., p + W - 1, at their stencils st,
// formed in packs across the particles; their stresses from `held` (null: the particles').
template <class State, int W>
COSMPM_ALWAYS_INLINE void scatter_pack(const typename State::store_type& particles,
                                       const ScatterSources<State>& from, Index p,
                                       const PackedStencilOf<State, W>& st, double* records,
                                       const StressOfPack<State, W>* held) {
  constexpr int Dim = State::dim;
  constexpr int n = State::model_type::stress_type::SizeAtCompileTime;
  using Record = typename State::scatter_record;
  using P = Pack<W>;
  const P mass = cosmpm::detail::load_pack<W>(from.mass + p);
  const P volume = cosmpm::detail::load_pack<W>(from.volume + p);
  const auto v = load_by_component<W, Dim>([&](int l) { return from.v[p + l].data(); });
  const StressOfPack<State, W> stress =
      held != nullptr ? *held
                      : load_by_component<W, n>([&](int l) { return from.stress[p + l].data(); });
  std::array<P, Record::all> weighted;
  std::array<std::array<P, Dim>, Record::all - Record::weighted> by_gradient;
  weighted[Record::mass] = mass;
  for (int d = 0; d < Dim; ++d) weighted[Record::momentum + d] = mass * v[d];
  if constexpr (State::rotational_dofs > 0) {
    rotational_terms<State>(particles, p, mass, weighted.data() + Record::inertia,
                            weighted.data() + Record::spin_momentum);
  }
  force_contribution<State>(mass, volume, stress, from.gravity, weighted.data() + Record::force,
                            by_gradient);
  shape::scatter_lanes<Record::weighted>(st, records, weighted, by_gradient);
}

// scatter_next for particles p, ..., p + W - 1 in that order, their stencils computed side by
// side with each lane's arithmetic as SeparableStencil::try_compute's, so the same records. A
// pack with a lane outside the valid range goes lane by lane, which reports it. stress: the
// particles' stresses as packs, where the caller holds them (else null).
template <int W, class State>
COSMPM_ALWAYS_INLINE void scatter_next_pack(State& s, const ScatterSources<State>& from, Index p,
                                            const shape::StencilGrid<State::dim>& stencil_grid,
                                            double* records, FusedHalfReport& report,
                                            const StressOfPack<State, W>* stress = nullptr) {
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
        report.lowest_node = std::min(report.lowest_node, st.first_node[l]);
        report.highest_node = std::max(report.highest_node, st.first_node[l]);
      }
      if constexpr (scatters_packs<State, W>) {
        scatter_pack(s.particles, from, p, st, records, stress);
      } else {
        for (int l = 0; l < W; ++l) {
          const Index q = p + l;
          scatter_particle<true, State>(s.particles, from, q, st.lane(l), s.stencil_cells[q],
                                        stencil_grid, records);
        }
      }
      return;
    }
  }
  for (int l = 0; l < W; ++l) scatter_next(s, from, p + l, stencil_grid, records, report);
}

// scatter_next for particles first, ..., last - 1: packs from `first`, the rest one by one. The
// fused USL pass groups its particles the same way; a fresh scatter must too, so that it repeats
// the pass's bits where the compiler contracts multiply-adds (-march=native). stresses: the
// whole packs' stresses from `first` on, where the caller holds them (else null).
template <class State>
COSMPM_ALWAYS_INLINE void scatter_next_range(
    State& s, const ScatterSources<State>& from, Index first, Index last,
    const shape::StencilGrid<State::dim>& stencil_grid, double* records, FusedHalfReport& report,
    const StressOfPack<State, pack_width>* stresses = nullptr) {
  constexpr int W = pack_width;
  Index q = first;
  for (; q + W <= last; q += W) {
    scatter_next_pack<W>(s, from, q, stencil_grid, records, report,
                         stresses != nullptr ? stresses + (q - first) / W : nullptr);
  }
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

// Runs report = visit(first, last, records, report) over the two halves of the particles, on
// up to two threads: the first half into `lower` (zeroed, in s.scatter, C doubles per node), the
// second into s.scatter_upper, left pending for the node pass that reads the records
// (records.hpp, complete_records). The cut is a multiple of 64 (stress_update.hpp's
// runs, and a whole number of packs), so each half starts a run. visit takes the report by
// value, so it stays in registers: through a reference, every particle's Index stores (its
// block) could alias it and the pass stored it to memory per particle (fused USL +1.6 %).
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
  int team = 1;
  parallel_region(std::min(s.threads, 2), count, [&] {
    const int size = current_team_size();
    const int thread = current_thread();
    if (thread == 0) team = size;
    for (int h = thread; h < 2; h += size) {  // thread h takes half h, as schedule(static)
      reports[h] =
          visit(h == 0 ? Index{0} : cut, h == 0 ? cut : count, h == 0 ? lower : upper, reports[h]);
    }
  });
  s.fused_team = team;
  // The second half's nodes: from its lowest first node to its highest one's stencil end.
  const FusedHalfReport& second = reports[1];
  if (second.highest_node >= 0) {
    const NodeRange nodes = scattered_nodes(s, second);
    s.upper_first = nodes.first;
    s.upper_end = nodes.end;
    s.upper_width = C;
    s.lower_nodes = scattered_nodes(s, reports[0]);
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
}  // namespace detail

}  // namespace cosmpm::stages
