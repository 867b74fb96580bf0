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
// (p = c cot(phi), s = 0, m = 0) takes the trial states the cone cannot.
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
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
    couple_weight_ = invariant.a3 / (elastic_.length * elastic_.length);
    symmetric_weight_ = invariant.a1 + invariant.a2;
    skew_weight_ = 2 * (invariant.a1 - invariant.a2);
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
    half_symmetric_weight_ = symmetric_weight_ / 2;
    quarter_skew_weight_ = skew_weight_ / 4;
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
    const Modes modes = split(stress);
    return std::sqrt(modes.weight[0] + modes.weight[1] + modes.weight[2]);
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

 private:
  // The stress split into p and the three mode groups with their contributions to q^2.
  struct Modes {
    T p{};
    std::array<T, 3> weight{};  // q^2 = sum of these
  };

  Modes split(const stress_type& s) const {
    Modes modes;
    modes.p = (s[0] + s[1] + s[2]) * (T(1) / 3);  // a product: a division would sit in the chain
    const T d0 = s[0] - modes.p, d1 = s[1] - modes.p, d2 = s[2] - modes.p;
    const T sym = (s[3] + s[4]) / 2;
    const T skew = (s[3] - s[4]) / 2;
    modes.weight[0] = symmetric_weight_ * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * sym * sym);
    modes.weight[1] = skew_weight_ * skew * skew;
    modes.weight[2] = couple_weight_ * (s[5] * s[5] + s[6] * s[6]);
    return modes;
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
      // Inside the apex pressure every u_j >= q0 > 0. Scaled by q_trial (y = x / q_trial,
      // theta = q0 / q_trial, pi_j = w_j / q_trial^2, v_j = theta + r_j y) the equation is
      // F(y) = sum_j pi_j / v_j^2 = 1, solved on G = F^(-1/2) = 1: G is the (p = -2) power mean
      // of the v_j, concave and increasing in y, linear when all r_j are equal.
      const T inverse_w = 1 / w_sum;  // independent of the square root that gave q_trial
      const T pi0 = w[0] * inverse_w, pi1 = w[1] * inverse_w, pi2 = w[2] * inverse_w;
      const T theta = q0 * q_trial * inverse_w;
      // Start: with r_mean = sum_j pi_j r_j, a = theta + r_mean y, tau = y / a, d_j = r_j -
      // r_mean and m_k = sum_j pi_j d_j^k, G = a phi(tau) and 1 / phi = sqrt(sum_j pi_j /
      // (1 + d_j tau)^2) = 1 + k2 tau^2 + ... + k6 tau^6 + O(tau^7) (k1 = 0 as m1 = 0); the start
      // is a = 1 / phi(tau) with tau at the linear root (1 - theta) / r_mean, exact when all
      // r_j are equal (the classical case). The terms up to tau^6 make one step enough for
      // about 90 % of the benchmark's plastic states (60 % with terms up to tau^3).
      const T wr = w[0] * r[0] + w[1] * r[1] + w[2] * r[2];
      const T r_mean = wr * inverse_w;
      const T inverse_r_mean = w_sum / wr;
      const T d0 = r[0] - r_mean, d1 = r[1] - r_mean, d2 = r[2] - r_mean;
      const T pd0 = pi0 * d0 * d0, pd1 = pi1 * d1 * d1, pd2 = pi2 * d2 * d2;
      const T pdd0 = pd0 * d0, pdd1 = pd1 * d1, pdd2 = pd2 * d2;
      const T m2 = pd0 + pd1 + pd2;
      const T m3 = pdd0 + pdd1 + pdd2;
      const T m4 = pdd0 * d0 + pdd1 * d1 + pdd2 * d2;
      const T m5 = pdd0 * d0 * d0 + pdd1 * d1 * d1 + pdd2 * d2 * d2;
      const T m6 = pdd0 * d0 * d0 * d0 + pdd1 * d1 * d1 * d1 + pdd2 * d2 * d2 * d2;
      const T k2 = T(1.5) * m2;
      const T k3 = -2 * m3;
      const T k4 = T(2.5) * m4 - T(1.125) * m2 * m2;
      const T k5 = 3 * (m2 * m3 - m5);
      const T k6 = T(3.5) * m6 - 2 * m3 * m3 - T(3.75) * m2 * m4 + T(1.6875) * m2 * m2 * m2;
      const T tau = (1 - theta) * inverse_r_mean;
      const T tau2 = tau * tau;  // Estrin's scheme: a shorter dependent chain than Horner's
      const T inverse_phi = 1 + tau2 * ((k2 + tau * k3) + tau2 * ((k4 + tau * k5) + tau2 * k6));
      // `lo` (all c_j = c_max) and `hi` (all c_j = c_min) bracket the root; `scale` is the
      // distance from y = 0 to the nearest pole of F.
      const T lo = (1 - theta) * inverse_rate_max_;
      const T hi = (1 - theta) * inverse_rate_min_;
      const T scale = theta * inverse_rate_max_;
      T y = std::clamp((inverse_phi - theta) * inverse_r_mean, lo, std::max(lo, hi));
      for (int iteration = 0; iteration < 60; ++iteration) {
        // With V = v0 v1 v2, P_j = V / v_j, N = sum pi_j P_j^2, D_k = sum pi_j r_j^k P_j^(k+2):
        // F = N / V^2, F' = -2 D1 / V^3, F'' = 6 D2 / V^4, F''' = -24 D3 / V^5. One square
        // root and one division (independent of each other) per step.
        const T v0 = theta + r[0] * y, v1 = theta + r[1] * y, v2 = theta + r[2] * y;
        const T p0 = v1 * v2, p1 = v0 * v2, p2 = v0 * v1;
        const T product = v0 * p0;
        const T a0 = pi0 * p0 * p0, a1 = pi1 * p1 * p1, a2 = pi2 * p2 * p2;
        const T b0 = r[0] * p0, b1 = r[1] * p1, b2 = r[2] * p2;
        const T ab0 = a0 * b0, ab1 = a1 * b1, ab2 = a2 * b2;
        const T abb0 = ab0 * b0, abb1 = ab1 * b1, abb2 = ab2 * b2;
        const T n = a0 + a1 + a2;
        const T e1 = ab0 + ab1 + ab2;
        const T e2 = abb0 + abb1 + abb2;
        const T e3 = abb0 * b0 + abb1 * b1 + abb2 * b2;
        const T root_n = std::sqrt(n);
        const T qn = product * n;
        const T inverse = 1 / (qn * qn * e1);  // 1 / (Q^2 D1), Q = V N
        // Series reversion of the cubic Taylor polynomial of G - 1 (a fourth-order step):
        // h = e - c2 e^2 + (2 c2^2 - c3) e^3 with e = -(G - 1) / G' the Newton step,
        // c2 = G'' / (2 G'), c3 = G''' / (6 G'), written out in N, V and the D_k.
        const T newton = (root_n - product) * n * qn * qn * inverse;
        const T c2 = T(1.5) * (e1 * e1 - e2 * n) * qn * inverse;
        const T c3 = (15 * e1 * e1 * e1 - 27 * e1 * e2 * n + 12 * e3 * n * n) * inverse / 6;
        const T c2e = c2 * newton;
        const T cubic = 2 * c2e * c2e - c3 * newton * newton;  // relative cubic term
        // Far from the root (the first steps of a large return) take the plain Newton step,
        // which stays left of the root of the concave G.
        const bool near = std::abs(c2e) < T(0.25);
        const T step = near ? newton * (1 - c2e + cubic) : newton;
        const T next = std::max(y + step, lo);
        // The error left by the fourth-order step is about |cubic term| |step| / reach, reach =
        // the distance to the nearest pole (within a factor 1.4 over the benchmark's states,
        // against a converged solve); accept at 1e-12 relative. The tests ask 1e-10 of f.
        const T reach = y + scale;
        if (near && y + step >= lo && !(std::abs(newton * cubic * step) > T(1e-13) * reach * reach))
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

  template <bool WithTangent>
  void update_impl(stress_type& stress, state_type& state, const strain_type& de,
                   tangent_type* tangent) const {
    // The trial stress in scalars, every load before the first store (see trial_stress).
    const std::array<T, 7> trial = detail::trial_stress(stress, de, moduli_);
    const T t0 = trial[0], t1 = trial[1], t2 = trial[2], t3 = trial[3], t4 = trial[4],
            t5 = trial[5], t6 = trial[6];
    const T p = (t0 + t1 + t2) * (T(1) / 3);
    const T d0 = t0 - p, d1 = t1 - p, d2 = t2 - p;
    const T sum = t3 + t4, difference = t3 - t4;  // twice the symmetric and skew shear
    const T w0 =
        symmetric_weight_ * (d0 * d0 + d1 * d1 + d2 * d2) + half_symmetric_weight_ * sum * sum;
    const T w1 = quarter_skew_weight_ * difference * difference;
    const T w2 = couple_weight_ * (t5 * t5 + t6 * t6);
    const T w_sum = w0 + w1 + w2;                            // q_trial^2
    const T q0 = coefficients_.k - coefficients_.alpha * p;  // q on the surface at p_trial
    // f_trial = q_trial - q0 <= 0, decided without the square root so the branch resolves early.
    if ((q0 >= T(0)) & (w_sum <= q0 * q0)) {
      stress << t0, t1, t2, t3, t4, t5, t6;
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_.tangent();
      return;
    }
    stress << t0, t1, t2, t3, t4, t5, t6;
    plastic_return<WithTangent>(stress, state, tangent, p, w0, w1, w2, w_sum, q0);
  }

  // The return of the plastic trial state `stress`, out of line so that the elastic path above
  // stays short (no spills, no saved registers); the trial's split (p, the weights of q^2,
  // q_trial^2, q0) comes in registers.
  template <bool WithTangent>
  [[gnu::noinline]] void plastic_return(stress_type& stress, state_type& state,
                                        tangent_type* tangent, T p_trial, T w0, T w1, T w2, T w_sum,
                                        T q0) const {
    const Modes trial{p_trial, {w0, w1, w2}};
    state.plastic = 1.0;
    const T q_trial = std::sqrt(w_sum);
    if (q0 <= T(0) && is_apex(trial.weight, q0, slope_)) {
      const T apex = apex_pressure();
      const T gamma2 = trial.weight[0] * inverse_stiffness_squared_[0] +
                       trial.weight[1] * inverse_stiffness_squared_[1] +
                       trial.weight[2] * inverse_stiffness_squared_[2];
      state.plastic_shear_strain += static_cast<double>(std::sqrt(gamma2));
      stress << apex, apex, apex, 0, 0, 0, 0;
      if constexpr (WithTangent) tangent->setZero();
      return;
    }
    const T multiplier = solve_multiplier(trial.weight, w_sum, q_trial, q0);
    const T q = q0 + slope_ * multiplier;
    const T p = trial.p - bulk_beta_ * multiplier;
    // scale_j = q / (q + c_j dlambda), the three from one division.
    const T v0 = q + mode_stiffness_[0] * multiplier;
    const T v1 = q + mode_stiffness_[1] * multiplier;
    const T v2 = q + mode_stiffness_[2] * multiplier;
    const T q_over_product = q / (v0 * v1 * v2);
    const std::array<T, 3> scale{v1 * v2 * q_over_product, v0 * v2 * q_over_product,
                                 v0 * v1 * q_over_product};
    const T sym = scale[0] * (stress[3] + stress[4]) / 2;
    const T skew = scale[1] * (stress[3] - stress[4]) / 2;
    for (int i = 0; i < 3; ++i) stress[i] = scale[0] * (stress[i] - trial.p) + p;
    stress[3] = sym + skew;
    stress[4] = sym - skew;
    stress[5] *= scale[2];
    stress[6] *= scale[2];
    // The multiplier is the plastic strain conjugate to q: the engineering plastic shear strain
    // sqrt(2 e:e) in the symmetric case.
    state.plastic_shear_strain += static_cast<double>(multiplier);
    if constexpr (WithTangent) *tangent = consistent_tangent(stress, q, multiplier);
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
  T couple_weight_{};                  // a3 / l^2
  T symmetric_weight_{};               // a1 + a2
  T skew_weight_{};                    // 2 (a1 - a2)
  T bulk_beta_{};                      // K beta: dp / dlambda
  T slope_{};                          // alpha beta K: dq / dlambda on the surface from p
  std::array<T, 3> rate_{};            // slope + c_j
  std::array<T, 3> inverse_stiffness_squared_{};  // 1 / c_j^2 (0 for c_j = 0), the apex strain
  T c_max_{};
  T inverse_rate_max_{};  // 1 / (slope + c_max)
  T inverse_rate_min_{};  // 1 / (slope + c_min), infinity for 0
  // The elastic moduli as add_elastic uses them and the weights of q^2 for the trial's
  // (t3 + t4) and (t3 - t4).
  detail::CosseratModuli<T> moduli_{};
  T half_symmetric_weight_{}, quarter_skew_weight_{};
};

static_assert(ConstitutiveModel<CosseratDruckerPrager<double>>);
static_assert(HasConsistentTangent<CosseratDruckerPrager<double>>);

}  // namespace cosmpm::material
