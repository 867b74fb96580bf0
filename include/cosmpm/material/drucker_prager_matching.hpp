#pragma once
// The Drucker-Prager cone fitted to Mohr-Coulomb: the matchings of alpha, beta and k to phi, psi
// and c, shared by DruckerPrager and CosseratDruckerPrager. Tension positive,
// p = tr(sigma) / 3, q = sqrt(J2):  f = q + alpha p - k,  g = q + beta p.
// k = alpha c cot(phi) for every matching, so the apex p = k / alpha = c cot(phi) coincides with
// the Mohr-Coulomb apex (docs/theory/materials.md derives the matchings).
#include <cmath>
#include <string_view>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"

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

}  // namespace cosmpm::material
