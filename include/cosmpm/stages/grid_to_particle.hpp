#pragma once
// Stage 3, grid to particle: particle velocity (PIC/FLIP blend) and position from the grid,
// and the rotational degrees of freedom likewise. With the stress update (USL) the same pass
// also takes the velocity gradient, the deformation and the constitutive update, at the same
// start-of-step stencil: one sweep over the particles instead of three.
//
// Particles run pack_width at a time (core/pack.hpp): stencils, node sums, velocity, position
// and deformation side by side, the stress update too for models that update packs; every
// lane does the scalar path's arithmetic in the same order, so results do not depend on the
// pack width.
#include <array>
#include <cmath>
#include <utility>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/simulation/parameters.hpp"
#include "cosmpm/stages/deformation.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/stress_update.hpp"
#include "cosmpm/transfer/apic.hpp"

namespace cosmpm::stages {

namespace detail {

// How a particle's velocity is updated: FLIP, a PIC/FLIP blend, or APIC's PIC velocity with
// its affine matrix (transfer/apic.hpp).
enum class VelocityUpdate { flip, blend, affine };

// What every particle of a grid-to-particle map shares.
template <int Dim, class Blocks>
struct ParticleMapPass {
  double dt;
  double flip;
  bool pic_where_separated;  // SimulationParameters::pic_where_separated
  const double* records;     // the gather records of update_grid
  shape::StencilGrid<Dim> stencil_grid;
  Blocks blocks;  // BlockScheduler::Lookup
};

template <class State, int W>
using PackedStencilOf = shape::PackedStencil<State::dim, typename State::kernel_type, W>;

// Grid to particles p, ..., p + W - 1, at their start-of-step stencils, computed into st.
template <int W, bool with_stress_update, VelocityUpdate update, class State>
COSMPM_ALWAYS_INLINE void map_from_grid(State& s, Index p, const auto& pass,
                                        PackedStencilOf<State, W>& st, Index& first_outside,
                                        Index& first_bad, Index& first_moved) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::gather_record;
  using P = Pack<W>;
  auto& particles = s.particles;
  auto& x = particles.template get<particles::field::Position<Dim>>();
  auto& v = particles.template get<particles::field::Velocity<Dim>>();
  const auto& half = particles.template get<particles::field::HalfWidth<Dim>>();
  const auto& start = s.stencil_cells;
  const double dt = pass.dt;
  const double flip = pass.flip;
  constexpr bool affine = update == VelocityUpdate::affine;
  // Velocity (and the rotational rates) with gradients when the stress is updated here, then
  // the accelerations.
  constexpr int with_gradient = with_stress_update ? Record::with_gradient : 0;
  st.compute_from_cell_units(
      pass.stencil_grid, [&](int l) -> const Vec<Dim>& { return start[p + l]; },
      [&](int l) -> const Vec<Dim>& { return half[p + l]; });
  const auto grid_values = shape::gather<Record::all, with_gradient>(st, pass.records);
  // SimulationParameters::pic_where_separated: the lanes whose grains are apart take the grid's
  // velocity, found once for all components.
  constexpr bool separable =
      !affine && material::records_separation<typename State::model_type::state_type>;
  [[maybe_unused]] std::array<bool, W> apart{};
  [[maybe_unused]] bool any_apart = false;
  if constexpr (separable) {
    if (pass.pic_where_separated) {
      const auto& state =
          particles.template get<particles::field::MaterialState<typename State::model_type>>();
      for (int l = 0; l < W; ++l) {
        apart[l] = material::grains_apart(state[p + l]);
        any_apart = any_apart || apart[l];
      }
    }
  }
  // New positions in cell units, for the box test and the particles' blocks.
  std::array<P, Dim> xi;
  const auto v_record = [&](int l) { return v[p + l].data(); };
  const auto x_record = [&](int l) { return x[p + l].data(); };
  const std::array<P, Dim> v_before = load_by_component<W, Dim>(v_record);
  const std::array<P, Dim> x_before = load_by_component<W, Dim>(x_record);
  std::array<P, Dim> v_after, x_after;
  for (int d = 0; d < Dim; ++d) {
    const P v_grid = grid_values.value[Record::velocity + d];
    const P a_grid = grid_values.value[Record::acceleration + d];
    const P v_old = v_before[d];
    const P x_old = x_before[d];
    P v_new;
    if constexpr (affine) {
      v_new = v_grid;
      (void)v_old;
      (void)a_grid;
    } else {
      v_new = v_old + dt * a_grid;
      if constexpr (update == VelocityUpdate::blend) v_new = flip * v_new + (1.0 - flip) * v_grid;
      if constexpr (separable) {
        if (any_apart) {
          v_new = make_pack<W>(
              [&](int l) { return apart[l] ? lane<W>(v_grid, l) : lane<W>(v_new, l); });
        }
      }
    }
    const P x_new = x_old + dt * v_grid;
    xi[d] = (x_new - pass.stencil_grid.origin[d]) * pass.stencil_grid.inverse_cell_size[d];
    v_after[d] = v_new;
    x_after[d] = x_new;
  }
  store_by_component<W, Dim>(v_record, v_after);
  store_by_component<W, Dim>(x_record, x_after);
  if constexpr (affine) {
    const auto b = transfer::detail::affine_moment<Record::all>(
        st, pass.stencil_grid, [&](int l) -> const Vec<Dim>& { return start[p + l]; },
        pass.records);
    auto& moment = particles.template get<particles::field::AffineMoment<Dim>>();
    for (int l = 0; l < W; ++l) {
      for (int i = 0; i < Dim; ++i) {
        for (int j = 0; j < Dim; ++j) moment[p + l](i, j) = lane<W>(b[i][j], l);
      }
    }
  }
  constexpr bool packed = with_stress_update && packed_stress_update<State, W>;
  [[maybe_unused]] P volume_ratio;
  [[maybe_unused]] std::array<std::array<P, Dim>, Dim> L;
  [[maybe_unused]] P stress_sum;  // the packed stress update's finiteness check
  if constexpr (with_stress_update) {
    for (int i = 0; i < Dim; ++i) L[i] = grid_values.gradient[Record::velocity + i];
    volume_ratio = update_deformation<W, Dim>(particles, p, L, dt);
    if constexpr (packed) stress_sum = update_stress_packed<W>(s, p, L, dt);
  }
  if constexpr (packed) {
    auto& velocity_gradient = particles.template get<particles::field::VelocityGradient<Dim>>();
    std::array<P, Dim * Dim> by_component;  // column-major records: L(i, j) at i + Dim j
    for (int i = 0; i < Dim; ++i) {
      for (int j = 0; j < Dim; ++j) by_component[i + Dim * j] = L[i][j];
    }
    store_by_component<W, Dim * Dim>([&](int l) { return velocity_gradient[p + l].data(); },
                                     by_component);
  }
  // The packed update checks all lanes with one comparison: s * 0 is 0 for a finite s and
  // NaN otherwise, so s * 0 + J > 0 holds exactly when s is finite and J > 0.
  [[maybe_unused]] bool pack_sound = true;
  if constexpr (packed) pack_sound = all_lanes<W>(stress_sum * 0.0 + volume_ratio > 0.0);
  // 0 < xi < last exactly when xi (last - xi) > 0 (false for NaN): one comparison per axis
  // for the whole pack.
  bool all_inside = true;
  for (int d = 0; d < Dim; ++d) {
    all_inside &= all_lanes<W>(xi[d] * (pass.stencil_grid.last[d] - xi[d]) > 0.0);
  }
  // The rotations on the packs where the continuum takes them (Cosserat), else lane by lane.
  // APIC carries no affine rotation field: the rotations take the grid's (PIC).
  constexpr bool packed_rotations = R > 0 && requires(std::array<P, R> rates) {
    State::continuum_type::update_rotations(particles, p, dt, flip, rates, rates);
  };
  if constexpr (packed_rotations) {
    std::array<P, R> spin_grid, spin_acceleration;
    for (int k = 0; k < R; ++k) {
      spin_grid[k] = grid_values.value[Record::spin + k];
      spin_acceleration[k] = grid_values.value[Record::spin_acceleration + k];
    }
    State::continuum_type::update_rotations(particles, p, dt, affine ? 0.0 : flip, spin_grid,
                                            spin_acceleration);
  }
  for (int l = 0; l < W; ++l) {
    const Index q = p + l;
    if constexpr (R > 0 && !packed_rotations) {
      std::array<double, R> spin_grid, spin_acceleration;
      for (int k = 0; k < R; ++k) {
        spin_grid[k] = lane<W>(grid_values.value[Record::spin + k], l);
        spin_acceleration[k] = lane<W>(grid_values.value[Record::spin_acceleration + k], l);
      }
      // APIC carries no affine rotation field: the rotations take the grid's (PIC).
      State::continuum_type::update_rotations(particles, q, dt, affine ? 0.0 : flip, spin_grid,
                                              spin_acceleration);
    }
    if constexpr (with_stress_update) {
      if constexpr (packed) {
        if (!pack_sound &&
            !(std::isfinite(lane<W>(stress_sum, l)) && lane<W>(volume_ratio, l) > 0.0)) [[unlikely]]
          record_first(first_bad, q);
      } else {
        const auto rates = rates_from<State, W>(grid_values, l);
        store_components(particles.template get<particles::field::VelocityGradient<Dim>>()[q],
                         rates.velocity_gradient);
        const bool finite = update_constitutive(s, q, rates, dt);
        if (!(finite && lane<W>(volume_ratio, l) > 0.0)) [[unlikely]]
          record_first(first_bad, q);
      }
    }
    if (!all_inside) [[unlikely]] {
      bool inside = true;  // this lane's own test: the pack's failed for some lane
      for (int d = 0; d < Dim; ++d) {
        inside = inside && pass.stencil_grid.inside(d, lane<W>(xi[d], l));
      }
      if (!inside) {
        record_first(first_outside, q);
        continue;
      }
    }
    // Inside, xi < cells, so the floor is already what cell_of gives (its clamp to the last
    // cell cost 13 instructions per particle here, from reloading the node counts).
    std::array<Index, Dim> cell;
    for (int d = 0; d < Dim; ++d) cell[d] = static_cast<Index>(lane<W>(xi[d], l));
    if (const Index block = pass.blocks.block_of_cell(cell);
        block != pass.blocks.particle_block[q]) {
      pass.blocks.particle_block[q] = block;  // sorted again at the next particle-to-grid map
      record_first(first_moved, q);
    }
  }
}

template <class State>
ParticleMapPass<State::dim, decltype(std::declval<State&>().blocks.lookup())> map_pass(State& s,
                                                                                       double dt) {
  return {dt,
          s.parameters.flip_fraction_or_default(),
          s.parameters.pic_where_separated,
          s.gather.data(),
          shape::StencilGrid<State::dim>(s.grid),
          s.blocks.lookup()};
}

// After a grid-to-particle pass: particles that changed block are sorted again before the
// next scatter; a particle outside the grid stops the run or becomes a stray; a bad stress
// stops the run, naming its cause.
template <class State>
void finish_map(State& s, Index first_outside, Index first_bad, Index first_moved) {
  constexpr int Dim = State::dim;
  const Index count = s.particles.size();
  if (first_moved < count) s.blocks.mark_changed();
  // A particle that left the grid usually also tore its neighbourhood: name the cause.
  if (first_outside < count) {
    if (s.parameters.stray_particles == StrayParticles::stop) {
      throw_outside<Dim>(s.particles, s.grid, first_outside, s.clock);
    }
    s.strays_pending = true;  // the rest of the step still maps them at their start stencils
  }
  if (first_bad < count) {
    throw_unstable_stress<Dim, typename State::model_type>(s.particles, first_bad, s.clock);
  }
}

// The packs of map_to_particles on the engine's team, each member its static share; returns
// the first particle outside, with a bad stress and moved (the count for none). Taking copies,
// it leaves map_to_particles' locals alone (see there).
template <int W, bool with_stress_update, VelocityUpdate update, class State, class Pass>
[[gnu::noinline]] std::array<Index, 3> map_packs_on_team(State& s, Index packs, const Pass pass) {
  const Index count = s.particles.size();
  std::array<Index, 3> firsts{count, count, count};
  parallel_region(s.threads, count, [&] {
    const Share share = static_share(packs);
    Index outside = count, bad = count, moved = count;  // this thread's firsts
    for (Index b = share.first; b < share.last; ++b) {
      PackedStencilOf<State, W> st;
      map_from_grid<W, with_stress_update, update>(s, b * W, pass, st, outside, bad, moved);
    }
    combine_min(firsts[0], outside);
    combine_min(firsts[1], bad);
    combine_min(firsts[2], moved);
  });
  return firsts;
}

template <bool with_stress_update, VelocityUpdate update, class State>
void map_to_particles(State& s, double dt) {
  require_start_stencils(s, "map_to_particles");
  const Index count = s.particles.size();
  const auto pass = map_pass(s, dt);
  Index first_outside = count;
  Index first_bad = count;
  Index first_moved = count;
  // pack_width particles at a time, then the rest one by one.
  constexpr int W = pack_width;
  const Index packs = count / W;
  // On a team through a function of its own, alone through the loop below: with the team's
  // lambda here, or the loop in a function both paths call, GCC 12 contracted this map's
  // multiply-adds differently (-march=native), and MUSL's Cosserat results moved.
  if (runs_on_team(s.threads, count)) {
    const auto firsts = map_packs_on_team<W, with_stress_update, update>(s, packs, pass);
    first_outside = firsts[0];
    first_bad = firsts[1];
    first_moved = firsts[2];
  } else {
    for (Index b = 0; b < packs; ++b) {
      PackedStencilOf<State, W> st;
      map_from_grid<W, with_stress_update, update>(s, b * W, pass, st, first_outside, first_bad,
                                                   first_moved);
    }
  }
  for (Index p = packs * W; p < count; ++p) {
    PackedStencilOf<State, 1> st;
    map_from_grid<1, with_stress_update, update>(s, p, pass, st, first_outside, first_bad,
                                                 first_moved);
  }
  finish_map(s, first_outside, first_bad, first_moved);
}

// Calls f.template operator()<update>() with the velocity update of the simulation's transfer
// and FLIP fraction: pure FLIP (the default) is its own instantiation, its update needs no
// blend.
template <class State, class F>
void with_velocity_update(const State& s, F&& f) {
  if constexpr (State::transfer_type::affine) {
    f.template operator()<VelocityUpdate::affine>();
  } else if (s.parameters.flip_fraction_or_default() == 1.0) {
    f.template operator()<VelocityUpdate::flip>();
  } else {
    f.template operator()<VelocityUpdate::blend>();
  }
}

}  // namespace detail

// At the end of a step: the particles outside the open grid box leave the simulation under
// StrayParticles::freeze (kept in s.frozen) or ::remove, counted with their mass. A stray
// whose position or velocity is not finite stops the run instead: it is unstable.
template <class State>
void handle_stray_particles(State& s) {
  constexpr int Dim = State::dim;
  s.strays.count_last_step = 0;
  s.strays.mass_last_step = 0.0;
  if (!s.strays_pending) return;
  s.strays_pending = false;
  const auto& x = s.particles.template get<particles::field::Position<Dim>>();
  const auto& v = s.particles.template get<particles::field::Velocity<Dim>>();
  const auto& mass = s.particles.template get<particles::field::Mass>();
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  const auto outside = [&](Index p) {
    for (int d = 0; d < Dim; ++d) {
      const double xi = (x[p][d] - stencil_grid.origin[d]) * stencil_grid.inverse_cell_size[d];
      if (!stencil_grid.inside(d, xi)) return true;
    }
    return false;
  };
  double stray_mass = 0.0;
  for (Index p = 0; p < s.particles.size(); ++p) {
    if (!outside(p)) continue;
    if (!x[p].allFinite() || !v[p].allFinite()) throw_outside<Dim>(s.particles, s.grid, p, s.clock);
    stray_mass += mass[p];
  }
  const bool keep = s.parameters.stray_particles == StrayParticles::freeze;
  const Index moved = s.particles.extract_if(outside, keep ? &s.frozen : nullptr);
  s.strays.count += moved;
  s.strays.mass += stray_mass;
  s.strays.count_last_step = moved;
  s.strays.mass_last_step = stray_mass;
  // The step's per-particle buffers no longer match; the next map_to_grid rebuilds them.
  s.prescattered = false;
  s.stencil_cells.clear();
  s.particle_rates.clear();
}

// Particle velocity and position from the grid; with_stress_update, also the stress update.
template <class State>
void map_to_particles(State& s, double dt, bool with_stress_update) {
  using detail::VelocityUpdate;
  // Averaging the volumetric rate over cells needs every particle's rate first: no fusion.
  const bool in_one_pass = with_stress_update && !averages_volume<State>;
  detail::with_velocity_update(s, [&]<VelocityUpdate update>() {
    in_one_pass ? detail::map_to_particles<true, update>(s, dt)
                : detail::map_to_particles<false, update>(s, dt);
  });
  if (with_stress_update && !in_one_pass) {
    velocity_gradient_from_grid(s, s.nodes.velocity, s.nodes.spin);
    update_stress(s, dt);
  }
}

}  // namespace cosmpm::stages
