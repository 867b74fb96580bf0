#pragma once
// The batched update of the plane-strain MohrCoulomb (update_batch) without a tension cut-off
// below the apex: L points at a time in SIMD lanes (the register width, lanes.hpp), trial,
// split, yield check, the cone return and the rotation back all without a branch.
//
// Why: one point's update is a chain of dependent operations ending in a branch on elastic or
// plastic, which mispredicts in a random mix of the two (the flat blade's run has both side by
// side); its return then branches again on the region. Here every lane computes every region
// and keeps the one the per-point update would have taken, each with that update's operations
// in its order, so each lane equals update() bit for bit (the conformance kit checks it).
//
// Lanes go to the per-point update instead when their grains are apart (separation > 0: the
// gap's own path) or their trial is not finite (update() then decides what the engine reports).
#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/lanes.hpp"
#include "cosmpm/material/detail/mohr_coulomb_return.hpp"

namespace cosmpm::material::detail {

template <class T>
struct MohrCoulombBatch2D {
  const IsotropicElasticity<T>& elastic;
  const MohrCoulombReturn<T>& flow;       // the return with the model's dilatancy
  const MohrCoulombReturn<T>& isochoric;  // psi = 0, past the dilatancy cut-off
  double dilatancy_cutoff_strain;
  bool separation;

  // stress, state and de arrays of `count` points, L at a time (L >= 2 and has_lanes, or
  // L = 1: all per point); per_point(stress, state, de) is update().
  template <int L, class Stress, class State, class Strain, class PerPoint>
  void run(Stress* stress, State* state, const Strain* de, std::size_t count,
           PerPoint&& per_point) const {
    std::size_t i = 0;
    if constexpr (L >= 2) {
      for (; i + L <= count; i += L) lanes<L>(stress + i, state + i, de + i, per_point);
    }
    for (; i < count; ++i) per_point(stress[i], state[i], de[i]);
  }

  // Packs stress[0 .. packs - 1] of L points by component, increments likewise, point l of
  // pack k with state[k L + l]; every point per point with `per_point_only` (a cut-off below
  // the apex, as run<1>).
  template <int L, class State, class PerPoint>
  void run_packs(std::array<Lanes<T, L>, 4>* stress, const std::array<Lanes<T, L>, 4>* de,
                 std::size_t packs, State* state, bool per_point_only,
                 const PerPoint& per_point) const {
    using Packs = std::array<Lanes<T, L>, 4>;
    for (std::size_t k = 0; k < packs; ++k) {
      State* const pack_state = state + k * L;
      const auto per_point_lane = [&](int l, const Packs& old, Packs& out) {
        Eigen::Matrix<T, 4, 1> point, increment;
        for (int c = 0; c < 4; ++c) {
          point[c] = old[c][l];
          increment[c] = de[k][c][l];
        }
        per_point(point, pack_state[l], increment);
        for (int c = 0; c < 4; ++c) out[c][l] = point[c];
      };
      if (per_point_only) {
        for (int l = 0; l < L; ++l) per_point_lane(l, stress[k], stress[k]);
      } else {
        lanes_by_component<L>(stress[k], de[k], pack_state, per_point_lane);
      }
    }
  }

 private:
  // lanes_by_component for points stress[0 .. L - 1] in memory.
  template <int L, class Stress, class State, class Strain, class PerPoint>
  void lanes(Stress* stress, State* state, const Strain* de, PerPoint& per_point) const {
    std::array<Lanes<T, L>, 4> stress_lanes, de_lanes;
    for (int c = 0; c < 4; ++c) {
      gather_lanes(stress_lanes[c], [&](int l) { return stress[l][c]; });
      gather_lanes(de_lanes[c], [&](int l) { return de[l][c]; });
    }
    // stress[l] still holds the old stress when a lane goes per point.
    const auto per_point_lane = [&](int l, const auto&, auto& out) {
      per_point(stress[l], state[l], de[l]);
      for (int c = 0; c < 4; ++c) out[c][l] = stress[l][c];
    };
    lanes_by_component<L>(stress_lanes, de_lanes, state, per_point_lane);
    for (int l = 0; l < L; ++l) {
      for (int c = 0; c < 4; ++c) stress[l][c] = stress_lanes[c][l];
    }
  }

 public:
  // The update of L points whose stresses and increments come by component: `stress` in, the
  // new stresses out; per_point_lane(l, old_stress, stress) is the per-point update of lane l
  // (a point apart, or a trial that is not finite), which leaves lane l of `stress` its result.
  template <int L, class State, class PerPointLane>
  COSMPM_ALWAYS_INLINE void lanes_by_component(std::array<Lanes<T, L>, 4>& stress,
                                               const std::array<Lanes<T, L>, 4>& de_lanes,
                                               State* state,
                                               const PerPointLane& per_point_lane) const {
    using V = Lanes<T, L>;
    using Mask = decltype(V{} < V{});
    const std::array<V, 4> old_stress = stress;
    const V zero = splat<V>(T(0));
    // Without separation the gap is never read nor written (it stays as it is).
    V gap = zero;
    if (separation) gather_lanes(gap, [&](int l) { return T(state[l].separation); });

    // The trial: the per-point update's own formula, on lanes.
    const std::array<V, 4> trial = elastic.template trial<4>(old_stress, de_lanes);
    const V &txx = trial[0], &tyy = trial[1], &tzz = trial[2], &txy = trial[3];

    // The split, as PlaneStrainSplit (std::max(x, y) is y > x ? y : x; std::min(x, y) is
    // y < x ? y : x).
    const V mean = (txx + tyy) / 2;
    const V half = (txx - tyy) / 2;
    V radius = half * half + txy * txy;
    sqrt_in_place(radius);
    const V a = mean + radius;
    const V b = mean - radius;
    const V s1 = a < tzz ? tzz : a;
    const V upper = tzz < b ? b : tzz;
    const V s2 = a < upper ? a : upper;
    const V s3 = tzz < b ? tzz : b;
    const V f = flow.yield(s1, s3);
    const Mask elastic_lane = f <= zero;
    const V finite = (txx - txx) + (tyy - tyy) + (tzz - tzz) + (txy - txy);
    Mask per_point_lane_mask = !(finite == zero);
    if (separation) per_point_lane_mask = per_point_lane_mask || gap > zero;
    // Runs of elastic points are common (the engine's points come in space order): one branch.
    if (cosmpm::all_lanes<L>(elastic_lane && !per_point_lane_mask)) {
      // By component: a copy of the whole array became 64-byte moves of the spilled trial,
      // each loading what two 32-byte stores had just written (no store forwarding).
      for (int c = 0; c < 4; ++c) stress[c] = trial[c];
      for (int l = 0; l < L; ++l) state[l].plastic = 0.0;
      return;
    }

    // The cone return and the rotation back (PlaneStrainSplit::back), for every lane.
    V shear_strain;
    gather_lanes(shear_strain, [&](int l) { return T(state[l].plastic_shear_strain); });
    const Mask use_isochoric = shear_strain >= splat<V>(T(dilatancy_cutoff_strain));
    V r1, r2, r3, gamma;
    Mask at_apex;
    flow.cone_lanes(s1, s2, s3, f, isochoric, use_isochoric, elastic_lane || per_point_lane_mask,
                    r1, r2, r3, gamma, at_apex);
    const Mask zz_first = tzz >= a;
    const Mask zz_second = !zz_first && tzz >= b;
    const V natural_a = zz_first ? r2 : r1;
    const V natural_b = zz_first || zz_second ? r3 : r2;
    const V natural_z = zz_first ? r1 : (zz_second ? r2 : r3);
    const V ratio = radius > zero ? (natural_a - natural_b) / (2 * radius) : zero;
    const V new_mean = (natural_a + natural_b) / 2;
    const V out_xx = elastic_lane ? txx : new_mean + half * ratio;
    const V out_yy = elastic_lane ? tyy : new_mean - half * ratio;
    const V out_zz = elastic_lane ? tzz : natural_z;
    const V out_xy = elastic_lane ? txy : txy * ratio;
    const V plastic = elastic_lane ? zero : splat<V>(T(1));
    const V new_shear_strain = elastic_lane ? shear_strain : shear_strain + gamma;
    // With separation, an apex return's plastic volumetric strain is the gap (update_separating).
    const T bulk = elastic.bulk();
    const V trial_mean = (old_stress[0] + old_stress[1] + old_stress[2]) / 3 +
                         bulk * (de_lanes[0] + de_lanes[1] + de_lanes[2]);
    const Mask opens = !elastic_lane && at_apex && trial_mean > zero;
    V new_gap = gap;
    if (separation) new_gap = opens ? gap + trial_mean / bulk : gap;

    stress = {out_xx, out_yy, out_zz, out_xy};
    // The per-point update for lanes apart or with a trial that is not finite.
    for (int l = 0; l < L; ++l) {
      if (per_point_lane_mask[l]) [[unlikely]] {
        per_point_lane(l, old_stress, stress);
        continue;
      }
      state[l].plastic_shear_strain = static_cast<double>(new_shear_strain[l]);
      state[l].plastic = static_cast<double>(plastic[l]);
      if (separation) state[l].separation = static_cast<double>(new_gap[l]);
    }
  }
};

}  // namespace cosmpm::material::detail
