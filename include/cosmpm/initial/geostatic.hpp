#pragma once
// Geostatic (at-rest) initial stress of a horizontal soil layer, tension positive, y up:
//   sigma_yy = -rho g depth,  sigma_xx = sigma_zz = K0 sigma_yy,  no shear,
// with Jaky's K0 = 1 - sin(phi) by default (the paper initialises its layer this way).
#include <cmath>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::initial {

// Jaky's coefficient of earth pressure at rest, K0 = 1 - sin(phi); phi in degrees, (0, 90).
inline double jaky_k0(double friction_angle_deg) {
  require_in_range("jaky_k0", "friction_angle_deg", friction_angle_deg, 0.0, 90.0);
  return 1.0 - std::sin(degrees_to_radians(friction_angle_deg));
}

// Stress at `depth` (m, >= 0) below the free surface: density (kg/m^3, > 0), gravity (m/s^2,
// the magnitude, > 0), k0 (>= 0).
template <class T = double>
SymTensor2D<T> geostatic_stress(T density, T gravity, T depth, T k0) {
  require_positive("geostatic_stress", "density", static_cast<double>(density));
  require_positive("geostatic_stress", "gravity", static_cast<double>(gravity));
  require_non_negative("geostatic_stress", "depth", static_cast<double>(depth));
  require_non_negative("geostatic_stress", "k0", static_cast<double>(k0));
  const T vertical = -density * gravity * depth;
  return SymTensor2D<T>(k0 * vertical, vertical, k0 * vertical, T(0));
}

// The Cosserat variant: the same force stresses (s_xy = s_yx = 0) and no couple stresses, which
// is an equilibrium state of the layer since nothing varies horizontally.
template <class T = double>
CosseratTensor2D<T> geostatic_cosserat_stress(T density, T gravity, T depth, T k0) {
  const SymTensor2D<T> s = geostatic_stress<T>(density, gravity, depth, k0);
  CosseratTensor2D<T> out;
  out << s[0], s[1], s[2], 0, 0, 0, 0;
  return out;
}

}  // namespace cosmpm::initial
