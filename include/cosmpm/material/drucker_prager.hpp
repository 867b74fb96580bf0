#pragma once
// Perfectly plastic Drucker-Prager with non-associated flow and an apex return, in plane strain
// with sigma_zz carried (Dim = 2) or in 3D (Dim = 3); component order in stress_space.hpp.
// Tension positive, p = tr(sigma) / 3, q = sqrt(J2) = sqrt(s:s / 2):
//   f = q + alpha p - k,   g = q + beta p,
// alpha, beta and k from the Mohr-Coulomb phi, psi and c by a DruckerPragerMatching
// (drucker_prager_matching.hpp).
#include <Eigen/Core>
#include <cmath>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"
#include "cosmpm/material/drucker_prager_matching.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace cosmpm::material {

// Parameters by name, e.g. DruckerPrager({.youngs_modulus = 2.76e6, .poisson_ratio = 0.2,
// .friction_angle_deg = 26, .dilatancy_angle_deg = 2}).
struct DruckerPragerParameters {
  double youngs_modulus = detail::unset;       // E (Pa), > 0
  double poisson_ratio = detail::unset;        // nu, -1 < nu < 0.5
  double friction_angle_deg = detail::unset;   // phi, 0 < phi < 90
  double dilatancy_angle_deg = detail::unset;  // psi, 0 <= psi <= phi
  double cohesion = 0.0;                       // c (Pa), >= 0
  DruckerPragerMatching matching = DruckerPragerMatching::plane_strain;
};

template <class T = double, int Dim = 2>
class DruckerPrager {
  static constexpr int n = symmetric_components<Dim>;

 public:
  using scalar_type = T;
  using stress_type = SymmetricTensor<Dim, T>;  // [xx, yy, zz, xy(, xz, yz)], tension positive
  using strain_type = SymmetricTensor<Dim, T>;  // tensor shear
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, n, n>;
  using parameters_type = DruckerPragerParameters;
  static constexpr bool is_cosserat = false;
  static constexpr int dimension = Dim;

  explicit DruckerPrager(const DruckerPragerParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_(detail::isotropic_elasticity<T>("DruckerPrager", T(parameters.youngs_modulus),
                                                 T(parameters.poisson_ratio))),
        coefficients_(drucker_prager_coefficients<T>(
            T(parameters.friction_angle_deg), T(parameters.dilatancy_angle_deg),
            T(parameters.cohesion), parameters.matching, "DruckerPrager")) {}
  DruckerPrager(T youngs_modulus, T poisson_ratio, T friction_angle_deg, T dilatancy_angle_deg,
                T cohesion = T(0),
                DruckerPragerMatching matching = DruckerPragerMatching::plane_strain)
      : DruckerPrager(DruckerPragerParameters{
            static_cast<double>(youngs_modulus), static_cast<double>(poisson_ratio),
            static_cast<double>(friction_angle_deg), static_cast<double>(dilatancy_angle_deg),
            static_cast<double>(cohesion), matching}) {}

  const DruckerPragerParameters& parameters() const { return parameters_; }
  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }
  const DruckerPragerCoefficients<T>& coefficients() const { return coefficients_; }
  DruckerPragerMatching matching() const { return parameters_.matching; }
  T apex_pressure() const { return coefficients_.k / coefficients_.alpha; }

  // f = q + alpha p - k in Pa; <= 0 inside.
  T yield_function(const stress_type& stress) const {
    const T p = (stress[0] + stress[1] + stress[2]) / 3;
    Vec s = stress;
    for (int i = 0; i < 3; ++i) s[i] = stress[i] - p;
    return invariant_q(s) + coefficients_.alpha * p - coefficients_.k;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    update_impl<false>(stress, state, de, nullptr);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update_impl<true>(stress, state, de, &tangent);
  }

  tangent_type elastic_tangent() const { return elastic_.template tangent<n>(); }

 private:
  using Vec = Eigen::Matrix<T, n, 1>;
  // q = sqrt(J2) of a deviator stored [xx, yy, zz, shears]: each shear counts twice in s:s.
  static T invariant_q(const Vec& s) {
    T q2 = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / 2;
    for (int c = 3; c < n; ++c) q2 += s[c] * s[c];
    return std::sqrt(q2);
  }

  static const DruckerPragerParameters& checked(const DruckerPragerParameters& p) {
    detail::require_set("DruckerPrager", "DruckerPragerParameters",
                        {{"youngs_modulus", p.youngs_modulus},
                         {"poisson_ratio", p.poisson_ratio},
                         {"friction_angle_deg", p.friction_angle_deg},
                         {"dilatancy_angle_deg", p.dilatancy_angle_deg}});
    return p;
  }

  // The one stress update (with or without the tangent).
  template <bool WithTangent>
  void update_impl(stress_type& stress, state_type& state, const strain_type& de,
                   tangent_type* tangent) const {
    const T shear = elastic_.shear;
    const T bulk = elastic_.bulk();
    const auto t = elastic_.template trial<n>(stress, de);
    const T p_trial = (t[0] + t[1] + t[2]) / 3;
    Vec s_trial;
    for (int c = 0; c < n; ++c) s_trial[c] = c < 3 ? t[c] - p_trial : t[c];
    const T q_trial = invariant_q(s_trial);
    const T f_trial = q_trial + coefficients_.alpha * p_trial - coefficients_.k;
    if (f_trial <= T(0)) {
      for (int c = 0; c < n; ++c) stress[c] = t[c];
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_tangent();
      return;
    }
    state.plastic = 1.0;
    const T hardness = shear + coefficients_.alpha * coefficients_.beta * bulk;
    const T multiplier = f_trial / hardness;
    if (q_trial - shear * multiplier > T(0)) {
      // Smooth cone: the deviator shrinks radially, p moves by the dilatancy.
      const T scale = 1 - shear * multiplier / q_trial;
      const T p = p_trial - bulk * coefficients_.beta * multiplier;
      for (int i = 0; i < 3; ++i) stress[i] = scale * s_trial[i] + p;
      for (int c = 3; c < n; ++c) stress[c] = scale * s_trial[c];
      // Equivalent plastic shear strain sqrt(2 e:e) of d eps_p = multiplier (s / 2q + ...).
      state.plastic_shear_strain += static_cast<double>(multiplier);
      if constexpr (WithTangent) {
        const Vec normal = s_trial / q_trial;  // unit in the sense q(normal) = 1
        Vec contract = normal;                 // normal . de counts each tensor shear twice
        for (int c = 3; c < n; ++c) contract[c] = 2 * normal[c];
        Vec ones = Vec::Zero();
        ones.template head<3>().setOnes();
        const Vec d_multiplier = (shear * contract + coefficients_.alpha * bulk * ones) / hardness;
        tangent_type deviatoric = tangent_type::Zero();
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) deviatoric(i, j) = (i == j ? T(1) : T(0)) - T(1) / 3;
        for (int c = 3; c < n; ++c) deviatoric(c, c) = 1;
        *tangent = scale * 2 * shear * deviatoric +
                   (shear * shear * multiplier / q_trial) * normal * contract.transpose() -
                   shear * normal * d_multiplier.transpose() + bulk * ones * ones.transpose() -
                   bulk * coefficients_.beta * ones * d_multiplier.transpose();
      }
      return;
    }
    // Apex: hydrostatic stress at c cot(phi); the whole trial deviator is plastic.
    const T apex = apex_pressure();
    for (int c = 0; c < n; ++c) stress[c] = c < 3 ? apex : T(0);
    state.plastic_shear_strain += static_cast<double>(q_trial / shear);
    if constexpr (WithTangent) tangent->setZero();
  }

  DruckerPragerParameters parameters_;
  detail::IsotropicElasticity<T> elastic_;
  DruckerPragerCoefficients<T> coefficients_;
};

static_assert(ConstitutiveModel<DruckerPrager<double>>);
static_assert(HasConsistentTangent<DruckerPrager<double>>);
static_assert(HasConsistentTangent<DruckerPrager<double, 3>>);

}  // namespace cosmpm::material
