#pragma once
// Perfectly plastic Cosserat Drucker-Prager in 2D plane strain after de Borst (1991, 1993) and
// Tejchman (1997), with the elasticity and component layout of cosserat_elastic.hpp.
// Tension positive, p = (s_xx + s_yy + s_zz) / 3, s_ij = sigma_ij - p delta_ij (non-symmetric):
//   q^2 = a1 s_ij s_ij + a2 s_ij s_ji + a3 m_3i m_3i / l^2      (i, j over x, y, z)
//   f = q + alpha p - k,   g = q + beta p,
// with alpha, beta, k from phi, psi, c by a DruckerPragerMatching (default: the per-angle
// plane-strain formula; the paper cites Tejchman for the conversion without giving it). With a1 +
// a2 = 1/2 (the defaults 0.375, 0.125, 1) q is sqrt(J2) for a symmetric stress without couple
// stresses, so the model reduces to the classical DruckerPrager with the same coefficients.
//
// The return is backward Euler. In the modes that diagonalise both q and the elastic law (the
// deviatoric normals with the symmetric shear, the skew shear, the couple stresses) each mode
// shrinks by q / (q + c_j dlambda), which leaves one monotone convex scalar equation in dlambda,
// solved by a safeguarded Newton iteration that converges from the left. The apex
// (p = c cot(phi), s = 0, m = 0) takes the trial states the cone cannot. update_batch runs the
// same return over arrays of points, several at a time in SIMD lanes.
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/detail/lanes.hpp"
#include "cosmpm/material/drucker_prager.hpp"

namespace cosmpm::material {

// Coefficients of the Cosserat invariant q; the defaults are Muhlhaus and Vardoulakis' values
// used by Tejchman (1997) and the paper.
template <class T = double>
struct CosseratInvariantCoefficients {
  T a1 = T(0.375);
  T a2 = T(0.125);
  T a3 = T(1);
};

template <class T = double>
class CosseratDruckerPrager {
 public:
  using scalar_type = T;
  using stress_type = CosseratTensor2D<T>;  // [s_xx, s_yy, s_zz, s_xy, s_yx, m_31, m_32]
  using strain_type = CosseratTensor2D<T>;  // [e_xx, e_yy, e_zz, e_xy, e_yx, k_31, k_32]
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, 7, 7>;
  static constexpr bool is_cosserat = true;

  // E > 0, -1 < nu < 0.5, Gc >= 0 (Pa), l > 0 (m), 0 < phi < 90, 0 <= psi <= phi (degrees),
  // c >= 0 (Pa); a1 + a2 > 0, a1 >= a2, a3 >= 0 keep q a (semi-)norm.
  CosseratDruckerPrager(
      T youngs_modulus, T poisson_ratio, T cosserat_shear_modulus, T characteristic_length,
      T friction_angle_deg, T dilatancy_angle_deg, T cohesion = T(0),
      CosseratInvariantCoefficients<T> invariant = {},
      DruckerPragerMatching matching = DruckerPragerMatching::plane_strain_per_angle)
      : elastic_("CosseratDruckerPrager", youngs_modulus, poisson_ratio, cosserat_shear_modulus,
                 characteristic_length),
        coefficients_(drucker_prager_coefficients<T>(friction_angle_deg, dilatancy_angle_deg,
                                                     cohesion, matching, "CosseratDruckerPrager")),
        invariant_(invariant),
        matching_(matching) {
    require_positive("CosseratDruckerPrager", "a1 + a2",
                     static_cast<double>(invariant.a1 + invariant.a2));
    require_non_negative("CosseratDruckerPrager", "a1 - a2",
                         static_cast<double>(invariant.a1 - invariant.a2));
    require_non_negative("CosseratDruckerPrager", "a3", static_cast<double>(invariant.a3));
    const T g = elastic_.iso.shear;
    mode_stiffness_ = {2 * g * (invariant.a1 + invariant.a2),
                       2 * elastic_.cosserat_shear * (invariant.a1 - invariant.a2),
                       2 * g * invariant.a3};
    bulk_beta_ = elastic_.iso.bulk() * coefficients_.beta;
    slope_ = coefficients_.alpha * bulk_beta_;
    for (int j = 0; j < 3; ++j) {
      rate_[j] = slope_ + mode_stiffness_[j];
      inverse_stiffness_squared_[j] =
          mode_stiffness_[j] > T(0) ? 1 / (mode_stiffness_[j] * mode_stiffness_[j]) : T(0);
    }
    c_max_ = std::max({mode_stiffness_[0], mode_stiffness_[1], mode_stiffness_[2]});
    inverse_rate_max_ = 1 / (slope_ + c_max_);
    moduli_ = elastic_.moduli();
    // q^2 = (a1 + a2) (d:d + 2 sym^2) + 2 (a1 - a2) skew^2 + a3 m.m / l^2, with sym and skew the
    // halves of t3 + t4 and t3 - t4.
    const T symmetric_weight = invariant.a1 + invariant.a2;
    const T skew_weight = 2 * (invariant.a1 - invariant.a2);
    trial_weights_ = {symmetric_weight, symmetric_weight / 2,
                      skew_weight / 4,  invariant.a3 / (elastic_.length * elastic_.length),
                      coefficients_.k,  coefficients_.alpha};
    for (int j = 0; j < 3; ++j) {  // the modes by rate, equal rates in one group
      int group = 0;
      while (group < groups_ && group_rate_[group] != rate_[j]) ++group;
      if (group == groups_) group_rate_[groups_++] = rate_[j];
      group_of_mode_[j] = group;
    }
    const T rate_min = std::min({rate_[0], rate_[1], rate_[2]});
    inverse_rate_min_ = rate_min > T(0) ? 1 / rate_min : std::numeric_limits<T>::infinity();
  }

  T shear_modulus() const { return elastic_.iso.shear; }
  T cosserat_shear_modulus() const { return elastic_.cosserat_shear; }
  T characteristic_length() const { return elastic_.length; }
  T lame_lambda() const { return elastic_.iso.lambda; }
  T bulk_modulus() const { return elastic_.iso.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave_modulus(); }
  T bending_modulus() const { return elastic_.bending_modulus(); }
  const DruckerPragerCoefficients<T>& coefficients() const { return coefficients_; }
  const CosseratInvariantCoefficients<T>& invariant_coefficients() const { return invariant_; }
  DruckerPragerMatching matching() const { return matching_; }
  T apex_pressure() const { return coefficients_.k / coefficients_.alpha; }
  tangent_type elastic_tangent() const { return elastic_.tangent(); }

  // The generalised invariant q of a stress.
  T invariant_q(const stress_type& stress) const {
    return std::sqrt(split_trial<T>({stress[0], stress[1], stress[2], stress[3], stress[4],
                                     stress[5], stress[6]},
                                    trial_weights_)
                         .w_sum);
  }

  // f = q + alpha p - k in Pa; <= 0 inside.
  T yield_function(const stress_type& stress) const {
    return invariant_q(stress) + coefficients_.alpha * (stress[0] + stress[1] + stress[2]) / 3 -
           coefficients_.k;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    update_impl<false>(stress, state, de, nullptr);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update_impl<true>(stress, state, de, &tangent);
  }

  // update(stress[i], state[i], increment[i]) for every i, with the same results to rounding,
  // several plastic points at a time in SIMD lanes (docs/theory/materials.md, "Batched
  // return"). Allocation-free. The three spans must have the same size and must not overlap.
  void update_batch(std::span<stress_type> stress, std::span<state_type> state,
                    std::span<const strain_type> increment) const {
    require_equal_batch_sizes("CosseratDruckerPrager::update_batch", stress.size(), state.size(),
                              increment.size());
    if constexpr (detail::has_lanes) {
      switch (groups_) {
        case 1:
          batch_impl<1>(stress.data(), state.data(), increment.data(), stress.size());
          break;
        case 2:
          batch_impl<2>(stress.data(), state.data(), increment.data(), stress.size());
          break;
        default:
          batch_impl<3>(stress.data(), state.data(), increment.data(), stress.size());
      }
    } else {
      for (std::size_t i = 0; i < stress.size(); ++i) update(stress[i], state[i], increment[i]);
    }
  }

 private:
  // The formulas below are templates on the value type V: T for update(), lanes of T for
  // update_batch(), so both run the same operations (update_batch merges the modes of equal
  // rate, see ConeStart, so the two agree to rounding, not bit for bit).

  // The weights of q^2 for the trial's d_i = t_i - p, (t3 + t4), (t3 - t4) and couple stresses,
  // and k, alpha.
  struct TrialWeights {
    T symmetric, half_symmetric, quarter_skew, couple, k, alpha;
  };
  // A trial's p, the contributions w_j to q^2, q_trial^2 and q0 = k - alpha p (q on the
  // surface at p_trial).
  template <class V>
  struct TrialSplit {
    V p, w0, w1, w2, w_sum, q0;
  };
  template <class V>
  static TrialSplit<V> split_trial(const std::array<V, 7>& t, const TrialWeights& c) {
    TrialSplit<V> out;
    out.p = (t[0] + t[1] + t[2]) * (T(1) / 3);
    const V d0 = t[0] - out.p, d1 = t[1] - out.p, d2 = t[2] - out.p;
    const V sum = t[3] + t[4], difference = t[3] - t[4];  // twice the symmetric and skew shear
    out.w0 = c.symmetric * (d0 * d0 + d1 * d1 + d2 * d2) + c.half_symmetric * sum * sum;
    out.w1 = c.quarter_skew * difference * difference;
    out.w2 = c.couple * (t[5] * t[5] + t[6] * t[6]);
    out.w_sum = out.w0 + out.w1 + out.w2;
    out.q0 = c.k - c.alpha * out.p;
    return out;
  }

  // Inside the apex pressure (q0 > 0) every u_j = q0 + r_j x >= q0 > 0. Scaled by q_trial
  // (y = x / q_trial, theta = q0 / q_trial, pi_j = w_j / q_trial^2, v_j = theta + r_j y) the
  // equation is F(y) = sum_j pi_j / v_j^2 = 1, solved on G = F^(-1/2) = 1: G is the (p = -2)
  // power mean of the v_j, concave and increasing in y, linear when all r_j are equal.
  //
  // The functions below take the modes in M groups of equal rate r_j (the sum of their w_j
  // each): update() passes the three modes as they are, update_batch() merges those of equal
  // rate (M = 2 with the paper's Gc = 2G and default a1, a2), which saves a third of the work
  // of a step.
  template <class V, std::size_t M>
  struct ConeStart {
    std::array<V, M> pi;
    V theta;
    V r_mean, inverse_r_mean;  // sum_j pi_j r_j and its inverse
    V lo, hi;  // the roots with all c_j = c_max and all c_j = c_min, which bracket the root
    V scale;   // the distance from y = 0 to the nearest pole of F
    V y;       // the start, to be clamped to [lo, max(lo, hi)]
  };

  // f(0) + f(1) + ... + f(M - 1), summed in that order.
  template <std::size_t M, class F>
  static auto sum_over(F&& f) {
    auto total = f(0);
    for (std::size_t j = 1; j < M; ++j) total = total + f(j);
    return total;
  }

  // The start in two parts (update_batch runs them in separate passes, which shortens the
  // chain of dependent operations in each): the scaled variables and r_mean, ...
  template <class V, std::size_t M>
  static ConeStart<V, M> cone_scaling(const std::array<V, M>& w, const V& w_sum, const V& q_trial,
                                      const V& q0, const std::array<T, M>& r) {
    ConeStart<V, M> s;
    const V inverse_w = T(1) / w_sum;  // independent of the square root that gave q_trial
    for (std::size_t j = 0; j < M; ++j) s.pi[j] = w[j] * inverse_w;
    s.theta = q0 * q_trial * inverse_w;
    // Start: with r_mean = sum_j pi_j r_j, a = theta + r_mean y, tau = y / a, d_j = r_j -
    // r_mean and m_k = sum_j pi_j d_j^k, G = a phi(tau) and 1 / phi = sqrt(sum_j pi_j /
    // (1 + d_j tau)^2) = 1 + k2 tau^2 + ... + k6 tau^6 + O(tau^7) (k1 = 0 as m1 = 0); the start
    // is a = 1 / phi(tau) with tau at the linear root (1 - theta) / r_mean, exact when all
    // r_j are equal (the classical case). The terms up to tau^6 make one step enough for
    // about 90 % of the benchmark's plastic states (60 % with terms up to tau^3).
    const V wr = sum_over<M>([&](std::size_t j) { return w[j] * r[j]; });
    s.r_mean = wr * inverse_w;
    s.inverse_r_mean = w_sum / wr;
    return s;
  }

  // ... then the series and the start y.
  template <class V, std::size_t M>
  void cone_series(ConeStart<V, M>& s, const std::array<T, M>& r) const {
    const V r_mean = s.r_mean, inverse_r_mean = s.inverse_r_mean;
    std::array<V, M> d, pd, pdd;
    for (std::size_t j = 0; j < M; ++j) {
      d[j] = r[j] - r_mean;
      pd[j] = s.pi[j] * d[j] * d[j];
      pdd[j] = pd[j] * d[j];
    }
    const V m2 = sum_over<M>([&](std::size_t j) { return pd[j]; });
    const V m3 = sum_over<M>([&](std::size_t j) { return pdd[j]; });
    const V m4 = sum_over<M>([&](std::size_t j) { return pdd[j] * d[j]; });
    const V m5 = sum_over<M>([&](std::size_t j) { return pdd[j] * d[j] * d[j]; });
    const V m6 = sum_over<M>([&](std::size_t j) { return pdd[j] * d[j] * d[j] * d[j]; });
    const V k2 = T(1.5) * m2;
    const V k3 = T(-2) * m3;
    const V k4 = T(2.5) * m4 - T(1.125) * m2 * m2;
    const V k5 = T(3) * (m2 * m3 - m5);
    const V k6 = T(3.5) * m6 - T(2) * m3 * m3 - T(3.75) * m2 * m4 + T(1.6875) * m2 * m2 * m2;
    const V tau = (T(1) - s.theta) * inverse_r_mean;
    const V tau2 = tau * tau;  // Estrin's scheme: a shorter dependent chain than Horner's
    const V inverse_phi = T(1) + tau2 * ((k2 + tau * k3) + tau2 * ((k4 + tau * k5) + tau2 * k6));
    s.lo = (T(1) - s.theta) * inverse_rate_max_;
    s.hi = (T(1) - s.theta) * inverse_rate_min_;
    s.scale = s.theta * inverse_rate_max_;
    s.y = (inverse_phi - s.theta) * inverse_r_mean;
  }

  // A step in two parts as well: the sums at y, ...
  template <class V>
  struct ConeSums {
    V product, n, e1, e2, e3;  // V, N, D1, D2, D3 below
  };
  template <class V, std::size_t M>
  static ConeSums<V> cone_sums(const ConeStart<V, M>& s, const V& y, const std::array<T, M>& r) {
    // With V = prod_j v_j, P_j = V / v_j, N = sum pi_j P_j^2, D_k = sum pi_j r_j^k P_j^(k+2):
    // F = N / V^2, F' = -2 D1 / V^3, F'' = 6 D2 / V^4, F''' = -24 D3 / V^5. One square
    // root and one division (independent of each other) per step.
    std::array<V, M> v, p, a, b, ab, abb;
    for (std::size_t j = 0; j < M; ++j) v[j] = s.theta + r[j] * y;
    for (std::size_t j = 0; j < M; ++j) {
      p[j] = V{} + T(1);  // the product of the other v_k, in order (v1 v2, v0 v2, v0 v1)
      bool first = true;
      for (std::size_t k = 0; k < M; ++k) {
        if (k == j) continue;
        p[j] = first ? v[k] : p[j] * v[k];
        first = false;
      }
      a[j] = s.pi[j] * p[j] * p[j];
      b[j] = r[j] * p[j];
      ab[j] = a[j] * b[j];
      abb[j] = ab[j] * b[j];
    }
    ConeSums<V> out;
    out.product = v[0] * p[0];
    out.n = sum_over<M>([&](std::size_t j) { return a[j]; });
    out.e1 = sum_over<M>([&](std::size_t j) { return ab[j]; });
    out.e2 = sum_over<M>([&](std::size_t j) { return abb[j]; });
    out.e3 = sum_over<M>([&](std::size_t j) { return abb[j] * b[j]; });
    return out;
  }

  // ... and from the sums the terms of the step: the Newton step e = -(G - 1) / G', c2 e and
  // the relative cubic term 2 (c2 e)^2 - c3 e^2, c_k = G^(k) / (k! G').
  template <class V>
  struct ConeStep {
    V newton, c2e, cubic;
  };
  template <class V>
  static ConeStep<V> cone_terms(const ConeSums<V>& sums) {
    const V &product = sums.product, &n = sums.n, &e1 = sums.e1, &e2 = sums.e2, &e3 = sums.e3;
    V root_n = n;
    detail::sqrt_in_place(root_n);
    const V qn = product * n;
    const V inverse = T(1) / (qn * qn * e1);  // 1 / (Q^2 D1), Q = V N
    // Series reversion of the cubic Taylor polynomial of G - 1 (a fourth-order step):
    // h = e - c2 e^2 + (2 c2^2 - c3) e^3, written out in N, V and the D_k.
    ConeStep<V> out;
    out.newton = (root_n - product) * n * qn * qn * inverse;
    const V c2 = T(1.5) * (e1 * e1 - e2 * n) * qn * inverse;
    const V c3 = (T(2.5) * e1 * e1 * e1 - T(4.5) * e1 * e2 * n + T(2) * e3 * n * n) * inverse;
    out.c2e = c2 * out.newton;
    out.cubic = T(2) * out.c2e * out.c2e - c3 * out.newton * out.newton;
    return out;
  }

  // Solves h(x) = sum_j w_j / (q0 + (slope + c_j) x)^2 - 1 = 0 for x > 0; h is convex and
  // decreasing where every u_j = q0 + (slope + c_j) x > 0. `w_sum` = q_trial^2.
  T solve_multiplier(const std::array<T, 3>& w, T w_sum, T q_trial, T q0) const {
    const std::array<T, 3>& r = rate_;  // slope + c_j
    const T slope = slope_;
    const auto h_and_slope = [&](T x, T& dh) {
      T h = -1;
      dh = 0;
      for (int j = 0; j < 3; ++j) {
        if (w[j] <= T(0)) continue;
        const T inverse = 1 / (q0 + r[j] * x);
        const T term = w[j] * inverse * inverse;
        h += term;
        dh -= 2 * term * r[j] * inverse;
      }
      return h;
    };
    if (q0 > T(0)) {
      ConeStart<T, 3> s = cone_scaling<T, 3>(w, w_sum, q_trial, q0, r);
      cone_series(s, r);
      T y = std::clamp(s.y, s.lo, std::max(s.lo, s.hi));
      for (int iteration = 0; iteration < 60; ++iteration) {
        const ConeStep<T> e = cone_terms(cone_sums(s, y, r));
        // Far from the root (the first steps of a large return) take the plain Newton step,
        // which stays left of the root of the concave G.
        const bool near = std::abs(e.c2e) < T(0.25);
        const T step = near ? e.newton * (1 - e.c2e + e.cubic) : e.newton;
        const T next = std::max(y + step, s.lo);
        // The error left by the fourth-order step is about |cubic term| |step| / reach, reach =
        // the distance to the nearest pole (within a factor 1.4 over the benchmark's states,
        // against a converged solve); accept at 1e-12 relative. The tests ask 1e-10 of f.
        const T reach = y + s.scale;
        if (near && y + step >= s.lo &&
            !(std::abs(e.newton * e.cubic * step) > T(1e-13) * reach * reach))
          return next * q_trial;
        y = next;
      }
      return y * q_trial;
    }
    // Beyond the apex pressure (the apex test failed): start right of the last pole of h,
    // where h > 0, and let Newton climb monotonically to the root.
    T x = (q_trial - q0) / (slope + c_max_);
    for (int j = 0; j < 3; ++j) {
      if (w[j] <= T(0)) continue;
      const T rate = r[j];
      if (q0 + rate * x <= T(0)) x = -q0 / rate * (1 + T(1e-6));
    }
    for (int iteration = 0; iteration < 100; ++iteration) {
      T dh;
      const T h = h_and_slope(x, dh);
      const T step = -h / dh;
      x += step;
      if (!(std::abs(step) > T(1e-15) * x)) break;
    }
    return x;
  }

  // The returned stress of trial t at the multiplier: p moves by -K beta dlambda and each mode
  // group shrinks by scale_j = q / (q + c_j dlambda), the three from one division.
  template <class V>
  struct ReturnScales {
    V scale0, scale1, scale2, p;
  };
  template <class V>
  ReturnScales<V> return_scales(const V& p_trial, const V& q0, const V& multiplier) const {
    const V q = q0 + slope_ * multiplier;
    const V v0 = q + mode_stiffness_[0] * multiplier;
    const V v1 = q + mode_stiffness_[1] * multiplier;
    const V v2 = q + mode_stiffness_[2] * multiplier;
    const V q_over_product = q / (v0 * v1 * v2);
    return {v1 * v2 * q_over_product, v0 * v2 * q_over_product, v0 * v1 * q_over_product,
            p_trial - bulk_beta_ * multiplier};
  }
  template <class V>
  static std::array<V, 7> scaled_stress(const std::array<V, 7>& t, const V& p_trial,
                                        const ReturnScales<V>& r) {
    const V sym = r.scale0 * (t[3] + t[4]) / T(2);
    const V skew = r.scale1 * (t[3] - t[4]) / T(2);
    return {r.scale0 * (t[0] - p_trial) + r.p,
            r.scale0 * (t[1] - p_trial) + r.p,
            r.scale0 * (t[2] - p_trial) + r.p,
            sym + skew,
            sym - skew,
            t[5] * r.scale2,
            t[6] * r.scale2};
  }

  template <bool WithTangent>
  void update_impl(stress_type& stress, state_type& state, const strain_type& de,
                   tangent_type* tangent) const {
    // The trial stress in scalars, every load before the first store (see trial_stress).
    const std::array<T, 7> t = detail::trial_stress(stress, de, moduli_);
    const TrialSplit<T> split = split_trial(t, trial_weights_);
    // f_trial = q_trial - q0 <= 0, decided without the square root so the branch resolves early.
    if ((split.q0 >= T(0)) & (split.w_sum <= split.q0 * split.q0)) {
      stress << t[0], t[1], t[2], t[3], t[4], t[5], t[6];
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_.tangent();
      return;
    }
    stress << t[0], t[1], t[2], t[3], t[4], t[5], t[6];
    plastic_return<WithTangent>(stress, state, tangent, split.p, split.w0, split.w1, split.w2,
                                split.w_sum, split.q0);
  }

  // The return of the plastic trial state `stress`, out of line so that the elastic path above
  // stays short (no spills, no saved registers); the trial's split (p, the weights of q^2,
  // q_trial^2, q0) comes in registers.
  template <bool WithTangent>
  [[gnu::noinline]] void plastic_return(stress_type& stress, state_type& state,
                                        tangent_type* tangent, T p_trial, T w0, T w1, T w2, T w_sum,
                                        T q0) const {
    const std::array<T, 3> weight{w0, w1, w2};
    state.plastic = 1.0;
    const T q_trial = std::sqrt(w_sum);
    if (q0 <= T(0) && is_apex(weight, q0, slope_)) {
      const T apex = apex_pressure();
      const T gamma2 = weight[0] * inverse_stiffness_squared_[0] +
                       weight[1] * inverse_stiffness_squared_[1] +
                       weight[2] * inverse_stiffness_squared_[2];
      state.plastic_shear_strain += static_cast<double>(std::sqrt(gamma2));
      stress << apex, apex, apex, 0, 0, 0, 0;
      if constexpr (WithTangent) tangent->setZero();
      return;
    }
    const T multiplier = solve_multiplier(weight, w_sum, q_trial, q0);
    const std::array<T, 7> s = scaled_stress<T>(
        {stress[0], stress[1], stress[2], stress[3], stress[4], stress[5], stress[6]}, p_trial,
        return_scales(p_trial, q0, multiplier));
    stress << s[0], s[1], s[2], s[3], s[4], s[5], s[6];
    // The multiplier is the plastic strain conjugate to q: the engineering plastic shear strain
    // sqrt(2 e:e) in the symmetric case.
    state.plastic_shear_strain += static_cast<double>(multiplier);
    if constexpr (WithTangent)
      *tangent = consistent_tangent(stress, q0 + slope_ * multiplier, multiplier);
  }

  // plastic_return for a point whose stress holds its plastic trial.
  void scalar_return(stress_type& stress, state_type& state) const {
    const TrialSplit<T> split = split_trial<T>(
        {stress[0], stress[1], stress[2], stress[3], stress[4], stress[5], stress[6]},
        trial_weights_);
    plastic_return<false>(stress, state, nullptr, split.p, split.w0, split.w1, split.w2,
                          split.w_sum, split.q0);
  }

  // The batch (update_batch) goes chunk by chunk (batch_chunk points) in passes over arrays.
  // One point's return is a chain of about 200 cycles of dependent operations, which the
  // processor overlaps little with the next point's; here each pass is a loop whose
  // iterations are independent and short (one link of the chain for L points), so it overlaps
  // several of them. The passes over a chunk:
  //  1. classify, L points at a time: trial, yield check, the trial stored and the plastic flag
  //     set. The plastic points are queued without a branch (index[n] = i; n += plastic): a
  //     branch on elastic/plastic would mispredict in a random mix. Those inside the apex
  //     pressure (q0 > 0) go to the cone queue, the rare others (the apex, beyond it) to `far`,
  //     which takes the per-point return.
  //  2. The cone queue in lanes of L points (the register width: 2 doubles with SSE2, 4 with
  //     AVX): scaling_lanes and series_lanes give solve_multiplier's start, then batch_steps
  //     times sums_lanes and step_lanes its step (a lane's y frozen once it meets the stopping
  //     test; a group whose lanes have all stopped is skipped), then finish_lanes the returned
  //     stress. A lane that has not stopped is redone by the per-point return. The modes of
  //     equal rate are merged (M groups, see ConeStart).
  static constexpr std::size_t batch_chunk = 128;  // the scratch (21 KB) stays in L1
  static constexpr int batch_steps = 2;  // about 90 % of the plastic points stop after one
  static constexpr int batch_lanes = static_cast<int>(detail::register_bytes / sizeof(T));
  using BatchLanes = detail::Lanes<T, batch_lanes>;

  // A chunk's queues and, by cone-queue entry, the solve's state (so L entries load as lanes).
  // The stresses of the queued points hold their trials.
  struct BatchScratch {
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

  template <std::size_t M>
  void batch_impl(stress_type* stress, state_type* state, const strain_type* increment,
                  std::size_t count) const {
    constexpr std::size_t L = batch_lanes;
    using V = BatchLanes;
    BatchScratch scratch;
    // Copies: the stores through stress and state could alias the members as far as the
    // compiler knows, which would reload them for every point.
    const detail::CosseratModuli<T> moduli = moduli_;
    const TrialWeights weights = trial_weights_;
    for (std::size_t begin = 0; begin < count; begin += batch_chunk) {
      const std::size_t end = std::min(count, begin + batch_chunk);
      std::size_t queued = 0, far_count = 0;
      std::size_t i = begin;
      for (; i + L <= end; i += L)
        classify<V>(i, stress, state, increment, moduli, weights, scratch, queued, far_count);
      for (; i < end; ++i)
        classify<T>(i, stress, state, increment, moduli, weights, scratch, queued, far_count);
      for (std::size_t k = 0; k < far_count; ++k)
        scalar_return(stress[scratch.far[k]], state[scratch.far[k]]);
      if (queued == 0) continue;
      const std::size_t padded = (queued + L - 1) / L * L;
      for (std::size_t k = queued; k < padded; ++k) scratch.index[k] = scratch.index[0];
      for (std::size_t k = 0; k < padded; k += L) scaling_lanes<M>(scratch, k, stress);
      for (std::size_t k = 0; k < padded; k += L) series_lanes<M>(scratch, k);
      for (int iteration = 0; iteration < batch_steps; ++iteration) {
        for (std::size_t k = 0; k < padded; k += L) sums_lanes<M>(scratch, k);
        for (std::size_t k = 0; k < padded; k += L) step_lanes(scratch, k);
      }
      for (std::size_t k = 0; k < padded; k += L)
        finish_lanes(scratch, k, std::min(L, queued - k), stress, state);
    }
  }

  // Pass 1 for points i .. i + n - 1, n the lanes of V (1 for T).
  template <class V>
  void classify(std::size_t i, stress_type* stress, state_type* state, const strain_type* increment,
                const detail::CosseratModuli<T>& moduli, const TrialWeights& weights,
                BatchScratch& b, std::size_t& queued, std::size_t& far_count) const {
    std::array<V, 7> s, d;
    for (int c = 0; c < 7; ++c) {
      detail::gather_lanes(s[c], [&](int lane) { return stress[i + lane][c]; });
      detail::gather_lanes(d[c], [&](int lane) { return increment[i + lane][c]; });
    }
    const std::array<V, 7> t = detail::trial_stress(s, d, moduli);
    const TrialSplit<V> split = split_trial(t, weights);
    const auto elastic = (split.q0 >= T(0)) & (split.w_sum <= split.q0 * split.q0);
    const auto inside = split.q0 > T(0);
    for (int lane = 0; lane < detail::lane_count<V>(); ++lane) {
      const std::size_t point = i + static_cast<std::size_t>(lane);
      for (int c = 0; c < 7; ++c) stress[point][c] = detail::lane_of(t[c], lane);
      const bool is_elastic = detail::lane_of(elastic, lane) != 0;
      const bool cone = !is_elastic & (detail::lane_of(inside, lane) != 0);
      state[point].plastic = static_cast<double>(!is_elastic);
      b.index[queued] = point;
      queued += static_cast<std::size_t>(cone);
      b.far[far_count] = point;
      far_count += static_cast<std::size_t>(!is_elastic & !cone);
    }
  }

  // The trial stresses of cone-queue entries k .. k + L - 1 by component.
  static std::array<BatchLanes, 7> gather_trials(const BatchScratch& b, std::size_t k,
                                                 const stress_type* stress) {
    std::array<BatchLanes, 7> t;
    for (int c = 0; c < 7; ++c)
      detail::gather_lanes(t[c], [&](int lane) { return stress[b.index[k + lane]][c]; });
    return t;
  }

  // The passes over the cone queue, each for entries k .. k + L - 1.
  template <std::size_t M>
  void scaling_lanes(BatchScratch& b, std::size_t k, const stress_type* stress) const {
    using V = BatchLanes;
    const std::array<V, 7> t = gather_trials(b, k, stress);
    const TrialSplit<V> split = split_trial(t, trial_weights_);
    V q_trial = split.w_sum;
    detail::sqrt_in_place(q_trial);
    const std::array<V, 3> mode_w{split.w0, split.w1, split.w2};
    std::array<V, M> w{};
    for (int j = 0; j < 3; ++j) w[group_of_mode_[j]] += mode_w[j];
    const ConeStart<V, M> s =
        cone_scaling<V, M>(w, split.w_sum, q_trial, split.q0, group_rates<M>());
    for (std::size_t j = 0; j < M; ++j) detail::store_lanes(&b.pi[j][k], s.pi[j]);
    detail::store_lanes(&b.theta[k], s.theta);
    detail::store_lanes(&b.r_mean[k], s.r_mean);
    detail::store_lanes(&b.inverse_r_mean[k], s.inverse_r_mean);
    detail::store_lanes(&b.q_trial[k], q_trial);
    detail::store_lanes(&b.p_trial[k], split.p);
    detail::store_lanes(&b.q0[k], split.q0);
  }

  template <std::size_t M>
  void series_lanes(BatchScratch& b, std::size_t k) const {
    using V = BatchLanes;
    ConeStart<V, M> s = load_scaling<M>(b, k);
    detail::load_lanes(s.r_mean, &b.r_mean[k]);
    detail::load_lanes(s.inverse_r_mean, &b.inverse_r_mean[k]);
    cone_series(s, group_rates<M>());
    const V top = s.lo < s.hi ? s.hi : s.lo;  // std::clamp(y, lo, std::max(lo, hi))
    const V y = s.y < s.lo ? s.lo : (top < s.y ? top : s.y);
    detail::store_lanes(&b.lo[k], s.lo);
    detail::store_lanes(&b.scale[k], s.scale);
    detail::store_lanes(&b.y[k], y);
    detail::store_lanes(&b.stopped[k], V{});
  }

  template <std::size_t M>
  static ConeStart<BatchLanes, M> load_scaling(const BatchScratch& b, std::size_t k) {
    ConeStart<BatchLanes, M> s;
    for (std::size_t j = 0; j < M; ++j) detail::load_lanes(s.pi[j], &b.pi[j][k]);
    detail::load_lanes(s.theta, &b.theta[k]);
    return s;
  }

  // The rates of the M groups of modes.
  template <std::size_t M>
  std::array<T, M> group_rates() const {
    std::array<T, M> r;
    for (std::size_t j = 0; j < M; ++j) r[j] = group_rate_[j];
    return r;
  }

  static bool all_stopped(const BatchScratch& b, std::size_t k) {
    bool all = true;
    for (std::size_t j = k; j < k + batch_lanes; ++j) all &= b.stopped[j] != T(0);
    return all;
  }

  template <std::size_t M>
  void sums_lanes(BatchScratch& b, std::size_t k) const {
    using V = BatchLanes;
    if (all_stopped(b, k)) return;
    V y;
    detail::load_lanes(y, &b.y[k]);
    const ConeSums<V> sums = cone_sums(load_scaling<M>(b, k), y, group_rates<M>());
    detail::store_lanes(&b.product[k], sums.product);
    detail::store_lanes(&b.n[k], sums.n);
    detail::store_lanes(&b.e1[k], sums.e1);
    detail::store_lanes(&b.e2[k], sums.e2);
    detail::store_lanes(&b.e3[k], sums.e3);
  }

  // solve_multiplier's step and its stopping test, lane by lane.
  void step_lanes(BatchScratch& b, std::size_t k) const {
    using V = BatchLanes;
    if (all_stopped(b, k)) return;
    ConeSums<V> sums;
    detail::load_lanes(sums.product, &b.product[k]);
    detail::load_lanes(sums.n, &b.n[k]);
    detail::load_lanes(sums.e1, &b.e1[k]);
    detail::load_lanes(sums.e2, &b.e2[k]);
    detail::load_lanes(sums.e3, &b.e3[k]);
    V y, lo, scale, stopped;
    detail::load_lanes(y, &b.y[k]);
    detail::load_lanes(lo, &b.lo[k]);
    detail::load_lanes(scale, &b.scale[k]);
    detail::load_lanes(stopped, &b.stopped[k]);
    const ConeStep<V> e = cone_terms(sums);
    // `stopped` is 0 / 1 in doubles: a compare of 64-bit integers needs SSE4.1.
    const auto done = stopped != T(0);
    // |x| < b as -b < x < b, false for NaN as there.
    const auto near = (e.c2e < T(0.25)) & (e.c2e > T(-0.25));
    const V step = near ? e.newton * (T(1) - e.c2e + e.cubic) : e.newton;
    const V moved = y + step;
    const V reach = y + scale;
    const V error = e.newton * e.cubic * step;
    const V tolerance = T(1e-13) * reach * reach;
    const auto stop = near & (moved >= lo) & ~((error > tolerance) | (error < -tolerance));
    const V next = done ? y : (moved < lo ? lo : moved);  // std::max(moved, lo)
    detail::store_lanes(&b.y[k], next);
    detail::store_lanes(&b.stopped[k], (done | stop) ? V{} + T(1) : V{});
  }

  // The returned stresses, stored for the first `count` lanes if they stopped; the others are
  // redone by the per-point return.
  void finish_lanes(const BatchScratch& b, std::size_t k, std::size_t count, stress_type* stress,
                    state_type* state) const {
    using V = BatchLanes;
    const std::array<V, 7> t = gather_trials(b, k, stress);
    V y, q_trial, p_trial, q0;
    detail::load_lanes(y, &b.y[k]);
    detail::load_lanes(q_trial, &b.q_trial[k]);
    detail::load_lanes(p_trial, &b.p_trial[k]);
    detail::load_lanes(q0, &b.q0[k]);
    const V multiplier = y * q_trial;
    const ReturnScales<V> r = return_scales(p_trial, q0, multiplier);
    const std::array<V, 7> out = scaled_stress(t, p_trial, r);
    // A loop of constant length, so each lane is taken from the registers by a constant index
    // (with a variable one the lanes go through memory, and 16-byte loads across two earlier
    // stores stall).
    for (int l = 0; l < batch_lanes; ++l) {
      const std::size_t lane = static_cast<std::size_t>(l);
      if (lane == count) break;
      const std::size_t i = b.index[k + lane];
      if (b.stopped[k + lane] != T(0)) {
        for (int c = 0; c < 7; ++c) stress[i][c] = out[c][l];
        state[i].plastic_shear_strain += static_cast<double>(multiplier[l]);
      } else {
        scalar_return(stress[i], state[i]);
      }
    }
  }

  // At the apex when no point of the cone with q >= 0 is reachable: with beta = 0 any trial
  // beyond the apex, otherwise when the deviator is small at the multiplier that brings p to it.
  bool is_apex(const std::array<T, 3>& w, T q0, T slope) const {
    if (slope <= T(0)) return true;
    const T x = -q0 / slope;
    T h = -1;
    for (int j = 0; j < 3; ++j) {
      if (w[j] <= T(0)) continue;
      const T u = mode_stiffness_[j] * x;
      if (u <= T(0)) return false;
      h += w[j] / (u * u);
    }
    return h <= T(0);
  }

  // D_alg = H - (H g')(f'^T H) / (f'^T H g'),  H = (I + dlambda D g'')^-1 D.
  tangent_type consistent_tangent(const stress_type& stress, T q, T multiplier) const {
    using Vec7 = Eigen::Matrix<T, 7, 1>;
    tangent_type p_tilde = tangent_type::Zero();  // d^2 (q^2 / 2) / d sigma^2
    const T a12 = invariant_.a1 + invariant_.a2;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p_tilde(i, j) = a12 * ((i == j ? T(1) : T(0)) - T(1) / 3);
    p_tilde(3, 3) = p_tilde(4, 4) = invariant_.a1;
    p_tilde(3, 4) = p_tilde(4, 3) = invariant_.a2;
    const T l2 = elastic_.length * elastic_.length;
    p_tilde(5, 5) = p_tilde(6, 6) = invariant_.a3 / l2;
    const Vec7 n = p_tilde * stress / q;
    const tangent_type hessian = (p_tilde - n * n.transpose()) / q;
    const tangent_type d = elastic_.tangent();
    const tangent_type h = (tangent_type::Identity() + multiplier * d * hessian).inverse() * d;
    Vec7 ones = Vec7::Zero();
    ones.template head<3>().setOnes();
    const Vec7 df = n + coefficients_.alpha / 3 * ones;
    const Vec7 dg = n + coefficients_.beta / 3 * ones;
    const Vec7 h_dg = h * dg;
    const Eigen::Matrix<T, 1, 7> df_h = df.transpose() * h;
    return h - h_dg * df_h / df.dot(h_dg);
  }

  detail::CosseratElasticity<T> elastic_;
  DruckerPragerCoefficients<T> coefficients_;
  CosseratInvariantCoefficients<T> invariant_;
  DruckerPragerMatching matching_;
  std::array<T, 3> mode_stiffness_{};  // c_j: how fast each mode shrinks with dlambda
  T bulk_beta_{};                      // K beta: dp / dlambda
  T slope_{};                          // alpha beta K: dq / dlambda on the surface from p
  std::array<T, 3> rate_{};            // slope + c_j
  std::array<T, 3> inverse_stiffness_squared_{};  // 1 / c_j^2 (0 for c_j = 0), the apex strain
  T c_max_{};
  T inverse_rate_max_{};                // 1 / (slope + c_max)
  T inverse_rate_min_{};                // 1 / (slope + c_min), infinity for 0
  detail::CosseratModuli<T> moduli_{};  // as trial_stress uses them
  TrialWeights trial_weights_{};
  // The distinct rates and each mode's group, for update_batch (see ConeStart).
  int groups_ = 0;
  std::array<T, 3> group_rate_{};
  std::array<int, 3> group_of_mode_{};
};

static_assert(ConstitutiveModel<CosseratDruckerPrager<double>>);
static_assert(HasConsistentTangent<CosseratDruckerPrager<double>>);
static_assert(HasBatchUpdate<CosseratDruckerPrager<double>>);

}  // namespace cosmpm::material
