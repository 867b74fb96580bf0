#pragma once
// Perfectly plastic Drucker-Prager with non-associated flow and an apex return, plane strain
// with sigma_zz carried. Tension positive, p = tr(sigma) / 3, q = sqrt(J2) = sqrt(s:s / 2):
//   f = q + alpha p - k,   g = q + beta p.
// alpha, beta and k follow from the Mohr-Coulomb phi, psi and c by one of the matchings below
// (docs/theory/materials.md derives them). k = alpha c cot(phi) for every matching, so the apex
// p = k / alpha = c cot(phi) coincides with the Mohr-Coulomb apex.
#include <Eigen/Core>
#include <cmath>
#include <string_view>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/elastic_parameters.hpp"

namespace cosmpm::material {

enum class DruckerPragerMatching {
  // The plane-strain limit state of Mohr-Coulomb, exactly, for the given psi (plastic flow with
  // d eps_zz = 0): alpha = sqrt3 sin(phi) sqrt(3 + sin^2 psi) / (3 + sin phi sin psi),
  // beta = sqrt3 sin(psi) / sqrt(3 + sin^2 psi). Reduces to the classical associated formula when
  // psi = phi. The default.
  plane_strain,
  // The associated plane-strain formula applied to each angle on its own:
  // alpha = sqrt3 sin(phi) / sqrt(3 + sin^2 phi) (= 3 tan phi / sqrt(9 + 12 tan^2 phi)), beta the
  // same with psi. The Cosserat default; our choice: the paper says only that the polar
  // parameters follow Tejchman (1997) and gives no formula (docs/theory/materials.md).
  plane_strain_per_angle,
  // Cone through the triaxial-compression corners (circumscribes Mohr-Coulomb):
  // alpha = 2 sqrt3 sin(phi) / (3 - sin phi), beta likewise with psi.
  outer,
  // Cone through the triaxial-extension corners: alpha = 2 sqrt3 sin(phi) / (3 + sin phi).
  inner,
};

// Drucker-Prager coefficients of f = q + alpha p - k and g = q + beta p (q = sqrt(J2)).
template <class T>
struct DruckerPragerCoefficients {
  T alpha{};
  T beta{};
  T k{};
};

// Angles in degrees (validated: 0 < phi < 90, 0 <= psi <= phi), cohesion in Pa (>= 0).
template <class T>
DruckerPragerCoefficients<T> drucker_prager_coefficients(
    T friction_angle_deg, T dilatancy_angle_deg, T cohesion,
    DruckerPragerMatching matching = DruckerPragerMatching::plane_strain,
    std::string_view where = "drucker_prager_coefficients") {
  detail::check_friction_angles(where, static_cast<double>(friction_angle_deg),
                                static_cast<double>(dilatancy_angle_deg));
  require_non_negative(where, "cohesion", static_cast<double>(cohesion));
  const T sp = std::sin(T(degrees_to_radians(static_cast<double>(friction_angle_deg))));
  const T sd = std::sin(T(degrees_to_radians(static_cast<double>(dilatancy_angle_deg))));
  const T sqrt3 = std::sqrt(T(3));
  DruckerPragerCoefficients<T> out;
  switch (matching) {
    case DruckerPragerMatching::plane_strain:
      out.alpha = sqrt3 * sp * std::sqrt(3 + sd * sd) / (3 + sp * sd);
      out.beta = sqrt3 * sd / std::sqrt(3 + sd * sd);
      break;
    case DruckerPragerMatching::plane_strain_per_angle:
      out.alpha = sqrt3 * sp / std::sqrt(3 + sp * sp);
      out.beta = sqrt3 * sd / std::sqrt(3 + sd * sd);
      break;
    case DruckerPragerMatching::outer:
      out.alpha = 2 * sqrt3 * sp / (3 - sp);
      out.beta = 2 * sqrt3 * sd / (3 - sd);
      break;
    case DruckerPragerMatching::inner:
      out.alpha = 2 * sqrt3 * sp / (3 + sp);
      out.beta = 2 * sqrt3 * sd / (3 + sd);
      break;
  }
  out.k = out.alpha * cohesion * std::sqrt(1 - sp * sp) / sp;
  return out;
}

template <class T = double>
class DruckerPrager {
 public:
  using scalar_type = T;
  using stress_type = SymTensor2D<T>;  // [xx, yy, zz, xy], tension positive
  using strain_type = SymTensor2D<T>;  // [dxx, dyy, dzz, dxy], tensor shear
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, 4, 4>;
  static constexpr bool is_cosserat = false;

  DruckerPrager(T youngs_modulus, T poisson_ratio, T friction_angle_deg, T dilatancy_angle_deg,
                T cohesion = T(0),
                DruckerPragerMatching matching = DruckerPragerMatching::plane_strain)
      : elastic_(detail::isotropic_elasticity<T>("DruckerPrager", youngs_modulus, poisson_ratio)),
        coefficients_(drucker_prager_coefficients<T>(friction_angle_deg, dilatancy_angle_deg,
                                                     cohesion, matching, "DruckerPrager")),
        matching_(matching) {}

  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }
  const DruckerPragerCoefficients<T>& coefficients() const { return coefficients_; }
  DruckerPragerMatching matching() const { return matching_; }
  T apex_pressure() const { return coefficients_.k / coefficients_.alpha; }

  // f = q + alpha p - k in Pa; <= 0 inside.
  T yield_function(const stress_type& stress) const {
    const T p = (stress[0] + stress[1] + stress[2]) / 3;
    const Eigen::Matrix<T, 4, 1> s(stress[0] - p, stress[1] - p, stress[2] - p, stress[3]);
    return invariant_q(s) + coefficients_.alpha * p - coefficients_.k;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    update_impl<false>(stress, state, de, nullptr);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update_impl<true>(stress, state, de, &tangent);
  }

  tangent_type elastic_tangent() const {
    tangent_type d = tangent_type::Zero();
    d.template topLeftCorner<3, 3>().setConstant(elastic_.lambda);
    for (int i = 0; i < 3; ++i) d(i, i) += 2 * elastic_.shear;
    d(3, 3) = 2 * elastic_.shear;
    return d;
  }

 private:
  using Vec4 = Eigen::Matrix<T, 4, 1>;
  // q = sqrt(J2) of a deviator stored [xx, yy, zz, xy]: the shear counts twice in s:s.
  static T invariant_q(const Vec4& s) {
    return std::sqrt((s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / 2 + s[3] * s[3]);
  }

  template <bool WithTangent>
  void update_impl(stress_type& stress, state_type& state, const strain_type& de,
                   tangent_type* tangent) const {
    const T shear = elastic_.shear;
    const T bulk = elastic_.bulk();
    const T volumetric = elastic_.lambda * (de[0] + de[1] + de[2]);
    stress[0] += volumetric + 2 * shear * de[0];
    stress[1] += volumetric + 2 * shear * de[1];
    stress[2] += volumetric + 2 * shear * de[2];
    stress[3] += 2 * shear * de[3];
    const T p_trial = (stress[0] + stress[1] + stress[2]) / 3;
    const Vec4 s_trial(stress[0] - p_trial, stress[1] - p_trial, stress[2] - p_trial, stress[3]);
    const T q_trial = invariant_q(s_trial);
    const T f_trial = q_trial + coefficients_.alpha * p_trial - coefficients_.k;
    if (f_trial <= T(0)) {
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
      stress[3] = scale * s_trial[3];
      // Equivalent plastic shear strain sqrt(2 e:e) of d eps_p = multiplier (s / 2q + ...).
      state.plastic_shear_strain += static_cast<double>(multiplier);
      if constexpr (WithTangent) {
        const Vec4 n = s_trial / q_trial;  // unit in the sense q(n) = 1
        const Vec4 n_contract(n[0], n[1], n[2], 2 * n[3]);
        const Vec4 ones(1, 1, 1, 0);
        const Vec4 d_multiplier =
            (shear * n_contract + coefficients_.alpha * bulk * ones) / hardness;
        tangent_type deviatoric = tangent_type::Zero();
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) deviatoric(i, j) = (i == j ? T(1) : T(0)) - T(1) / 3;
        deviatoric(3, 3) = 1;
        *tangent = scale * 2 * shear * deviatoric +
                   (shear * shear * multiplier / q_trial) * n * n_contract.transpose() -
                   shear * n * d_multiplier.transpose() + bulk * ones * ones.transpose() -
                   bulk * coefficients_.beta * ones * d_multiplier.transpose();
      }
      return;
    }
    // Apex: hydrostatic stress at c cot(phi); the whole trial deviator is plastic.
    const T apex = apex_pressure();
    stress = Vec4(apex, apex, apex, 0);
    state.plastic_shear_strain += static_cast<double>(q_trial / shear);
    if constexpr (WithTangent) tangent->setZero();
  }

  detail::IsotropicElasticity<T> elastic_;
  DruckerPragerCoefficients<T> coefficients_;
  DruckerPragerMatching matching_;
};

static_assert(ConstitutiveModel<DruckerPrager<double>>);
static_assert(HasConsistentTangent<DruckerPrager<double>>);

}  // namespace cosmpm::material
