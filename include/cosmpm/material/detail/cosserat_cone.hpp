#pragma once
// The return of CosseratDruckerPrager onto its cone (theory in cosserat_drucker_prager.hpp and
// docs/theory/materials.md): the trial's split into modes, the scalar equation for the plastic
// multiplier, its start, its fourth-order step and the returned stress. Every formula is a
// template on the value type V, T for the per-point update and lanes of T (lanes.hpp) for the
// batched one (cosserat_batch.hpp), so both run the same operations, written once. Masks are
// what a comparison of V gives: bool for T, lanes of -1 / 0 for lanes; `cond ? a : b` selects
// with either.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "cosmpm/material/detail/cosserat_elasticity.hpp"
#include "cosmpm/material/detail/lanes.hpp"
#include "cosmpm/material/drucker_prager_matching.hpp"

namespace cosmpm::material::detail {

// Not, for masks of plain values (bool, or the int that & and | of bools give) and lane masks.
template <class Mask>
inline Mask mask_not(const Mask& m) {
  if constexpr (std::is_arithmetic_v<Mask>) {
    return !m;
  } else {
    return ~m;
  }
}

template <class T>
class CosseratCone {
 public:
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

  CosseratCone() = default;
  // q^2 = a1 s_ij s_ij + a2 s_ij s_ji + a3 m_3i m_3i / l^2 (validated by the model).
  CosseratCone(const CosseratElasticity<T>& elastic, const DruckerPragerCoefficients<T>& cone, T a1,
               T a2, T a3) {
    const T g = elastic.iso.shear;
    mode_stiffness_ = {2 * g * (a1 + a2), 2 * elastic.cosserat_shear * (a1 - a2), 2 * g * a3};
    bulk_beta_ = elastic.iso.bulk() * cone.beta;
    slope_ = cone.alpha * bulk_beta_;
    for (int j = 0; j < 3; ++j) {
      rate_[j] = slope_ + mode_stiffness_[j];
      inverse_stiffness_squared_[j] =
          mode_stiffness_[j] > T(0) ? 1 / (mode_stiffness_[j] * mode_stiffness_[j]) : T(0);
    }
    c_max_ = std::max({mode_stiffness_[0], mode_stiffness_[1], mode_stiffness_[2]});
    inverse_rate_max_ = 1 / (slope_ + c_max_);
    // q^2 = (a1 + a2) (d:d + 2 sym^2) + 2 (a1 - a2) skew^2 + a3 m.m / l^2, with sym and skew the
    // halves of t3 + t4 and t3 - t4.
    const T symmetric_weight = a1 + a2;
    const T skew_weight = 2 * (a1 - a2);
    weights_ = {symmetric_weight, symmetric_weight / 2,
                skew_weight / 4,  a3 / (elastic.length * elastic.length),
                cone.k,           cone.alpha};
    for (int j = 0; j < 3; ++j) {  // the modes by rate, equal rates in one group
      int group = 0;
      while (group < groups_ && group_rate_[group] != rate_[j]) ++group;
      if (group == groups_) group_rate_[groups_++] = rate_[j];
      group_of_mode_[j] = group;
    }
    const T rate_min = std::min({rate_[0], rate_[1], rate_[2]});
    inverse_rate_min_ = rate_min > T(0) ? 1 / rate_min : std::numeric_limits<T>::infinity();
  }

  const TrialWeights& weights() const { return weights_; }
  T slope() const { return slope_; }  // alpha beta K: dq / dlambda on the surface from p
  int groups() const { return groups_; }
  int group_of_mode(int j) const { return group_of_mode_[j]; }
  // The rates of the M groups of modes.
  template <std::size_t M>
  std::array<T, M> group_rates() const {
    std::array<T, M> r;
    for (std::size_t j = 0; j < M; ++j) r[j] = group_rate_[j];
    return r;
  }

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
  // f_trial = q_trial - q0 <= 0, decided without the square root.
  template <class V>
  static auto is_elastic(const TrialSplit<V>& split) {
    return (split.q0 >= T(0)) & (split.w_sum <= split.q0 * split.q0);
  }

  // Inside the apex pressure (q0 > 0) every u_j = q0 + r_j x >= q0 > 0. Scaled by q_trial
  // (y = x / q_trial, theta = q0 / q_trial, pi_j = w_j / q_trial^2, v_j = theta + r_j y) the
  // equation is F(y) = sum_j pi_j / v_j^2 = 1, solved on G = F^(-1/2) = 1: G is the (p = -2)
  // power mean of the v_j, concave and increasing in y, linear when all r_j are equal.
  //
  // The functions below take the modes in M groups of equal rate r_j (the sum of their w_j
  // each): update() passes the three modes as they are, update_batch() merges those of equal
  // rate (M = 2 with the paper's Gc = 2G and default a1, a2), which saves a third of the work
  // of a step and is the one difference between the two paths (rounding only).
  template <class V, std::size_t M>
  struct ConeStart {
    std::array<V, M> pi;
    V theta;
    V r_mean, inverse_r_mean;  // sum_j pi_j r_j and its inverse
    V lo, hi;  // the roots with all c_j = c_max and all c_j = c_min, which bracket the root
    V scale;   // the distance from y = 0 to the nearest pole of F
    V y;       // the start, to be clamped to [lo, max(lo, hi)]
  };

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

  // The start y clamped to [lo, max(lo, hi)] (std::clamp, written with selections).
  template <class V, std::size_t M>
  static V clamped_start(const ConeStart<V, M>& s) {
    const V top = s.lo < s.hi ? s.hi : s.lo;
    return s.y < s.lo ? s.lo : (top < s.y ? top : s.y);
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
    sqrt_in_place(root_n);
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

  // The step from y and whether it meets the stopping test; `next` = max(y + step, lo). Far
  // from the root (the first steps of a large return, |c2 e| >= 1/4) the plain Newton step,
  // which stays left of the root of the concave G. The error left by the fourth-order step is
  // about |cubic term| |step| / reach, reach = the distance to the nearest pole (within a
  // factor 1.4 over the benchmark's states, against a converged solve); it stops at 1e-12
  // relative. The tests ask 1e-10 of f.
  template <class V>
  static auto cone_step(const ConeStep<V>& e, const V& y, const V& lo, const V& scale, V& next) {
    const auto near = (e.c2e < T(0.25)) & (e.c2e > T(-0.25));  // |c2e| < 1/4, false for NaN
    const V step = near ? e.newton * (T(1) - e.c2e + e.cubic) : e.newton;
    const V moved = y + step;
    next = moved < lo ? lo : moved;
    const V reach = y + scale;
    const V error = e.newton * e.cubic * step;
    const V tolerance = T(1e-13) * reach * reach;
    return near & (moved >= lo) & mask_not((error > tolerance) | (error < -tolerance));
  }

  // Solves h(x) = sum_j w_j / (q0 + (slope + c_j) x)^2 - 1 = 0 for x > 0 over the three modes;
  // h is convex and decreasing where every u_j = q0 + (slope + c_j) x > 0. `w_sum` = q_trial^2.
  T solve_multiplier(const std::array<T, 3>& w, T w_sum, T q_trial, T q0) const {
    const std::array<T, 3>& r = rate_;  // slope + c_j
    if (q0 > T(0)) {
      ConeStart<T, 3> s = cone_scaling<T, 3>(w, w_sum, q_trial, q0, r);
      cone_series(s, r);
      T y = clamped_start(s);
      for (int iteration = 0; iteration < 60; ++iteration) {
        T next;
        if (cone_step(cone_terms(cone_sums(s, y, r)), y, s.lo, s.scale, next))
          return next * q_trial;
        y = next;
      }
      return y * q_trial;
    }
    // Beyond the apex pressure (the apex test failed): start right of the last pole of h,
    // where h > 0, and let Newton climb monotonically to the root.
    T x = (q_trial - q0) / (slope_ + c_max_);
    for (int j = 0; j < 3; ++j) {
      if (w[j] <= T(0)) continue;
      if (q0 + r[j] * x <= T(0)) x = -q0 / r[j] * (1 + T(1e-6));
    }
    for (int iteration = 0; iteration < 100; ++iteration) {
      T h = -1, dh = 0;
      for (int j = 0; j < 3; ++j) {
        if (w[j] <= T(0)) continue;
        const T inverse = 1 / (q0 + r[j] * x);
        const T term = w[j] * inverse * inverse;
        h += term;
        dh -= 2 * term * r[j] * inverse;
      }
      const T step = -h / dh;
      x += step;
      if (!(std::abs(step) > T(1e-15) * x)) break;
    }
    return x;
  }

  // At the apex when no point of the cone with q >= 0 is reachable: with beta = 0 any trial
  // beyond the apex, otherwise when the deviator is small at the multiplier that brings p to it.
  bool is_apex(const std::array<T, 3>& w, T q0) const {
    if (slope_ <= T(0)) return true;
    const T x = -q0 / slope_;
    T h = -1;
    for (int j = 0; j < 3; ++j) {
      if (w[j] <= T(0)) continue;
      const T u = mode_stiffness_[j] * x;
      if (u <= T(0)) return false;
      h += w[j] / (u * u);
    }
    return h <= T(0);
  }
  // The plastic shear strain of a return to the apex: the whole trial deviator of each mode.
  T apex_strain(const std::array<T, 3>& w) const {
    return std::sqrt(w[0] * inverse_stiffness_squared_[0] + w[1] * inverse_stiffness_squared_[1] +
                     w[2] * inverse_stiffness_squared_[2]);
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

 private:
  // f(0) + f(1) + ... + f(M - 1), summed in that order.
  template <std::size_t M, class F>
  static auto sum_over(F&& f) {
    auto total = f(0);
    for (std::size_t j = 1; j < M; ++j) total = total + f(j);
    return total;
  }

  std::array<T, 3> mode_stiffness_{};             // c_j: how fast each mode shrinks with dlambda
  T bulk_beta_{};                                 // K beta: dp / dlambda
  T slope_{};                                     // alpha beta K
  std::array<T, 3> rate_{};                       // slope + c_j
  std::array<T, 3> inverse_stiffness_squared_{};  // 1 / c_j^2 (0 for c_j = 0), the apex strain
  T c_max_{};
  T inverse_rate_max_{};  // 1 / (slope + c_max)
  T inverse_rate_min_{};  // 1 / (slope + c_min), infinity for 0
  TrialWeights weights_{};
  // The distinct rates and each mode's group, for update_batch (see ConeStart).
  int groups_ = 0;
  std::array<T, 3> group_rate_{};
  std::array<int, 3> group_of_mode_{};
};

}  // namespace cosmpm::material::detail
