#pragma once
// Perfectly plastic Cosserat Drucker-Prager in 2D plane strain after de Borst (1991, 1993) and
// Tejchman (1997), with the elasticity and component layout of cosserat_elastic.hpp.
// Tension positive, p = (s_xx + s_yy + s_zz) / 3, s_ij = sigma_ij - p delta_ij (non-symmetric):
//   q^2 = a1 s_ij s_ij + a2 s_ij s_ji + a3 m_3i m_3i / l^2      (i, j over x, y, z)
//   f = q + alpha p - k,   g = q + beta p,
// with alpha, beta, k from phi, psi, c by a DruckerPragerMatching (default: the per-angle
// plane-strain formula after Tejchman). With a1 + a2 = 1/2 (the defaults 0.375, 0.125, 1) q is
// sqrt(J2) for a symmetric stress without couple stresses, so the model reduces to the classical
// DruckerPrager with the same coefficients.
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
    modes.p = (s[0] + s[1] + s[2]) / 3;
    const T d0 = s[0] - modes.p, d1 = s[1] - modes.p, d2 = s[2] - modes.p;
    const T sym = (s[3] + s[4]) / 2;
    const T skew = (s[3] - s[4]) / 2;
    modes.weight[0] =
        (invariant_.a1 + invariant_.a2) * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * sym * sym);
    modes.weight[1] = 2 * (invariant_.a1 - invariant_.a2) * skew * skew;
    modes.weight[2] = couple_weight_ * (s[5] * s[5] + s[6] * s[6]);
    return modes;
  }

  // Solves h(x) = sum_j w_j / (q0 + (slope + c_j) x)^2 - 1 = 0 for x > 0; h is convex and
  // decreasing where every u_j = q0 + (slope + c_j) x > 0.
  T solve_multiplier(const std::array<T, 3>& w, T q_trial, T q0, T slope) const {
    const std::array<T, 3>& c = mode_stiffness_;
    const auto h_and_slope = [&](T x, T& dh) {
      T h = -1;
      dh = 0;
      for (int j = 0; j < 3; ++j) {
        if (w[j] <= T(0)) continue;
        const T inverse = 1 / (q0 + (slope + c[j]) * x);
        const T term = w[j] * inverse * inverse;
        h += term;
        dh -= 2 * term * (slope + c[j]) * inverse;
      }
      return h;
    };
    const T c_max = std::max({c[0], c[1], c[2]});
    if (q0 > T(0)) {
      // Inside the apex pressure every u_j >= q0 > 0. The iteration runs on G(x) = F^(-1/2) = 1,
      // F = sum_j w_j / u_j^2: G is a (p = -2) power mean of the u_j, so it is concave and
      // increasing in x and linear when all c_j are equal (one step is then exact). The start
      // is one Newton step from x = 0; `lo` (all c_j = c_max) bounds the root from the left.
      const T lo = (q_trial - q0) / (slope + c_max);
      const T c_mean = (w[0] * c[0] + w[1] * c[1] + w[2] * c[2]) / (q_trial * q_trial);
      T x = (q_trial - q0) / (slope + c_mean);
      const T scale = q0 / (slope + c_max);
      for (int iteration = 0; iteration < 60; ++iteration) {
        const T u0 = q0 + (slope + c[0]) * x;
        const T u1 = q0 + (slope + c[1]) * x;
        const T u2 = q0 + (slope + c[2]) * x;
        const T inverse_product = 1 / (u0 * u1 * u2);  // one division for the three inverses
        const T i0 = u1 * u2 * inverse_product;
        const T i1 = u0 * u2 * inverse_product;
        const T i2 = u0 * u1 * inverse_product;
        const T t0 = w[0] * i0 * i0, t1 = w[1] * i1 * i1, t2 = w[2] * i2 * i2;
        const T r0 = slope + c[0], r1 = slope + c[1], r2 = slope + c[2];
        const T f = t0 + t1 + t2;
        const T df = -2 * (t0 * r0 * i0 + t1 * r1 * i1 + t2 * r2 * i2);
        const T d2f =
            6 * (t0 * r0 * r0 * i0 * i0 + t1 * r1 * r1 * i1 * i1 + t2 * r2 * r2 * i2 * i2);
        // Halley on g = G - 1, G = F^(-1/2): cubic convergence, two evaluations as a rule.
        const T inverse_root = 1 / std::sqrt(f);
        const T inverse_f = inverse_root * inverse_root;
        const T g_value = inverse_root - 1;
        const T g1 = -T(0.5) * df * inverse_f * inverse_root;
        const T g2 = (T(0.75) * df * df * inverse_f - T(0.5) * d2f) * inverse_f * inverse_root;
        const T step = -2 * g_value * g1 / (2 * g1 * g1 - g_value * g2);
        const T next = std::max(x + step, lo);
        // With cubic convergence (constant ~ 1 on this scale) a step below 3e-5 of the scale of
        // the u_j leaves a relative error of order 1e-14 after it: take it and stop. (A test
        // relative to x alone would chase rounding noise when x is tiny.)
        if (!(std::abs(next - x) > T(3e-5) * (x + scale))) return next;
        x = next;
      }
      return x;
    }
    // Beyond the apex pressure (the apex test failed): start right of the last pole of h,
    // where h > 0, and let Newton climb monotonically to the root.
    T x = (q_trial - q0) / (slope + c_max);
    for (int j = 0; j < 3; ++j) {
      if (w[j] <= T(0)) continue;
      const T rate = slope + c[j];
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
    elastic_.add_elastic(stress, de);
    const Modes trial = split(stress);
    const T q_trial = std::sqrt(trial.weight[0] + trial.weight[1] + trial.weight[2]);
    const T alpha = coefficients_.alpha;
    const T f_trial = q_trial + alpha * trial.p - coefficients_.k;
    if (f_trial <= T(0)) {
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_.tangent();
      return;
    }
    state.plastic = 1.0;
    const T bulk = elastic_.iso.bulk();
    const T slope = alpha * coefficients_.beta * bulk;  // dq/dlambda on the surface from p
    const T q0 = coefficients_.k - alpha * trial.p;
    if (q0 <= T(0) && is_apex(trial.weight, q0, slope)) {
      const T apex = apex_pressure();
      T gamma2 = 0;
      for (int j = 0; j < 3; ++j)
        if (mode_stiffness_[j] > T(0))
          gamma2 += trial.weight[j] / (mode_stiffness_[j] * mode_stiffness_[j]);
      state.plastic_shear_strain += static_cast<double>(std::sqrt(gamma2));
      stress << apex, apex, apex, 0, 0, 0, 0;
      if constexpr (WithTangent) tangent->setZero();
      return;
    }
    const T multiplier = solve_multiplier(trial.weight, q_trial, q0, slope);
    const T q = q0 + slope * multiplier;
    const T p = trial.p - bulk * coefficients_.beta * multiplier;
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
};

static_assert(ConstitutiveModel<CosseratDruckerPrager<double>>);
static_assert(HasConsistentTangent<CosseratDruckerPrager<double>>);

}  // namespace cosmpm::material
