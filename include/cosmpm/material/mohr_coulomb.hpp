#pragma once
// Perfectly plastic Mohr-Coulomb in plane strain with sigma_zz carried, non-associated flow and a
// tension cut-off. The return is exact (no iteration, no drift): it is done in principal-stress
// space (detail/mohr_coulomb_return.hpp, after Clausen, Damkilde and Andersen 2006, 2007), and
// the stress is rotated back with the trial eigenvectors. See docs/theory/materials.md.
//
// Tension positive. Principal stresses sorted s1 >= s2 >= s3 (s3 the most compressive):
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi)        (yield_function, Pa)
//   g = m s1 - s3,  m = (1 + sin psi) / (1 - sin psi)
// sigma_zz is principal in plane strain, so the split is the closed-form in-plane 2x2 problem.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/mohr_coulomb_return.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"
#include "cosmpm/material/detail/principal_2d.hpp"

namespace cosmpm::material {

// Parameters by name, e.g. MohrCoulomb({.youngs_modulus = 2.76e6, .poisson_ratio = 0.2,
// .friction_angle_deg = 26, .dilatancy_angle_deg = 2}). Angles in degrees.
struct MohrCoulombParameters {
  double youngs_modulus = detail::unset;       // E (Pa), > 0
  double poisson_ratio = detail::unset;        // nu, -1 < nu < 0.5
  double friction_angle_deg = detail::unset;   // phi, 0 < phi < 90
  double dilatancy_angle_deg = detail::unset;  // psi, 0 <= psi <= phi
  double cohesion = 0.0;                       // c (Pa), >= 0
  // The largest principal stress allowed (Pa), in [0, c cot(phi)]; none: the apex c cot(phi).
  std::optional<double> tension_cutoff = std::nullopt;
};

template <class T = double>
class MohrCoulomb {
 public:
  using scalar_type = T;
  using stress_type = SymTensor2D<T>;  // [xx, yy, zz, xy], tension positive
  using strain_type = SymTensor2D<T>;  // [dxx, dyy, dzz, dxy], tensor shear
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, 4, 4>;
  using parameters_type = MohrCoulombParameters;
  static constexpr bool is_cosserat = false;

  explicit MohrCoulomb(const MohrCoulombParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_(detail::isotropic_elasticity<T>("MohrCoulomb", T(parameters.youngs_modulus),
                                                 T(parameters.poisson_ratio))) {
    const T phi = T(parameters.friction_angle_deg), psi = T(parameters.dilatancy_angle_deg);
    const T cohesion = T(parameters.cohesion);
    detail::check_friction_angles("MohrCoulomb", static_cast<double>(phi),
                                  static_cast<double>(psi));
    require_non_negative("MohrCoulomb", "cohesion", static_cast<double>(cohesion));
    const T sin_phi = std::sin(T(degrees_to_radians(static_cast<double>(phi))));
    const T sin_psi = std::sin(T(degrees_to_radians(static_cast<double>(psi))));
    sin_phi_ = sin_phi;
    cos_phi_ = std::sqrt(1 - sin_phi * sin_phi);
    const T k = (1 + sin_phi) / (1 - sin_phi);
    const T m = (1 + sin_psi) / (1 - sin_psi);
    const T apex = cohesion * cos_phi_ / sin_phi;
    T cutoff = apex;
    if (parameters.tension_cutoff) {
      require_in_range("MohrCoulomb", "tension_cutoff",
                       static_cast<double>(T(*parameters.tension_cutoff)), 0.0,
                       static_cast<double>(apex), Bounds::closed);
      cutoff = T(*parameters.tension_cutoff);
    }
    return_ =
        detail::MohrCoulombReturn<T>(elastic_, k, m, 2 * cohesion * std::sqrt(k), apex, cutoff);
  }
  // Positional, for compatibility: prefer the parameters by name (phi and psi cannot swap).
  MohrCoulomb(T youngs_modulus, T poisson_ratio, T friction_angle_deg, T dilatancy_angle_deg,
              T cohesion = T(0), std::optional<T> tension_cutoff = std::nullopt)
      : MohrCoulomb(MohrCoulombParameters{
            static_cast<double>(youngs_modulus), static_cast<double>(poisson_ratio),
            static_cast<double>(friction_angle_deg), static_cast<double>(dilatancy_angle_deg),
            static_cast<double>(cohesion),
            tension_cutoff ? std::optional<double>(static_cast<double>(*tension_cutoff))
                           : std::nullopt}) {}

  const MohrCoulombParameters& parameters() const { return parameters_; }
  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }
  T friction_angle_deg() const { return T(parameters_.friction_angle_deg); }
  T dilatancy_angle_deg() const { return T(parameters_.dilatancy_angle_deg); }
  T cohesion() const { return T(parameters_.cohesion); }
  T apex_stress() const { return return_.apex(); }       // c cot(phi): all principal stresses
  T tension_cutoff() const { return return_.cutoff(); }  // largest principal stress allowed

  // f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) in Pa; <= 0 inside. With a tension
  // cut-off below the apex, the larger of f and s1 - cut-off.
  T yield_function(const stress_type& stress) const {
    const auto spectrum = detail::plane_strain_spectrum(stress[0], stress[1], stress[2], stress[3]);
    const auto sorted = spectrum.sorted();
    const T f =
        (sorted[0] - sorted[2]) + (sorted[0] + sorted[2]) * sin_phi_ - 2 * cohesion() * cos_phi_;
    return return_.has_cutoff() ? std::max(f, sorted[0] - return_.cutoff()) : f;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    (void)update_impl<false>(stress, state, de, nullptr);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    (void)update_impl<true>(stress, state, de, &tangent);
  }
  // The same update, reporting which return region it used (tests, diagnostics).
  MohrCoulombRegion update_region(stress_type& stress, state_type& state,
                                  const strain_type& de) const {
    return update_impl<false>(stress, state, de, nullptr);
  }

  tangent_type elastic_tangent() const { return elastic_.template tangent<4>(); }

  // The principal-space return on its own: `trial` sorted descending, result sorted likewise.
  // `map` (optional) receives d result / d trial. Exposed for tests.
  MohrCoulombRegion principal_return(const Eigen::Matrix<T, 3, 1>& trial,
                                     Eigen::Matrix<T, 3, 1>& result,
                                     Eigen::Matrix<T, 3, 3>* map = nullptr) const {
    const T f = return_.yield(trial[0], trial[2]);
    if (return_.is_elastic(trial[0], f)) {
      result = trial;
      if (map) map->setIdentity();
      return MohrCoulombRegion::elastic;
    }
    if (return_.has_cutoff())
      return map ? sorted_return<true, true>(trial, f, result, map)
                 : sorted_return<false, true>(trial, f, result, nullptr);
    return map ? sorted_return<true, false>(trial, f, result, map)
               : sorted_return<false, false>(trial, f, result, nullptr);
  }

 private:
  using Mat3 = Eigen::Matrix<T, 3, 3>;

  template <bool WithMap, bool Cutoff>
  MohrCoulombRegion sorted_return(const Eigen::Matrix<T, 3, 1>& trial, T f,
                                  Eigen::Matrix<T, 3, 1>& result, Mat3* map) const {
    T gamma;
    return return_.template plastic_return<WithMap, Cutoff>(
        trial[0], trial[1], trial[2], f, result[0], result[1], result[2], gamma, map);
  }

  static const MohrCoulombParameters& checked(const MohrCoulombParameters& p) {
    detail::require_set("MohrCoulomb", "MohrCoulombParameters",
                        {{"youngs_modulus", p.youngs_modulus},
                         {"poisson_ratio", p.poisson_ratio},
                         {"friction_angle_deg", p.friction_angle_deg},
                         {"dilatancy_angle_deg", p.dilatancy_angle_deg}});
    return p;
  }

  // The one stress update: trial, closed-form split, principal return, rotation back, and
  // (WithTangent) the consistent tangent. With a cut-off below the apex the same code runs
  // out of line (Cutoff = true), so that the common case holds no call.
  template <bool WithTangent, bool Cutoff = false>
  MohrCoulombRegion update_impl(stress_type& stress, state_type& state, const strain_type& de,
                                tangent_type* tangent) const {
    const auto t = elastic_.template trial<4>(stress, de);
    const T xx = t[0], yy = t[1], zz = t[2], xy = t[3];
    const T mean = (xx + yy) / 2;
    const T half = (xx - yy) / 2;
    const T radius = std::sqrt(half * half + xy * xy);
    const T a = mean + radius;
    const T b = mean - radius;
    const T s1 = std::max(a, zz);
    const T s2 = std::min(std::max(zz, b), a);
    const T s3 = std::min(b, zz);
    const T f = return_.yield(s1, s3);
    if (return_.is_elastic(s1, f)) {
      stress = stress_type(xx, yy, zz, xy);
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_tangent();
      return MohrCoulombRegion::elastic;
    }
    if constexpr (!Cutoff) {
      if (return_.has_cutoff()) [[unlikely]]
        return update_with_cutoff<WithTangent>(stress, state, de, tangent);
    }
    T r1, r2, r3, gamma;
    Mat3 sorted_map;
    const MohrCoulombRegion region = return_.template plastic_return<WithTangent, Cutoff>(
        s1, s2, s3, f, r1, r2, r3, gamma, WithTangent ? &sorted_map : nullptr);
    // Back to (a, b, zz) by the rank sigma_zz had (sorted[i] = natural[order[i]]), then rotate
    // with the trial directions.
    T na, nb, nz;
    int zz_rank;
    if (zz >= a) {
      nz = r1, na = r2, nb = r3, zz_rank = 0;
    } else if (zz >= b) {
      na = r1, nz = r2, nb = r3, zz_rank = 1;
    } else {
      na = r1, nb = r2, nz = r3, zz_rank = 2;
    }
    const T ratio = radius > T(0) ? (na - nb) / (2 * radius) : T(0);
    const T new_mean = (na + nb) / 2;
    stress = stress_type(new_mean + half * ratio, new_mean - half * ratio, nz, xy * ratio);
    state.plastic_shear_strain += static_cast<double>(gamma);
    state.plastic = 1.0;
    if constexpr (WithTangent) {
      static constexpr int orders[3][3] = {{2, 0, 1}, {0, 2, 1}, {0, 1, 2}};
      const int* order = orders[zz_rank];
      Mat3 natural_map;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) natural_map(order[i], order[j]) = sorted_map(i, j);
      Mat3 elastic_principal = Mat3::Constant(elastic_.lambda);
      elastic_principal.diagonal().array() += 2 * elastic_.shear;
      // Equal in-plane trial eigenvalues: the ratio's limit is the map's derivative along a - b.
      const T shear_ratio =
          2 * radius > T(1e-12) * std::max(std::abs(a), T(1))
              ? ratio
              : (natural_map(0, 0) - natural_map(0, 1) - natural_map(1, 0) + natural_map(1, 1)) / 2;
      const T cos_2theta = radius > T(0) ? half / radius : T(1);
      const T sin_2theta = radius > T(0) ? xy / radius : T(0);
      *tangent = detail::spectral_tangent<T>(natural_map * elastic_principal, elastic_.shear,
                                             shear_ratio, cos_2theta, sin_2theta);
    }
    return region;
  }

  template <bool WithTangent>
  [[gnu::noinline]] MohrCoulombRegion update_with_cutoff(stress_type& stress, state_type& state,
                                                         const strain_type& de,
                                                         tangent_type* tangent) const {
    return update_impl<WithTangent, true>(stress, state, de, tangent);
  }

  MohrCoulombParameters parameters_;
  detail::IsotropicElasticity<T> elastic_;
  T sin_phi_{};
  T cos_phi_{};
  detail::MohrCoulombReturn<T> return_;
};

static_assert(ConstitutiveModel<MohrCoulomb<double>>);
static_assert(HasConsistentTangent<MohrCoulomb<double>>);

}  // namespace cosmpm::material
