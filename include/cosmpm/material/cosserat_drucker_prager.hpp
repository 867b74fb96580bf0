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
// (p = c cot(phi), s = 0, m = 0) takes the trial states the cone cannot. The formulas are in
// detail/cosserat_cone.hpp; update_batch runs them over arrays of points, several at a time in
// SIMD lanes (detail/cosserat_batch.hpp).
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/cosserat_batch.hpp"
#include "cosmpm/material/detail/cosserat_cone.hpp"
#include "cosmpm/material/detail/cosserat_elasticity.hpp"
#include "cosmpm/material/detail/lanes.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"
#include "cosmpm/material/drucker_prager_matching.hpp"

namespace cosmpm::material {

// Coefficients of the Cosserat invariant q; the defaults are Muhlhaus and Vardoulakis' values
// used by Tejchman (1997) and the paper.
template <class T = double>
struct CosseratInvariantCoefficients {
  T a1 = T(0.375);
  T a2 = T(0.125);
  T a3 = T(1);
};

// Parameters by name, e.g. CosseratDruckerPrager({.youngs_modulus = 2.76e6, .poisson_ratio =
// 0.2, .cosserat_shear_modulus = 2.3e6, .characteristic_length = 0.01, .friction_angle_deg = 26,
// .dilatancy_angle_deg = 2}).
struct CosseratDruckerPragerParameters {
  double youngs_modulus = detail::unset;          // E (Pa), > 0
  double poisson_ratio = detail::unset;           // nu, -1 < nu < 0.5
  double cosserat_shear_modulus = detail::unset;  // Gc (Pa), >= 0
  double characteristic_length = detail::unset;   // l (m), > 0
  double friction_angle_deg = detail::unset;      // phi, 0 < phi < 90
  double dilatancy_angle_deg = detail::unset;     // psi, 0 <= psi <= phi
  double cohesion = 0.0;                          // c (Pa), >= 0
  // a1 + a2 > 0, a1 >= a2, a3 >= 0 keep q a (semi-)norm.
  CosseratInvariantCoefficients<double> invariant = {};
  DruckerPragerMatching matching = DruckerPragerMatching::plane_strain_per_angle;
};

template <class T = double>
class CosseratDruckerPrager {
 public:
  using scalar_type = T;
  using stress_type = CosseratTensor2D<T>;  // [s_xx, s_yy, s_zz, s_xy, s_yx, m_31, m_32]
  using strain_type = CosseratTensor2D<T>;  // [e_xx, e_yy, e_zz, e_xy, e_yx, k_31, k_32]
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, 7, 7>;
  using parameters_type = CosseratDruckerPragerParameters;
  static constexpr bool is_cosserat = true;
  static constexpr int dimension = 2;  // plane strain only (issue 18 leaves 3D Cosserat out)
  // update_batch merges the modes of equal rate (detail/cosserat_batch.hpp), which changes the
  // rounding of the multiplier's solve: its results differ from update()'s by at most this,
  // relative (HasBatchUpdate). Measured: at most 3.4e-14 over 1.0e6 states (half of them
  // plastic) of eight parameter sets with one, two and three distinct rates; the bound leaves
  // room for compilers that contract into FMA differently in the two paths.
  static constexpr double batch_rounding = 1e-12;

  explicit CosseratDruckerPrager(const CosseratDruckerPragerParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_("CosseratDruckerPrager", T(parameters.youngs_modulus), T(parameters.poisson_ratio),
                 T(parameters.cosserat_shear_modulus), T(parameters.characteristic_length)),
        coefficients_(drucker_prager_coefficients<T>(
            T(parameters.friction_angle_deg), T(parameters.dilatancy_angle_deg),
            T(parameters.cohesion), parameters.matching, "CosseratDruckerPrager")),
        invariant_{T(parameters.invariant.a1), T(parameters.invariant.a2),
                   T(parameters.invariant.a3)} {
    require_positive("CosseratDruckerPrager", "a1 + a2",
                     static_cast<double>(invariant_.a1 + invariant_.a2));
    require_non_negative("CosseratDruckerPrager", "a1 - a2",
                         static_cast<double>(invariant_.a1 - invariant_.a2));
    require_non_negative("CosseratDruckerPrager", "a3", static_cast<double>(invariant_.a3));
    cone_ = detail::CosseratCone<T>(elastic_, coefficients_, invariant_.a1, invariant_.a2,
                                    invariant_.a3);
    moduli_ = elastic_.moduli();
  }
  // Positional, for compatibility: prefer the parameters by name (phi and psi cannot swap).
  CosseratDruckerPrager(
      T youngs_modulus, T poisson_ratio, T cosserat_shear_modulus, T characteristic_length,
      T friction_angle_deg, T dilatancy_angle_deg, T cohesion = T(0),
      CosseratInvariantCoefficients<T> invariant = {},
      DruckerPragerMatching matching = DruckerPragerMatching::plane_strain_per_angle)
      : CosseratDruckerPrager(CosseratDruckerPragerParameters{
            static_cast<double>(youngs_modulus),
            static_cast<double>(poisson_ratio),
            static_cast<double>(cosserat_shear_modulus),
            static_cast<double>(characteristic_length),
            static_cast<double>(friction_angle_deg),
            static_cast<double>(dilatancy_angle_deg),
            static_cast<double>(cohesion),
            {static_cast<double>(invariant.a1), static_cast<double>(invariant.a2),
             static_cast<double>(invariant.a3)},
            matching}) {}

  const CosseratDruckerPragerParameters& parameters() const { return parameters_; }
  T shear_modulus() const { return elastic_.iso.shear; }
  T cosserat_shear_modulus() const { return elastic_.cosserat_shear; }
  T characteristic_length() const { return elastic_.length; }
  T lame_lambda() const { return elastic_.iso.lambda; }
  T bulk_modulus() const { return elastic_.iso.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave_modulus(); }
  T bending_modulus() const { return elastic_.bending_modulus(); }
  const DruckerPragerCoefficients<T>& coefficients() const { return coefficients_; }
  const CosseratInvariantCoefficients<T>& invariant_coefficients() const { return invariant_; }
  DruckerPragerMatching matching() const { return parameters_.matching; }
  T apex_pressure() const { return coefficients_.k / coefficients_.alpha; }
  tangent_type elastic_tangent() const { return elastic_.tangent(); }

  // The generalised invariant q of a stress.
  T invariant_q(const stress_type& stress) const {
    return std::sqrt(Cone::split_trial(as_array(stress), cone_.weights()).w_sum);
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

  // The batched hook (HasBatchUpdate): update(stress[i], state[i], increment[i]) for every i,
  // within batch_rounding, several plastic points at a time in SIMD lanes
  // (docs/theory/materials.md, "Batched return"). Allocation-free. The three spans must have
  // the same size and must not overlap.
  void update_batch(std::span<stress_type> stress, std::span<state_type> state,
                    std::span<const strain_type> increment) const {
    require_equal_batch_sizes("CosseratDruckerPrager::update_batch", stress.size(), state.size(),
                              increment.size());
    if constexpr (detail::has_lanes) {
      detail::CosseratBatch<T>::run(
          cone_, moduli_, stress.data(), state.data(), increment.data(), stress.size(),
          [this](stress_type& s, state_type& st) { plastic_return_of_trial(s, st); });
    } else {
      for (std::size_t i = 0; i < stress.size(); ++i) update(stress[i], state[i], increment[i]);
    }
  }

  // The hook on packs (HasPacksUpdate): update_batch for points whose stresses and increments
  // come by component in packs of the register width, point l of pack k with state[k W + l];
  // the same values (detail::CosseratBatch::run_packs). The engine's stage 4b calls it with the
  // packs of its rotation, which saves update_batch's loads and stores lane by lane.
  template <int W>
  void update_packs(std::span<std::array<detail::Lanes<T, W>, 7>> stress,
                    std::span<const std::array<detail::Lanes<T, W>, 7>> increment,
                    state_type* state) const
      requires(W == detail::CosseratBatch<T>::batch_lanes && detail::has_lanes) {
    require_equal_pack_counts("CosseratDruckerPrager::update_packs", stress.size(),
                              increment.size());
    detail::CosseratBatch<T>::run_packs(
        cone_, moduli_, stress.data(), increment.data(), stress.size(), state,
        [this](stress_type& s, state_type& st) { plastic_return_of_trial(s, st); });
  }

 private:
  using Cone = detail::CosseratCone<T>;

  static std::array<T, 7> as_array(const stress_type& s) {
    return {s[0], s[1], s[2], s[3], s[4], s[5], s[6]};
  }

  static const CosseratDruckerPragerParameters& checked(const CosseratDruckerPragerParameters& p) {
    detail::require_set("CosseratDruckerPrager", "CosseratDruckerPragerParameters",
                        {{"youngs_modulus", p.youngs_modulus},
                         {"poisson_ratio", p.poisson_ratio},
                         {"cosserat_shear_modulus", p.cosserat_shear_modulus},
                         {"characteristic_length", p.characteristic_length},
                         {"friction_angle_deg", p.friction_angle_deg},
                         {"dilatancy_angle_deg", p.dilatancy_angle_deg}});
    return p;
  }

  // The one stress update (with or without the tangent); update_batch runs its formulas on
  // lanes.
  template <bool WithTangent>
  void update_impl(stress_type& stress, state_type& state, const strain_type& de,
                   tangent_type* tangent) const {
    // The trial stress in scalars, every load before the first store (see isotropic_trial).
    const std::array<T, 7> t = detail::cosserat_trial(stress, de, moduli_);
    const auto split = Cone::split_trial(t, cone_.weights());
    // f_trial = q_trial - q0 <= 0, decided without the square root so the branch resolves early.
    if (Cone::is_elastic(split)) {
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
    if (q0 <= T(0) && cone_.is_apex(weight, q0)) {
      const T apex = apex_pressure();
      state.plastic_shear_strain += static_cast<double>(cone_.apex_strain(weight));
      stress << apex, apex, apex, 0, 0, 0, 0;
      if constexpr (WithTangent) tangent->setZero();
      return;
    }
    const T multiplier = cone_.solve_multiplier(weight, w_sum, q_trial, q0);
    const std::array<T, 7> s = Cone::scaled_stress(as_array(stress), p_trial,
                                                   cone_.return_scales(p_trial, q0, multiplier));
    stress << s[0], s[1], s[2], s[3], s[4], s[5], s[6];
    // The multiplier is the plastic strain conjugate to q: the engineering plastic shear strain
    // sqrt(2 e:e) in the symmetric case.
    state.plastic_shear_strain += static_cast<double>(multiplier);
    if constexpr (WithTangent)
      *tangent = consistent_tangent(stress, q0 + cone_.slope() * multiplier, multiplier);
  }

  // plastic_return for a point whose stress holds its plastic trial (update_batch's fallback).
  void plastic_return_of_trial(stress_type& stress, state_type& state) const {
    const auto split = Cone::split_trial(as_array(stress), cone_.weights());
    plastic_return<false>(stress, state, nullptr, split.p, split.w0, split.w1, split.w2,
                          split.w_sum, split.q0);
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

  CosseratDruckerPragerParameters parameters_;
  detail::CosseratElasticity<T> elastic_;
  DruckerPragerCoefficients<T> coefficients_;
  CosseratInvariantCoefficients<T> invariant_;
  Cone cone_;
  detail::CosseratModuli<T> moduli_{};  // as cosserat_trial uses them
};

static_assert(ConstitutiveModel<CosseratDruckerPrager<double>>);
static_assert(HasConsistentTangent<CosseratDruckerPrager<double>>);
static_assert(HasBatchUpdate<CosseratDruckerPrager<double>>);
static_assert(
    !detail::has_lanes ||
    HasPacksUpdate<CosseratDruckerPrager<double>, detail::CosseratBatch<double>::batch_lanes>);

}  // namespace cosmpm::material
