#pragma once
// The batched return of CosseratDruckerPrager (update_batch): the formulas of the per-point
// return (cosserat_cone.hpp) run over arrays of points, several plastic points at a time in SIMD
// lanes.
//
// Why: one point's return is a chain of about 200 cycles of dependent operations, which the
// processor overlaps little with the next point's; here each pass is a loop whose iterations
// are independent and short (one link of the chain for L points), so it overlaps several of
// them. The batch goes chunk by chunk (batch_chunk points) in passes over arrays:
//  1. classify, L points at a time: trial, yield check, the trial stored and the plastic flag
//     set. The plastic points are queued without a branch (index[n] = i; n += plastic): a
//     branch on elastic/plastic would mispredict in a random mix. Those inside the apex
//     pressure (q0 > 0) go to the cone queue, the rare others (the apex, beyond it) to `far`,
//     which takes the per-point return.
//  2. The cone queue in lanes of L points (the register width: 2 doubles with SSE2, 4 with
//     AVX): scaling_lanes and series_lanes give the solve's start, then batch_steps times
//     sums_lanes and step_lanes its step (a lane's y frozen once it meets the stopping test; a
//     group whose lanes have all stopped is skipped), then finish_lanes the returned stress. A
//     lane that has not stopped is redone by the per-point return. The modes of equal rate are
//     merged (M groups, see CosseratCone::ConeStart): the one difference from the per-point
//     return, at rounding.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>

#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/cosserat_cone.hpp"
#include "cosmpm/material/detail/cosserat_elasticity.hpp"
#include "cosmpm/material/detail/lanes.hpp"

namespace cosmpm::material::detail {

template <class T>
class CosseratBatch {
 public:
  using Stress = Eigen::Matrix<T, 7, 1>;
  static constexpr int batch_lanes = static_cast<int>(register_bytes / sizeof(T));
  using V = Lanes<T, batch_lanes>;

  // update(stress[i], state[i], increment[i]) for i < count; `per_point(stress, state)` is the
  // per-point return of a plastic point whose stress holds its trial.
  template <class PerPoint>
  static void run(const CosseratCone<T>& cone, const CosseratModuli<T>& moduli, Stress* stress,
                  PlasticState* state, const Stress* increment, std::size_t count,
                  const PerPoint& per_point) {
    switch (cone.groups()) {
      case 1:
        Pass<1, PerPoint>{cone, per_point}.run(moduli, stress, state, increment, count);
        break;
      case 2:
        Pass<2, PerPoint>{cone, per_point}.run(moduli, stress, state, increment, count);
        break;
      default:
        Pass<3, PerPoint>{cone, per_point}.run(moduli, stress, state, increment, count);
    }
  }

  // run() for points whose stresses and increments come in packs by component (the engine's
  // stage 4b holds them so): pack k holds points k L .. k L + L - 1 (L = batch_lanes), whose
  // states are state[k L ..]. The same passes and lane values as run(), with pass 1 on the
  // packs and the packs with a plastic lane queued whole: the engine's points come in space
  // order, so a pack is mostly all elastic or all plastic (a mixed pack's other lanes ride
  // along, counted as stopped, and keep their values).
  template <class PerPoint>
  static void run_packs(const CosseratCone<T>& cone, const CosseratModuli<T>& moduli,
                        std::array<V, 7>* stress, const std::array<V, 7>* increment,
                        std::size_t packs, PlasticState* state, const PerPoint& per_point) {
    switch (cone.groups()) {
      case 1:
        Pass<1, PerPoint>{cone, per_point}.run_packs(moduli, stress, increment, packs, state);
        break;
      case 2:
        Pass<2, PerPoint>{cone, per_point}.run_packs(moduli, stress, increment, packs, state);
        break;
      default:
        Pass<3, PerPoint>{cone, per_point}.run_packs(moduli, stress, increment, packs, state);
    }
  }

 private:
  using Cone = CosseratCone<T>;
  static constexpr std::size_t batch_chunk = 128;  // the scratch (21 KB) stays in L1
  static constexpr int batch_steps = 2;  // about 90 % of the plastic points stop after one

  // A chunk's queues and, by cone-queue entry, the solve's state (so L entries load as lanes).
  // The stresses of the queued points hold their trials.
  struct Scratch {
    static constexpr std::size_t capacity = batch_chunk + batch_lanes;  // with the padding
    std::size_t index[capacity];
    std::size_t far[batch_chunk];
    // scaling_lanes
    T pi[3][capacity], theta[capacity], r_mean[capacity], inverse_r_mean[capacity],
        q_trial[capacity], p_trial[capacity], q0[capacity];
    T lo[capacity], scale[capacity], y[capacity];  // series_lanes, step_lanes
    T stopped[capacity];                           // 1 once stopped, else 0
    T product[capacity], n[capacity], e1[capacity], e2[capacity], e3[capacity];  // sums_lanes
  };

  template <std::size_t M, class PerPoint>
  struct Pass {
    const Cone& cone;
    const PerPoint& per_point;

    void run(const CosseratModuli<T>& model_moduli, Stress* stress, PlasticState* state,
             const Stress* increment, std::size_t count) const {
      constexpr std::size_t L = batch_lanes;
      Scratch scratch;
      // Copies: the stores through stress and state could alias these as far as the compiler
      // knows, which would reload them for every point.
      const CosseratModuli<T> moduli = model_moduli;
      const typename Cone::TrialWeights weights = cone.weights();
      for (std::size_t begin = 0; begin < count; begin += batch_chunk) {
        const std::size_t end = std::min(count, begin + batch_chunk);
        std::size_t queued = 0, far_count = 0;
        std::size_t i = begin;
        for (; i + L <= end; i += L)
          classify<V>(i, stress, state, increment, moduli, weights, scratch, queued, far_count);
        for (; i < end; ++i)
          classify<T>(i, stress, state, increment, moduli, weights, scratch, queued, far_count);
        for (std::size_t k = 0; k < far_count; ++k)
          per_point(stress[scratch.far[k]], state[scratch.far[k]]);
        if (queued == 0) continue;
        const std::size_t padded = (queued + L - 1) / L * L;
        for (std::size_t k = queued; k < padded; ++k) scratch.index[k] = scratch.index[0];
        for (std::size_t k = 0; k < padded; k += L) scaling_lanes(scratch, k, stress);
        for (std::size_t k = 0; k < padded; k += L) series_lanes(scratch, k);
        for (int iteration = 0; iteration < batch_steps; ++iteration) {
          for (std::size_t k = 0; k < padded; k += L) sums_lanes(scratch, k);
          for (std::size_t k = 0; k < padded; k += L) step_lanes(scratch, k);
        }
        for (std::size_t k = 0; k < padded; k += L)
          finish_lanes(scratch, k, std::min(L, queued - k), stress, state);
      }
    }

    void run_packs(const CosseratModuli<T>& model_moduli, std::array<V, 7>* stress,
                   const std::array<V, 7>* increment, std::size_t packs,
                   PlasticState* state) const {
      constexpr std::size_t L = batch_lanes;
      Scratch scratch;
      const CosseratModuli<T> moduli = model_moduli;
      const typename Cone::TrialWeights weights = cone.weights();
      for (std::size_t begin = 0; begin < packs; begin += batch_chunk / L) {
        const std::size_t end = std::min(packs, begin + batch_chunk / L);
        std::size_t queued = 0;  // packs, in scratch.index
        for (std::size_t k = begin; k < end; ++k) {
          stress[k] = cosserat_trial(stress[k], increment[k], moduli);
          const auto elastic = Cone::is_elastic(Cone::split_trial(stress[k], weights));
          const V plastic = elastic ? V{} : V{} + T(1);  // the flags as doubles, by one select
          for (std::size_t l = 0; l < L; ++l)
            state[k * L + l].plastic = static_cast<double>(lane_of(plastic, int(l)));
          scratch.index[queued] = k;
          queued += static_cast<std::size_t>(!cosmpm::all_lanes<L>(elastic));
        }
        if (queued == 0) continue;
        const std::size_t lanes = queued * L;
        for (std::size_t k = 0; k < lanes; k += L)
          scaling_lanes(scratch, k, stress[scratch.index[k / L]]);
        for (std::size_t k = 0; k < lanes; k += L) series_lanes(scratch, k);
        for (int iteration = 0; iteration < batch_steps; ++iteration) {
          for (std::size_t k = 0; k < lanes; k += L) sums_lanes(scratch, k);
          for (std::size_t k = 0; k < lanes; k += L) step_lanes(scratch, k);
        }
        for (std::size_t k = 0; k < lanes; k += L) {
          const std::size_t pack = scratch.index[k / L];
          finish_pack(scratch, k, stress[pack], state + pack * L);
        }
      }
    }

    // Pass 1 for points i .. i + n - 1, n the lanes of W (1 for T).
    template <class W>
    static void classify(std::size_t i, Stress* stress, PlasticState* state,
                         const Stress* increment, const CosseratModuli<T>& moduli,
                         const typename Cone::TrialWeights& weights, Scratch& b,
                         std::size_t& queued, std::size_t& far_count) {
      std::array<W, 7> s, d;
      for (int c = 0; c < 7; ++c) {
        gather_lanes(s[c], [&](int lane) { return stress[i + lane][c]; });
        gather_lanes(d[c], [&](int lane) { return increment[i + lane][c]; });
      }
      const std::array<W, 7> t = cosserat_trial(s, d, moduli);
      const auto split = Cone::split_trial(t, weights);
      const auto elastic = Cone::is_elastic(split);
      const auto inside = split.q0 > T(0);
      for (int lane = 0; lane < lane_count<W>(); ++lane) {
        const std::size_t point = i + static_cast<std::size_t>(lane);
        for (int c = 0; c < 7; ++c) stress[point][c] = lane_of(t[c], lane);
        const bool is_elastic = lane_of(elastic, lane) != 0;
        const bool cone_point = !is_elastic & (lane_of(inside, lane) != 0);
        state[point].plastic = static_cast<double>(!is_elastic);
        b.index[queued] = point;
        queued += static_cast<std::size_t>(cone_point);
        b.far[far_count] = point;
        far_count += static_cast<std::size_t>(!is_elastic & !cone_point);
      }
    }

    // The trial stresses of cone-queue entries k .. k + L - 1 by component.
    static std::array<V, 7> gather_trials(const Scratch& b, std::size_t k, const Stress* stress) {
      std::array<V, 7> t;
      for (int c = 0; c < 7; ++c)
        gather_lanes(t[c], [&](int lane) { return stress[b.index[k + lane]][c]; });
      return t;
    }

    // The passes over the cone queue, each for entries k .. k + L - 1.
    void scaling_lanes(Scratch& b, std::size_t k, const Stress* stress) const {
      scaling_lanes(b, k, gather_trials(b, k, stress));
    }
    // ... from the trials t. A lane that is not a cone point (elastic, or beyond the apex
    // pressure: only in run_packs) starts as stopped.
    void scaling_lanes(Scratch& b, std::size_t k, const std::array<V, 7>& t) const {
      const auto split = Cone::split_trial(t, cone.weights());
      V q_trial = split.w_sum;
      sqrt_in_place(q_trial);
      const std::array<V, 3> mode_w{split.w0, split.w1, split.w2};
      std::array<V, M> w{};
      for (int j = 0; j < 3; ++j) w[cone.group_of_mode(j)] += mode_w[j];
      const auto s = Cone::template cone_scaling<V, M>(w, split.w_sum, q_trial, split.q0,
                                                       cone.template group_rates<M>());
      for (std::size_t j = 0; j < M; ++j) store_lanes(&b.pi[j][k], s.pi[j]);
      store_lanes(&b.theta[k], s.theta);
      store_lanes(&b.r_mean[k], s.r_mean);
      store_lanes(&b.inverse_r_mean[k], s.inverse_r_mean);
      store_lanes(&b.q_trial[k], q_trial);
      store_lanes(&b.p_trial[k], split.p);
      store_lanes(&b.q0[k], split.q0);
      const auto cone_point = mask_not(Cone::is_elastic(split)) & (split.q0 > T(0));
      store_lanes(&b.stopped[k], cone_point ? V{} : V{} + T(1));
    }

    void series_lanes(Scratch& b, std::size_t k) const {
      typename Cone::template ConeStart<V, M> s = load_scaling(b, k);
      load_lanes(s.r_mean, &b.r_mean[k]);
      load_lanes(s.inverse_r_mean, &b.inverse_r_mean[k]);
      cone.cone_series(s, cone.template group_rates<M>());
      store_lanes(&b.lo[k], s.lo);
      store_lanes(&b.scale[k], s.scale);
      store_lanes(&b.y[k], Cone::clamped_start(s));
    }

    static typename Cone::template ConeStart<V, M> load_scaling(const Scratch& b, std::size_t k) {
      typename Cone::template ConeStart<V, M> s;
      for (std::size_t j = 0; j < M; ++j) load_lanes(s.pi[j], &b.pi[j][k]);
      load_lanes(s.theta, &b.theta[k]);
      return s;
    }

    static bool all_stopped(const Scratch& b, std::size_t k) {
      V stopped;
      load_lanes(stopped, &b.stopped[k]);
      return cosmpm::all_lanes<batch_lanes>(stopped != T(0));
    }

    void sums_lanes(Scratch& b, std::size_t k) const {
      if (all_stopped(b, k)) return;
      V y;
      load_lanes(y, &b.y[k]);
      const auto sums = Cone::cone_sums(load_scaling(b, k), y, cone.template group_rates<M>());
      store_lanes(&b.product[k], sums.product);
      store_lanes(&b.n[k], sums.n);
      store_lanes(&b.e1[k], sums.e1);
      store_lanes(&b.e2[k], sums.e2);
      store_lanes(&b.e3[k], sums.e3);
    }

    // The per-point return's step and stopping test (CosseratCone::cone_step), lane by lane.
    static void step_lanes(Scratch& b, std::size_t k) {
      if (all_stopped(b, k)) return;
      typename Cone::template ConeSums<V> sums;
      load_lanes(sums.product, &b.product[k]);
      load_lanes(sums.n, &b.n[k]);
      load_lanes(sums.e1, &b.e1[k]);
      load_lanes(sums.e2, &b.e2[k]);
      load_lanes(sums.e3, &b.e3[k]);
      V y, lo, scale, stopped;
      load_lanes(y, &b.y[k]);
      load_lanes(lo, &b.lo[k]);
      load_lanes(scale, &b.scale[k]);
      load_lanes(stopped, &b.stopped[k]);
      // `stopped` is 0 / 1 in doubles: a compare of 64-bit integers needs SSE4.1.
      const auto done = stopped != T(0);
      V next;
      const auto stop = Cone::cone_step(Cone::cone_terms(sums), y, lo, scale, next);
      store_lanes(&b.y[k], done ? y : next);
      store_lanes(&b.stopped[k], (done | stop) ? V{} + T(1) : V{});
    }

    // The returned stresses of entries k .. k + L - 1 from their trials t, and the multipliers.
    std::array<V, 7> returned(const Scratch& b, std::size_t k, const std::array<V, 7>& t,
                              V& multiplier) const {
      V y, q_trial, p_trial, q0;
      load_lanes(y, &b.y[k]);
      load_lanes(q_trial, &b.q_trial[k]);
      load_lanes(p_trial, &b.p_trial[k]);
      load_lanes(q0, &b.q0[k]);
      multiplier = y * q_trial;
      return Cone::scaled_stress(t, p_trial, cone.return_scales(p_trial, q0, multiplier));
    }

    // run_packs' last pass: the pack `t` of trials (entries k ..) gets its cone points' returned
    // stresses where they stopped; its other plastic lanes take the per-point return.
    void finish_pack(const Scratch& b, std::size_t k, std::array<V, 7>& t,
                     PlasticState* state) const {
      V multiplier;
      const std::array<V, 7> out = returned(b, k, t, multiplier);
      V q0, stopped, plastic;
      load_lanes(q0, &b.q0[k]);
      load_lanes(stopped, &b.stopped[k]);
      gather_lanes(plastic, [&](int l) { return T(state[l].plastic); });
      // The plastic cone points that stopped take the returned stress, selected by mask (lane
      // by lane the copies went through memory); the other plastic lanes the per-point return.
      const auto take = (plastic != T(0)) & (q0 > T(0)) & (stopped != T(0));
      for (int c = 0; c < 7; ++c) t[c] = take ? out[c] : t[c];
      if (cosmpm::all_lanes<batch_lanes>(take)) {  // the usual pack: no lane left to redo
        for (int l = 0; l < batch_lanes; ++l)
          state[l].plastic_shear_strain += static_cast<double>(lane_of(multiplier, l));
        return;
      }
      for (int l = 0; l < batch_lanes; ++l) {
        const std::size_t lane = static_cast<std::size_t>(l);
        if (state[lane].plastic == 0.0) continue;
        if (lane_of(take, l) != 0) {
          state[lane].plastic_shear_strain += static_cast<double>(lane_of(multiplier, l));
        } else {
          Stress point;
          for (int c = 0; c < 7; ++c) point[c] = t[c][l];
          per_point(point, state[lane]);
          for (int c = 0; c < 7; ++c) t[c][l] = point[c];
        }
      }
    }

    // The returned stresses, stored for the first `count` lanes if they stopped; the others are
    // redone by the per-point return.
    void finish_lanes(const Scratch& b, std::size_t k, std::size_t count, Stress* stress,
                      PlasticState* state) const {
      V multiplier;
      const std::array<V, 7> out = returned(b, k, gather_trials(b, k, stress), multiplier);
      // A loop of constant length, so each lane is taken from the registers by a constant
      // index (with a variable one the lanes go through memory, and 16-byte loads across two
      // earlier stores stall).
      for (int l = 0; l < batch_lanes; ++l) {
        const std::size_t lane = static_cast<std::size_t>(l);
        if (lane == count) break;
        const std::size_t i = b.index[k + lane];
        if (b.stopped[k + lane] != T(0)) {
          for (int c = 0; c < 7; ++c) stress[i][c] = out[c][l];
          state[i].plastic_shear_strain += static_cast<double>(multiplier[l]);
        } else {
          per_point(stress[i], state[i]);
        }
      }
    }
  };
};

}  // namespace cosmpm::material::detail
