#pragma once
// Validation and derived constants of isotropic elasticity shared by the material models.
#include <string_view>

#include "cosmpm/core/error.hpp"

namespace cosmpm::material::detail {

template <class T>
struct IsotropicElasticity {
  T shear{};   // G
  T lambda{};  // Lame's first parameter
  T bulk() const { return lambda + T(2) / 3 * shear; }
  T p_wave() const { return lambda + 2 * shear; }
};

// Checks E > 0 and -1 < nu < 0.5 (the range where the elastic energy is positive definite).
template <class T>
IsotropicElasticity<T> isotropic_elasticity(std::string_view where, T youngs_modulus,
                                            T poisson_ratio) {
  require_positive(where, "youngs_modulus", static_cast<double>(youngs_modulus));
  require_in_range(where, "poisson_ratio", static_cast<double>(poisson_ratio), -1.0, 0.5);
  IsotropicElasticity<T> elastic;
  elastic.shear = youngs_modulus / (2 * (1 + poisson_ratio));
  elastic.lambda = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  return elastic;
}

// Friction and dilatancy angles in degrees: 0 < phi < 90 and 0 <= psi <= phi.
inline void check_friction_angles(std::string_view where, double friction_angle_deg,
                                  double dilatancy_angle_deg) {
  require_in_range(where, "friction_angle_deg", friction_angle_deg, 0.0, 90.0, Bounds::open);
  require_in_range(where, "dilatancy_angle_deg", dilatancy_angle_deg, 0.0, friction_angle_deg,
                   Bounds::closed);
}

}  // namespace cosmpm::material::detail
