#pragma once
// Closed-form earth-pressure coefficients for a vertical wall and a level backfill, plane
// strain: Rankine (smooth wall), Coulomb (planar wedge with wall friction) and the weightless
// log-spiral solution (Lancellotta 2002). They are the limits and bounds the method of
// characteristics in sokolovski.hpp is checked against; docs/theory/earth_pressure.md derives
// them.
//
// Conventions of the whole analysis/earth-pressure API:
//  - angles are given in DEGREES (every such parameter ends in _deg);
//  - every coefficient is the NORMAL (here horizontal) component: the normal wall pressure is
//    K * (vertical stress), compression positive. Tables that give the coefficient of the
//    inclined resultant (Caquot-Kerisel, Kerisel-Absi) list K / cos(delta).
//  - the backfill is cohesionless in these formulas; cohesion enters through the shift
//    H = c cot(phi) (theorem of corresponding states), see sokolovski.hpp.
#include <algorithm>
#include <cmath>
#include <string_view>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::analysis {

// Passive: the wall pushes into the soil, which heaves along the wall. Active: the wall
// yields away from the soil, which settles along the wall.
enum class EarthPressureCase { passive, active };

namespace detail {

inline void check_friction_angle(std::string_view where, double friction_angle_deg) {
  require_in_range(where, "friction_angle_deg", friction_angle_deg, 0.0, 90.0, Bounds::open);
}

inline void check_wall_friction(std::string_view where, double friction_angle_deg,
                                double wall_friction_deg) {
  check_friction_angle(where, friction_angle_deg);
  require_in_range(where, "wall_friction_deg", wall_friction_deg, 0.0, friction_angle_deg,
                   Bounds::closed);
}

// The major principal stress direction at a rough wall, measured from the horizontal axis
// pointing into the soil towards depth (radians): where tau/sigma_n = +-tan(delta) meets the
// yield condition. Passive: (delta + asin(sin delta / sin phi)) / 2, zero for a smooth wall.
// Active: pi/2 + (asin(sin delta / sin phi) - delta) / 2, pi/2 for a smooth wall.
inline double wall_stress_direction(EarthPressureCase kind, double phi, double delta) {
  const double ratio = std::min(1.0, std::sin(delta) / std::sin(phi));  // rounding at delta=phi
  const double omega = std::asin(ratio);
  return kind == EarthPressureCase::passive ? 0.5 * (delta + omega)
                                            : 0.5 * pi + 0.5 * (omega - delta);
}

}  // namespace detail

// Rankine passive coefficient tan^2(45 deg + phi/2) = (1 + sin phi) / (1 - sin phi): smooth
// wall, any of the gamma, surcharge (and, as 2 sqrt(Kp), cohesion) terms.
inline double rankine_kp(double friction_angle_deg) {
  detail::check_friction_angle("analysis::rankine_kp", friction_angle_deg);
  const double s = std::sin(degrees_to_radians(friction_angle_deg));
  return (1 + s) / (1 - s);
}

// Rankine active coefficient tan^2(45 deg - phi/2) = 1 / rankine_kp.
inline double rankine_ka(double friction_angle_deg) {
  detail::check_friction_angle("analysis::rankine_ka", friction_angle_deg);
  const double s = std::sin(degrees_to_radians(friction_angle_deg));
  return (1 - s) / (1 + s);
}

// Coulomb passive coefficient (normal component) of a planar wedge on a vertical wall with wall
// friction delta: cos^2 phi / (1 - sqrt(sin(phi + delta) sin(phi) / cos(delta)))^2. The wedge
// needs phi + delta < 90 deg; beyond that no plane fails and the coefficient is unbounded.
inline double coulomb_kp(double friction_angle_deg, double wall_friction_deg) {
  constexpr std::string_view where = "analysis::coulomb_kp";
  detail::check_wall_friction(where, friction_angle_deg, wall_friction_deg);
  require_in_range(where, "friction_angle_deg + wall_friction_deg",
                   friction_angle_deg + wall_friction_deg, 0.0, 90.0, Bounds::open);
  const double phi = degrees_to_radians(friction_angle_deg);
  const double delta = degrees_to_radians(wall_friction_deg);
  const double root = std::sqrt(std::sin(phi + delta) * std::sin(phi) / std::cos(delta));
  return std::cos(phi) * std::cos(phi) / ((1 - root) * (1 - root));
}

// Coulomb active coefficient (normal component):
// cos^2 phi / (1 + sqrt(sin(phi + delta) sin(phi) / cos(delta)))^2.
inline double coulomb_ka(double friction_angle_deg, double wall_friction_deg) {
  detail::check_wall_friction("analysis::coulomb_ka", friction_angle_deg, wall_friction_deg);
  const double phi = degrees_to_radians(friction_angle_deg);
  const double delta = degrees_to_radians(wall_friction_deg);
  const double root = std::sqrt(std::sin(phi + delta) * std::sin(phi) / std::cos(delta));
  return std::cos(phi) * std::cos(phi) / ((1 + root) * (1 + root));
}

// The critical Coulomb wedge found by searching over the plane inclination rho (from the
// horizontal) instead of the closed form: the normal force on a wall of height h is
// K(rho) gamma h^2 / 2 with K(rho) = cot(rho) / (cot(rho + phi) - tan(delta)) (passive,
// minimised) or cot(rho) / (cot(rho - phi) + tan(delta)) (active, maximised). It gives where the
// planar slip line reaches the surface, exit_distance = h cot(rho).
struct CoulombWedge {
  double k;                // normal-component coefficient (matches coulomb_kp / coulomb_ka)
  double plane_angle_deg;  // inclination of the critical plane from the horizontal
  double exit_distance_per_height;  // cot(rho): surface exit distance from the wall over h
};

inline CoulombWedge coulomb_wedge(EarthPressureCase kind, double friction_angle_deg,
                                  double wall_friction_deg) {
  constexpr std::string_view where = "analysis::coulomb_wedge";
  detail::check_wall_friction(where, friction_angle_deg, wall_friction_deg);
  const double phi = degrees_to_radians(friction_angle_deg);
  const double tan_delta = std::tan(degrees_to_radians(wall_friction_deg));
  const bool passive = kind == EarthPressureCase::passive;
  if (passive) {
    require_in_range(where, "friction_angle_deg + wall_friction_deg",
                     friction_angle_deg + wall_friction_deg, 0.0, 90.0, Bounds::open);
  }
  // Minimise +-K(rho) on the admissible interval: K is unimodal there, so golden section works.
  const double lo = passive ? 0.0 : phi;
  const double hi = passive ? 0.5 * pi - phi - degrees_to_radians(wall_friction_deg) : 0.5 * pi;
  const auto objective = [&](double rho) {
    return passive ? 1 / (std::tan(rho) * (1 / std::tan(rho + phi) - tan_delta))
                   : -1 / (std::tan(rho) * (1 / std::tan(rho - phi) + tan_delta));
  };
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  double a = lo, b = hi;
  double c = b - golden * (b - a), d = a + golden * (b - a);
  double fc = objective(c), fd = objective(d);
  for (int iteration = 0; iteration < 200 && b - a > 1e-15; ++iteration) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - golden * (b - a), fc = objective(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + golden * (b - a), fd = objective(d);
    }
  }
  const double rho = 0.5 * (a + b);
  const double k = passive ? objective(rho) : -objective(rho);
  return {k, radians_to_degrees(rho), 1 / std::tan(rho)};
}

// Weightless log-spiral (Prandtl fan) solution, normal component, for a surcharge q on the
// level surface: sigma_n = K q along the whole wall (Lancellotta 2002, Geotechnique 52(8)):
//   Kp = cos(delta) (cos(delta) + sqrt(sin^2 phi - sin^2 delta)) / (1 - sin phi) exp(2 t tan phi),
//   2 t = asin(sin delta / sin phi) + delta.
// The method of characteristics is exact for this problem (Rankine zone, fan, uniform zone).
inline double log_spiral_kp_weightless(double friction_angle_deg, double wall_friction_deg) {
  detail::check_wall_friction("analysis::log_spiral_kp_weightless", friction_angle_deg,
                              wall_friction_deg);
  const double phi = degrees_to_radians(friction_angle_deg);
  const double delta = degrees_to_radians(wall_friction_deg);
  const double s = std::sin(phi), sd = std::sin(delta), cd = std::cos(delta);
  const double fan = detail::wall_stress_direction(EarthPressureCase::passive, phi, delta);
  return cd * (cd + std::sqrt(std::max(0.0, s * s - sd * sd))) / (1 - s) *
         std::exp(2 * fan * std::tan(phi));
}

// Active counterpart (Lancellotta 2002):
//   Ka = cos(delta) (cos(delta) - sqrt(sin^2 phi - sin^2 delta)) / (1 + sin phi) exp(-2 t tan phi),
//   2 t = asin(sin delta / sin phi) - delta.
inline double log_spiral_ka_weightless(double friction_angle_deg, double wall_friction_deg) {
  detail::check_wall_friction("analysis::log_spiral_ka_weightless", friction_angle_deg,
                              wall_friction_deg);
  const double phi = degrees_to_radians(friction_angle_deg);
  const double delta = degrees_to_radians(wall_friction_deg);
  const double s = std::sin(phi), sd = std::sin(delta), cd = std::cos(delta);
  const double fan =
      detail::wall_stress_direction(EarthPressureCase::active, phi, delta) - 0.5 * pi;
  return cd * (cd - std::sqrt(std::max(0.0, s * s - sd * sd))) / (1 + s) *
         std::exp(-2 * fan * std::tan(phi));
}

}  // namespace cosmpm::analysis
