#pragma once
// Stage 4b on one run of particles (stress_update.hpp's update_stress, the fused MUSL pass of
// fused_pass.hpp): the continuum's rotation and increment, the deformation and the model's
// update for up to update_run particles, on packs where the continuum and the model take them.
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/stages/deformation.hpp"

namespace cosmpm::stages::detail {

// Stage 4b for particles begin, ..., begin + size - 1 (size <= update_run), one call of the
// model's batch update; notes the first whose stress or volume came out bad.
inline constexpr Index update_run = 64;

// Whether stage 4b rotates the stresses on packs (the continuum's rotate_and_increment_values),
// with the records transposed in registers (core/pack_records.hpp); each lane's arithmetic is
// the one-particle path's.
template <class State>
inline constexpr bool rotates_packs = [] {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  constexpr int W = pack_width;
  constexpr int n = State::model_type::strain_type::SizeAtCompileTime;
  using Continuum = typename State::continuum_type;
  using P = Pack<W>;
  if constexpr (W == 1 || R > 1 || (R > 0 && Dim != 2)) {
    return false;
  } else if constexpr (R == 0) {
    return requires(std::array<std::array<P, Dim>, Dim> g, std::array<P, n> sigma) {
      Continuum::rotate_and_increment_values(g, 0.0, sigma);
    };
  } else {
    return requires(std::array<std::array<P, Dim>, Dim> g, P spin, std::array<P, Dim> grad,
                    std::array<P, n> sigma) {
      Continuum::rotate_and_increment_values(g, spin, grad, 0.0, sigma);
    };
  }
}();

// One pack's rates, handed from stage 4a to 4b in registers or on the stack where the two run
// in one pass (stress_update.hpp, update_stress_from_grid), instead of through
// EngineState::particle_rates: stored lane by lane and loaded back, they were a transpose each
// way and a 7-double record per particle written to memory (Cosserat).
template <class State>
struct PackedRates {
  using P = Pack<pack_width>;
  std::array<std::array<P, State::dim>, State::dim> velocity_gradient;  // [i][j] = dv_i / dx_j
  std::array<P, State::rotational_dofs> spin;
  std::array<std::array<P, State::dim>, State::rotational_dofs> spin_gradient;
};
template <class State>
using RunRates =
    std::array<PackedRates<State>, (rotates_packs<State> ? update_run / pack_width : 0)>;

// Whether stage 4b updates whole packs with the model's own update on packs
// (material::HasPacksUpdate), the stresses rotated on packs too.
template <class State>
inline constexpr bool updates_packs =
    rotates_packs<State>&& material::HasPacksUpdate<typename State::model_type, pack_width>;

// The run's stresses after the model's update, one array of components per whole pack of the
// run, where updates_packs: the fused MUSL pass scatters them from here (fused_scatter.hpp)
// instead of loading them back from the particles' records.
template <class State>
using RunStresses =
    std::array<std::array<Pack<pack_width>, State::model_type::stress_type::SizeAtCompileTime>,
               (updates_packs<State> ? update_run / pack_width : 0)>;

// held: the rates of the run's whole packs from stage 4a (with rotates_packs), else null for
// EngineState::particle_rates; the particles after the last whole pack always come from there.
// sigma_packs: where the whole packs' stresses go (as well as to the particles).
template <class State>
COSMPM_ALWAYS_INLINE void update_stress_run(State& s, Index begin, Index size, double dt,
                                            Index& first_bad, RunStresses<State>& sigma_packs,
                                            const PackedRates<State>* held = nullptr) {
  constexpr int Dim = State::dim;
  using Model = typename State::model_type;
  using Continuum = typename State::continuum_type;
  using strain_type = typename Model::strain_type;
  auto& stress = s.particles.template get<particles::field::Stress<Model>>();
  auto& state = s.particles.template get<particles::field::MaterialState<Model>>();
  auto& strain = s.particles.template get<particles::field::Strain<Model>>();
  const auto points = static_cast<std::size_t>(size);
  std::array<strain_type, update_run> increment;
  std::array<double, update_run> volume_ratio;
  // The deformation before the model's call, which reads neither F nor the volume: MUSL's
  // Cosserat step runs 8-9 % faster than with it after the call (docs/performance.md).
  constexpr int W = pack_width;
  constexpr int n = strain_type::SizeAtCompileTime;
  constexpr int R = State::rotational_dofs;
  using P = Pack<W>;
  constexpr bool packed = rotates_packs<State>;
  // The model's update on the same packs where it has one (material::HasPacksUpdate), for
  // the whole packs; update_batch for the rest.
  constexpr bool packed_model = updates_packs<State>;
  using StressPacks = std::array<P, n>;
  // ... and the strains accumulated on the same packs where the continuum can.
  constexpr bool packed_strain =
      packed_model && requires(StressPacks & strain_packs, const StressPacks& step) {
    Continuum::accumulate_strain(strain_packs, step);
  };
  constexpr std::size_t packs_held = packed_model ? update_run / W : 0;
  std::array<StressPacks, packs_held> increment_packs;
  Index packed_end = 0;  // the particles done in packs
  if constexpr (packed) {
    for (; packed_end + W <= size; packed_end += W) {
      const Index p = begin + packed_end;
      const auto* const rates = s.particle_rates.data() + p;
      const PackedRates<State>* const pack_rates =
          held != nullptr ? held + packed_end / W : nullptr;
      std::array<std::array<P, Dim>, Dim> L;
      if (pack_rates != nullptr) {
        L = pack_rates->velocity_gradient;
      } else {
        const auto gradient = load_by_component<W, Dim * Dim>(
            [&](int l) { return rates[l].velocity_gradient.data(); });
        for (int i = 0; i < Dim; ++i) {
          for (int j = 0; j < Dim; ++j) L[i][j] = gradient[i + Dim * j];
        }
      }
      const auto stress_record = [&](int l) { return stress[p + l].data(); };
      std::array<P, n> sigma = load_by_component<W, n>(stress_record);
      std::array<P, n> step;
      if constexpr (R == 0) {
        step = Continuum::rotate_and_increment_values(L, dt, sigma);
      } else if (pack_rates != nullptr) {
        step = Continuum::rotate_and_increment_values(L, pack_rates->spin[0],
                                                      pack_rates->spin_gradient[0], dt, sigma);
      } else {
        const P spin = make_pack<W>([&](int l) { return rates[l].spin[0]; });
        const auto spin_gradient =
            load_by_component<W, Dim>([&](int l) { return rates[l].spin_gradient[0].data(); });
        step = Continuum::rotate_and_increment_values(L, spin, spin_gradient, dt, sigma);
      }
      if constexpr (packed_model) {
        sigma_packs[static_cast<std::size_t>(packed_end / W)] = sigma;
        increment_packs[static_cast<std::size_t>(packed_end / W)] = step;
      } else {
        store_by_component<W, n>(stress_record, sigma);
      }
      if constexpr (!packed_strain) {
        store_by_component<W, n>([&](int l) { return increment[packed_end + l].data(); }, step);
      }
      const P J = update_deformation<W, Dim>(s.particles, p, L, dt);
      cosmpm::detail::store_pack<W>(volume_ratio.data() + packed_end, J);
    }
  }
  for (Index k = packed_end; k < size; ++k) {
    const Index p = begin + k;
    increment[k] = Continuum::rotate_and_increment(s.particle_rates[p], dt, stress[p]);
    std::array<std::array<double, Dim>, Dim> L;
    for (int i = 0; i < Dim; ++i) {
      for (int j = 0; j < Dim; ++j) L[i][j] = s.particle_rates[p].velocity_gradient(i, j);
    }
    volume_ratio[k] = update_deformation<1, Dim>(s.particles, p, L, dt);
  }
  Index checked_end = 0;  // the particles whose stress and volume the packs checked
  if constexpr (packed_model) {
    const auto packs = static_cast<std::size_t>(packed_end / W);
    s.model().template update_packs<W>(std::span(sigma_packs.data(), packs),
                                       std::span<const StressPacks>(increment_packs.data(), packs),
                                       &state[begin]);
    bool sound = true;
    for (std::size_t k = 0; k < packs; ++k) {
      const Index p = begin + static_cast<Index>(k) * W;
      store_by_component<W, n>([&](int l) { return stress[p + l].data(); }, sigma_packs[k]);
      // As the check below, for the pack at once: s * 0 is 0 for a finite sum s and NaN
      // otherwise, so sum * 0 + J > 0 holds exactly when the sum is finite and J > 0.
      P sum = sigma_packs[k][0];
      for (int c = 1; c < n; ++c) sum += sigma_packs[k][c];
      const P J = cosmpm::detail::load_pack<W>(volume_ratio.data() + k * W);
      sound = sound && all_lanes<W>(sum * 0.0 + J > 0.0);
      if constexpr (packed_strain) {  // whole records: a component not accumulated goes back as is
        const auto strain_record = [&](int l) { return strain[p + l].data(); };
        StressPacks strain_packs = load_by_component<W, n>(strain_record);
        Continuum::accumulate_strain(strain_packs, increment_packs[k]);
        store_by_component<W, n>(strain_record, strain_packs);
      }
    }
    if (sound) checked_end = packed_end;
  }
  const auto batch_begin = static_cast<std::size_t>(packed_model ? packed_end : 0);
  material::update_batch(
      s.model(), std::span(stress.data() + begin + batch_begin, points - batch_begin),
      std::span(state.data() + begin + batch_begin, points - batch_begin),
      std::span<const strain_type>(increment.data() + batch_begin, points - batch_begin));
  for (Index k = packed_strain ? packed_end : 0; k < size; ++k)
    Continuum::accumulate_strain(strain[begin + k], increment[k]);
  // A non-finite component makes the sum non-finite (finite stresses near 1e308 that would
  // overflow it do not occur in soil).
  for (Index k = checked_end; k < size; ++k) {
    const Index p = begin + k;
    if (!(std::isfinite(stress[p].sum()) && volume_ratio[k] > 0.0)) record_first(first_bad, p);
  }
}

}  // namespace cosmpm::stages::detail
