#pragma once
// Stage 4, the stress update: each particle's rates (velocity gradient; with rotational
// degrees of freedom also their rates and gradients) from a nodal field, then the continuum's
// objective update, the constitutive model's return and the deformation. USL runs the same
// per-particle pieces inside its grid-to-particle pass (stages/grid_to_particle.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/stress_space.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/stages/deformation.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/stress_run.hpp"

namespace cosmpm::stages {

// to = from, component by component: Eigen's packet stores are may-alias vector types, after
// which the compiler reloads every array pointer in the loop.
template <class Matrix>
COSMPM_ALWAYS_INLINE void store_components(Matrix& to, const Matrix& from) {
  for (Index i = 0; i < Matrix::SizeAtCompileTime; ++i) to.data()[i] = from.data()[i];
}

// Lane l's rotational rates (spin and its gradient) from such a gather, into `rates`.
template <class State, int W, class GridValues>
COSMPM_ALWAYS_INLINE void spin_rates_from(const GridValues& grid_values, int l,
                                          typename State::rates_type& rates) {
  using Record = typename State::gather_record;
  for (int k = 0; k < State::rotational_dofs; ++k) {
    rates.spin[k] = lane<W>(grid_values.value[Record::spin + k], l);
    for (int d = 0; d < State::dim; ++d) {
      rates.spin_gradient[k][d] = lane<W>(grid_values.gradient[Record::spin + k][d], l);
    }
  }
}

// Lane l's rates from a gather whose first fields (velocity, then the rotational rates) carry
// gradients.
template <class State, int W, class GridValues>
COSMPM_ALWAYS_INLINE typename State::rates_type rates_from(const GridValues& grid_values, int l) {
  constexpr int Dim = State::dim;
  using Record = typename State::gather_record;
  typename State::rates_type rates;
  for (int i = 0; i < Dim; ++i) {
    for (int j = 0; j < Dim; ++j) {
      rates.velocity_gradient(i, j) = lane<W>(grid_values.gradient[Record::velocity + i][j], l);
    }
  }
  spin_rates_from<State, W>(grid_values, l, rates);
  return rates;
}

// The constitutive update of one particle; false if the stress came out non-finite.
template <class State>
COSMPM_ALWAYS_INLINE bool update_constitutive(State& s, Index q,
                                              const typename State::rates_type& rates, double dt) {
  using Model = typename State::model_type;
  auto& stress = s.particles.template get<particles::field::Stress<Model>>()[q];
  State::continuum_type::update_stress(
      s.model(), rates, dt, stress,
      s.particles.template get<particles::field::MaterialState<Model>>()[q],
      s.particles.template get<particles::field::Strain<Model>>()[q]);
  // A non-finite component makes the sum non-finite (finite stresses near 1e308 that would
  // overflow it do not occur in soil).
  return std::isfinite(stress.sum());
}

// Whether the stress update of the grid-to-particle loop runs on packs of W particles: for
// continua and models that update packs of components (Continuum::updates_values).
template <class State, int W>
inline constexpr bool packed_stress_update =
    State::continuum_type::template updates_values<Pack<W>>;

// The stress update of particles p, ..., p + W - 1 on packs, with their velocity gradient L;
// returns the sum of each new stress's components (non-finite when one is).
template <int W, class State>
COSMPM_ALWAYS_INLINE Pack<W> update_stress_packed(
    State& s, Index p, const std::array<std::array<Pack<W>, State::dim>, State::dim>& L,
    double dt) {
  using P = Pack<W>;
  using Model = typename State::model_type;
  constexpr int n = material::symmetric_components<State::dim>;
  auto& stress = s.particles.template get<particles::field::Stress<Model>>();
  auto& strain = s.particles.template get<particles::field::Strain<Model>>();
  const auto stress_record = [&](int l) { return stress[p + l].data(); };
  const auto strain_record = [&](int l) { return strain[p + l].data(); };
  // Whole records: in plane strain the zz strain, which the update does not touch, is written
  // back as it was read.
  std::array<P, n> sigma = load_by_component<W, n>(stress_record);
  std::array<P, n> e = load_by_component<W, n>(strain_record);
  State::continuum_type::update_stress_values(s.model(), L, dt, sigma, e);
  store_by_component<W, n>(strain_record, e);
  store_by_component<W, n>(stress_record, sigma);
  if constexpr (n == 4) {
    return (sigma[0] + sigma[1]) + (sigma[2] + sigma[3]);
  } else {
    return ((sigma[0] + sigma[1]) + (sigma[2] + sigma[3])) + (sigma[4] + sigma[5]);
  }
}

namespace detail {
// Stage 4a for particles p, ..., p + W - 1 side by side (their stencils and node sums in
// packs; each lane does the one-particle arithmetic, in its order). The rates go to
// s.particle_rates, or, given `held` (W = pack_width), to it as packs for stage 4b in the same
// pass; the velocity gradient field is written either way.
template <int W, class State>
COSMPM_ALWAYS_INLINE void rates_from_grid(State& s, Index p,
                                          const shape::StencilGrid<State::dim>& stencil_grid,
                                          const double* records,
                                          PackedRates<State>* held = nullptr) {
  constexpr int Dim = State::dim;
  constexpr int size = State::gather_record::with_gradient;
  const auto& half = s.particles.template get<particles::field::HalfWidth<Dim>>();
  auto& L = s.particles.template get<particles::field::VelocityGradient<Dim>>();
  shape::PackedStencil<Dim, typename State::kernel_type, W> st;
  st.compute_from_cell_units(
      stencil_grid, [&](int l) -> const Vec<Dim>& { return s.stencil_cells[p + l]; },
      [&](int l) -> const Vec<Dim>& { return half[p + l]; });
  const auto values = shape::gather<size, size>(st, records);
  using Record = typename State::gather_record;
  // The velocity gradients to both arrays, as records (column-major: L(i, j) at i + Dim j).
  std::array<Pack<W>, Dim * Dim> gradient;
  for (int i = 0; i < Dim; ++i) {
    for (int j = 0; j < Dim; ++j) gradient[i + Dim * j] = values.gradient[Record::velocity + i][j];
  }
  store_by_component<W, Dim * Dim>([&](int l) { return L[p + l].data(); }, gradient);
  if constexpr (W == pack_width) {
    if (held != nullptr) {
      for (int i = 0; i < Dim; ++i) {
        for (int j = 0; j < Dim; ++j) held->velocity_gradient[i][j] = gradient[i + Dim * j];
      }
      for (int k = 0; k < State::rotational_dofs; ++k) {
        held->spin[k] = values.value[Record::spin + k];
        for (int d = 0; d < Dim; ++d)
          held->spin_gradient[k][d] = values.gradient[Record::spin + k][d];
      }
      return;
    }
  }
  store_by_component<W, Dim * Dim>(
      [&](int l) { return s.particle_rates[p + l].velocity_gradient.data(); }, gradient);
  for (int l = 0; l < W; ++l) spin_rates_from<State, W>(values, l, s.particle_rates[p + l]);
}
}  // namespace detail

namespace detail {
// The node records stage 4a gathers from: the velocities themselves for a classical continuum
// (laid out as the records, no copy), else velocity and rotational rates copied into
// s.rate_gather.
template <class State>
const double* rate_records(State& s, const std::vector<Vec<State::dim>>& node_velocity,
                           const std::vector<double>& node_spin, const char* where) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::gather_record;
  const Index nodes = s.grid.node_count();
  require(static_cast<Index>(node_velocity.size()) == nodes &&
              static_cast<Index>(node_spin.size()) == R * nodes,
          std::string("Simulation::") + where + ": a nodal field does not match the grid's " +
              std::to_string(nodes) + " nodes");
  require_start_stencils(s, where);
  s.particle_rates.resize(static_cast<std::size_t>(s.particles.size()));
  constexpr int size = Record::with_gradient;  // per node: velocity and the rotational rates
  if constexpr (size == Dim && sizeof(Vec<Dim>) == Dim * sizeof(double)) {
    // No parallel region for a copy: about 5 us of a two-thread step here.
    static_assert(Record::velocity == 0);
    return node_velocity.data()->data();
  } else {
    s.rate_gather.resize(static_cast<std::size_t>(size * nodes));
    const NodeRange range = s.node_range;                 // the stencils lie in it
    parallel_for(s.threads, range.size(), [&](Index i) {  // the node loops' static shares
      const Index n = range.first + i;
      double* const record = s.rate_gather.data() + n * size;
      for (int d = 0; d < Dim; ++d) record[Record::velocity + d] = node_velocity[n][d];
      for (int k = 0; k < R; ++k) record[Record::spin + k] = node_spin[n * R + k];
    });
    return s.rate_gather.data();
  }
}

// Stage 4a for particles first, ..., last - 1 on one thread: pack_width at a time from
// `first`, then the rest one by one. Given `held` (a run's, last - first <= update_run), the
// whole packs' rates go there, pack k of the range to held[k].
template <class State>
COSMPM_ALWAYS_INLINE void rates_of_range(State& s, Index first, Index last,
                                         const shape::StencilGrid<State::dim>& stencil_grid,
                                         const double* records,
                                         PackedRates<State>* held = nullptr) {
  constexpr int W = pack_width;
  Index p = first;
  for (; p + W <= last; p += W) {
    rates_from_grid<W>(s, p, stencil_grid, records,
                       held != nullptr ? held + (p - first) / W : nullptr);
  }
  for (; p < last; ++p) rates_from_grid<1>(s, p, stencil_grid, records);
}

// Stages 4a (from `records`; none: the rates are in s.particle_rates already) and 4b for the
// run of particles [begin, end), its whole packs' rates handed over as packs where 4b takes them;
// the whole packs' new stresses also in `stresses` (update_stress_run).
template <class State>
COSMPM_ALWAYS_INLINE void update_stress_of_run(State& s, Index begin, Index end, double dt,
                                               const shape::StencilGrid<State::dim>& stencil_grid,
                                               const double* records, Index& first_bad,
                                               RunStresses<State>& stresses) {
  RunRates<State> rates;
  PackedRates<State>* const held = records != nullptr && !rates.empty() ? rates.data() : nullptr;
  if (records != nullptr) rates_of_range(s, begin, end, stencil_grid, records, held);
  update_stress_run(s, begin, end - begin, dt, first_bad, stresses, held);
}
}  // namespace detail

// Stage 4a: particle rates from a nodal velocity field (and the rotational rates, ignored by a
// classical continuum), at the stencils of the start of the step.
template <class State>
void velocity_gradient_from_grid(State& s, const std::vector<Vec<State::dim>>& node_velocity,
                                 const std::vector<double>& node_spin) {
  const double* const records =
      detail::rate_records(s, node_velocity, node_spin, "velocity_gradient_from_grid");
  const shape::StencilGrid<State::dim> stencil_grid(s.grid);
  const Index count = s.particles.size();
  // pack_width particles at a time, then the rest one by one.
  constexpr int W = pack_width;
  const Index packs = count / W;
  parallel_region(s.threads, count, [&] {
    const Share share = static_share(packs);
    for (Index b = share.first; b < share.last; ++b)
      detail::rates_from_grid<W>(s, b * W, stencil_grid, records);
  });
  detail::rates_of_range(s, packs * W, count, stencil_grid, records);
  s.rates_stored = true;
}

// Whether the continuum averages the volumetric strain rate over cells (antilocking::FBar).
template <class State>
inline constexpr bool averages_volume = [] {
  if constexpr (requires { State::continuum_type::antilocking_type::averages_volume; }) {
    return static_cast<bool>(State::continuum_type::antilocking_type::averages_volume);
  } else {
    return false;
  }
}();

// F-bar in rate form (continuum/antilocking.hpp): each particle's volumetric strain rate
// becomes the volume-weighted average over the particles of its start-of-step cell, in the
// rates of stage 4a and the particles' velocity gradient field. A point whose grains have come
// apart (state.separation > 0, a model with separation) is stress-free and its divergence is
// its gap opening: it neither enters nor takes the average, else the gap spreads to the packed
// points of its cell and unloads them (the flat blade's draft fell 30 % so). The sums run in
// particle order, so they do not depend on the thread count.
template <class State>
void average_volumetric_rate(State& s) {
  constexpr int Dim = State::dim;
  require_start_stencils(s, "average_volumetric_rate");
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  const auto cell_of = [&](Index p) {
    Index cell = 0;
    for (int d = Dim - 1; d >= 0; --d) {
      cell = cell * s.grid.cells(d) + stencil_grid.cell_of(d, s.stencil_cells[p][d]);
    }
    return cell;
  };
  Index cells = 1;
  for (int d = 0; d < Dim; ++d) cells *= s.grid.cells(d);
  s.cell_sums.assign(static_cast<std::size_t>(2 * cells), 0.0);  // volume, volume x div v
  const auto& volume = s.particles.template get<particles::field::Volume>();
  const auto& state =
      s.particles.template get<particles::field::MaterialState<typename State::model_type>>();
  const auto packed = [&](Index p) { return !material::grains_apart(state[p]); };
  const Index count = s.particles.size();
  for (Index p = 0; p < count; ++p) {
    if (!packed(p)) continue;
    const Index c = cell_of(p);
    s.cell_sums[2 * c] += volume[p];
    s.cell_sums[2 * c + 1] += volume[p] * s.particle_rates[p].velocity_gradient.trace();
  }
  auto& L = s.particles.template get<particles::field::VelocityGradient<Dim>>();
  for (Index p = 0; p < count; ++p) {
    if (!packed(p)) continue;
    const Index c = cell_of(p);
    Mat<Dim>& rate = s.particle_rates[p].velocity_gradient;
    const double shift = (s.cell_sums[2 * c + 1] / s.cell_sums[2 * c] - rate.trace()) / Dim;
    for (int d = 0; d < Dim; ++d) rate(d, d) += shift;
    L[p] = rate;
  }
}

namespace detail {
template <class State>
void require_rates(const State& s, const char* where) {
  require(s.rates_stored && static_cast<Index>(s.particle_rates.size()) == s.particles.size(),
          std::string("Simulation::") + where + ": call velocity_gradient_from_grid first");
}
}  // namespace detail

// Stage 4b: constitutive update, deformation gradient and volume from the rates of 4a. The
// model takes the particles in runs of fixed length, one call each (material::update_batch):
// a model with a batched return (CosseratDruckerPrager) is faster so, and the runs do not
// depend on the thread count.
template <class State>
void update_stress(State& s, double dt) {
  detail::require_rates(s, "update_stress");
  if constexpr (averages_volume<State>) average_volumetric_rate(s);
  const Index count = s.particles.size();
  constexpr Index run = detail::update_run;
  const Index runs = (count + run - 1) / run;
  Index first_bad = count;
  parallel_region(s.threads, count, [&] {
    Index bad = count;  // this thread's first, in a register
    const Share share = static_share(runs);
    for (Index r = share.first; r < share.last; ++r) {
      detail::RunStresses<State> stresses;
      detail::update_stress_run(s, r * run, std::min(run, count - r * run), dt, bad, stresses);
    }
    combine_min(first_bad, bad);
  });
  if (first_bad < count) {
    throw_unstable_stress<State::dim, typename State::model_type>(s.particles, first_bad, s.clock);
  }
}

// Stages 4a and 4b in one pass over the particles: velocity_gradient_from_grid(node_velocity,
// node_spin), then update_stress(dt), run by run, so a run's rates are read back from the cache
// they were just written to. Each particle's arithmetic is the separate stages', in the same
// packs: the same bits. A continuum that averages the volumetric rate over cells
// (antilocking::FBar) needs every particle's rate before any stress update: it runs them apart.
template <class State>
void update_stress_from_grid(State& s, double dt, const std::vector<Vec<State::dim>>& node_velocity,
                             const std::vector<double>& node_spin) {
  if constexpr (averages_volume<State>) {
    velocity_gradient_from_grid(s, node_velocity, node_spin);
    update_stress(s, dt);
  } else {
    const double* const records =
        detail::rate_records(s, node_velocity, node_spin, "update_stress_from_grid");
    const shape::StencilGrid<State::dim> stencil_grid(s.grid);
    const Index count = s.particles.size();
    constexpr Index run = detail::update_run;  // a whole number of packs: 4a's packs as apart
    const Index runs = (count + run - 1) / run;
    Index first_bad = count;
    parallel_region(s.threads, count, [&] {
      Index bad = count;  // this thread's first, in a register
      const Share share = static_share(runs);
      for (Index r = share.first; r < share.last; ++r) {
        const Index begin = r * run;
        detail::RunStresses<State> stresses;
        detail::update_stress_of_run(s, begin, std::min(begin + run, count), dt, stencil_grid,
                                     records, bad, stresses);
      }
      combine_min(first_bad, bad);
    });
    s.rates_stored = false;  // the packs' rates were not stored: update_stress needs 4a again
    if (first_bad < count) {
      throw_unstable_stress<State::dim, typename State::model_type>(s.particles, first_bad,
                                                                    s.clock);
    }
  }
}

}  // namespace cosmpm::stages
