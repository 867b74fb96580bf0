#pragma once
// Sokolovski's method of characteristics for the plane-strain passive (and active) earth
// pressure on a vertical wall of height h with wall friction delta, a level backfill of unit
// weight gamma, a surcharge q on the surface and cohesion c. The reference the paper checks its
// blade forces, blade stresses and slip line against; docs/theory/earth_pressure.md gives the
// equations as implemented here.
//
// Geometry: x is the horizontal distance from the wall into the soil, z the depth below the
// level surface (both in m). Angles in the API are in DEGREES.
//
// Sign conventions of the results (the library itself is tension positive; these are the
// usual earth-pressure quantities at the output edge and their names say so):
//  - WallStress::normal_pressure: normal stress the soil exerts on the wall, COMPRESSION
//    POSITIVE (Pa);
//  - WallStress::shear_stress: shear stress the soil exerts on the wall, UPWARD POSITIVE (Pa):
//    positive in the passive case (the heaving soil drags the wall up), negative when active;
//  - horizontal_force_per_width / vertical_force_per_width: force the WALL APPLIES TO THE SOIL
//    per unit width (N/m), horizontal positive into the soil, vertical positive UPWARD. Passive:
//    the draft force is positive and the vertical force negative (the soil pushes the wall up,
//    so the wall pushes the soil down).
//
// Cohesion enters by the theorem of corresponding states: the shifted stress sigma + c cot phi
// is cohesionless, the surface carries q + c cot phi, and the wall adhesion is
// a = c tan(delta) / tan(phi) (so that tau = (sigma_n + c cot phi) tan delta). No tension
// cut-off is applied: an active case with cohesion reports negative normal pressure near the
// top (tension), as the theory gives it.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "cosmpm/analysis/detail/characteristics_net.hpp"
#include "cosmpm/analysis/earth_pressure.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::analysis {

// The problem. The fields without a usable default are NaN so that forgetting them fails
// loudly instead of computing a weightless or zero-height case.
struct EarthPressureProblem {
  double friction_angle_deg = std::numeric_limits<double>::quiet_NaN();  // phi, (0, 60] deg
  double wall_friction_deg = 0;  // delta, [0, phi] deg; 0 is a smooth wall
  double unit_weight = std::numeric_limits<double>::quiet_NaN();  // gamma, N/m^3, >= 0
  double height = std::numeric_limits<double>::quiet_NaN();       // h, wall height in soil, m
  double surcharge = 0;  // q, uniform normal load on the backfill surface, Pa, >= 0
  double cohesion = 0;   // c, Pa, >= 0
};

// The net's resolution, CharacteristicsResolution, is in analysis/detail/characteristics_net.hpp.

struct WallStress {
  double depth;            // m below the surface
  double normal_pressure;  // Pa, soil on wall, compression positive
  double shear_stress;     // Pa, soil on wall, upward positive
};

struct SlipLinePoint {
  double distance;  // m from the wall into the soil
  double depth;     // m below the surface
};

struct EarthPressureSolution {
  EarthPressureCase kind{};
  // Normal-component coefficient of the gamma term: normal_pressure = K gamma z when there is
  // no surcharge and no cohesion (always computed on such a net, whatever q and c are). K_p when
  // passive, K_a when active. Divide by cos(delta) for the coefficient of the inclined resultant
  // tabulated by Caquot-Kerisel and Kerisel-Absi.
  double k_gamma{};
  double horizontal_force_per_width{};   // N/m, wall on soil, positive into the soil
  double vertical_force_per_width{};     // N/m, wall on soil, positive upward
  double resultant_depth{};              // m, depth where the horizontal resultant acts
  double fan_angle_deg{};                // rotation of the principal axes across the fan
  double slip_exit_distance{};           // m, where the slip line reaches the surface
  std::vector<WallStress> wall;          // from the top of the wall (depth 0) to its tip
  std::vector<SlipLinePoint> slip_line;  // from the wall tip (0, h) to the surface
};

namespace detail {

struct WallIntegrals {
  double normal_force, shear_force, normal_moment;  // per unit width, about the surface
};

// Trapezoidal integration over the wall nodes (exact for the linear gamma-only profile).
inline WallIntegrals integrate_wall(const std::vector<WallStress>& wall) {
  WallIntegrals sum{0, 0, 0};
  for (std::size_t i = 1; i < wall.size(); ++i) {
    const double dz = wall[i].depth - wall[i - 1].depth;
    sum.normal_force += 0.5 * dz * (wall[i].normal_pressure + wall[i - 1].normal_pressure);
    sum.shear_force += 0.5 * dz * (wall[i].shear_stress + wall[i - 1].shear_stress);
    sum.normal_moment +=
        0.5 * dz *
        (wall[i].normal_pressure * wall[i].depth + wall[i - 1].normal_pressure * wall[i - 1].depth);
  }
  return sum;
}

inline std::vector<WallStress> wall_stresses(const NetResult& net, const NetSetup& setup,
                                             double cohesion_shift) {
  const double s = setup.sin_phi, theta = setup.theta_wall;
  std::vector<WallStress> wall;
  wall.reserve(net.wall.size());
  for (const NetPoint& node : net.wall) {
    wall.push_back({node.z, node.p * (1 + s * std::cos(2 * theta)) - cohesion_shift,
                    node.p * s * std::sin(2 * theta)});
  }
  return wall;
}

}  // namespace detail

// Solves the passive or active problem. Throws cosmpm::Error naming the bad field and its
// valid range: phi in (0, 60] deg, delta in [0, phi], gamma >= 0, h > 0, q >= 0, c >= 0 (not
// all three of gamma, q, c zero), wall_lines in [2, 20000], fan_rays in [2, 20000].
inline EarthPressureSolution sokolovski(EarthPressureCase kind, const EarthPressureProblem& problem,
                                        const CharacteristicsResolution& resolution = {}) {
  const std::string_view where = kind == EarthPressureCase::passive ? "analysis::sokolovski_passive"
                                                                    : "analysis::sokolovski_active";
  detail::check_wall_friction(where, problem.friction_angle_deg, problem.wall_friction_deg);
  // Beyond 60 deg the passive net with wall friction spans tens of wall heights with p growing
  // like exp(2 theta tan phi); the marching scheme is not verified there (see the docs).
  require_in_range(where, "friction_angle_deg", problem.friction_angle_deg, 0.0, 60.0,
                   Bounds::right_closed);
  require_non_negative(where, "unit_weight", problem.unit_weight);
  require_positive(where, "height", problem.height);
  require_non_negative(where, "surcharge", problem.surcharge);
  require_non_negative(where, "cohesion", problem.cohesion);
  require_in_range(where, "resolution.wall_lines", resolution.wall_lines, 2, 20000, Bounds::closed);
  require_in_range(where, "resolution.fan_rays", resolution.fan_rays, 2, 20000, Bounds::closed);

  if (problem.unit_weight == 0 && problem.surcharge == 0 && problem.cohesion == 0) {
    // No stress anywhere: the principal directions, and so the net, are undefined.
    throw Error(std::string(where) +
                ": unit_weight, surcharge and cohesion are all 0; at least one must be positive");
  }
  const double phi = degrees_to_radians(problem.friction_angle_deg);
  const double delta = degrees_to_radians(problem.wall_friction_deg);
  const double cohesion_shift = problem.cohesion / std::tan(phi);
  const double surface_load = problem.surcharge + cohesion_shift;

  EarthPressureSolution solution;
  solution.kind = kind;

  // The gamma coefficient from a unit, weight-only net (self-similar: sigma_n = K gamma z).
  const auto k_gamma_of = [](const std::vector<WallStress>& wall, double gamma, double h) {
    return 2 * detail::integrate_wall(wall).normal_force / (gamma * h * h);
  };
  const bool weight_only = surface_load == 0 && problem.unit_weight > 0;
  if (!weight_only) {
    const detail::NetSetup unit = detail::make_net_setup(kind, phi, delta, 1.0, 0.0, resolution);
    const detail::NetResult unit_net = detail::solve_net(unit, 1.0);
    detail::check_net(where, unit_net);
    solution.k_gamma = k_gamma_of(detail::wall_stresses(unit_net, unit, 0.0), 1.0, 1.0);
  }

  const detail::NetSetup setup =
      detail::make_net_setup(kind, phi, delta, problem.unit_weight, surface_load, resolution);
  const detail::NetResult net = detail::solve_net(setup, problem.height);
  detail::check_net(where, net);
  solution.wall = detail::wall_stresses(net, setup, cohesion_shift);
  if (weight_only)
    solution.k_gamma = k_gamma_of(solution.wall, problem.unit_weight, problem.height);

  const detail::WallIntegrals integrals = detail::integrate_wall(solution.wall);
  solution.horizontal_force_per_width = integrals.normal_force;
  solution.vertical_force_per_width = -integrals.shear_force;
  solution.resultant_depth = integrals.normal_force != 0
                                 ? integrals.normal_moment / integrals.normal_force
                                 : std::numeric_limits<double>::quiet_NaN();
  solution.fan_angle_deg = radians_to_degrees(std::abs(setup.theta_wall - setup.theta_rankine));

  // Slip line: the deepest wall-bound characteristic from the tip back to the Rankine zone,
  // then straight (the Rankine state is uniform in direction) up to the surface.
  const std::vector<detail::NetPoint>& line = net.last_line;
  solution.slip_line.reserve(line.size() + 1);
  for (auto node = line.rbegin(); node != line.rend(); ++node) {
    solution.slip_line.push_back({node->x, node->z});
  }
  const detail::NetPoint& start = line.front();
  const double dir = setup.theta_rankine + setup.constants.eps_wall * setup.constants.mu;
  const double t = -start.z / std::sin(dir);
  solution.slip_exit_distance = start.x + t * std::cos(dir);
  solution.slip_line.push_back({solution.slip_exit_distance, 0.0});
  return solution;
}

// Passive earth pressure: the wall pushes into the soil (a blade's draft force), e.g.
//   sokolovski_passive({.friction_angle_deg = 26, .wall_friction_deg = 14,
//                       .unit_weight = 778 * 9.81, .height = 0.25}).horizontal_force_per_width
inline EarthPressureSolution sokolovski_passive(const EarthPressureProblem& problem,
                                                const CharacteristicsResolution& resolution = {}) {
  return sokolovski(EarthPressureCase::passive, problem, resolution);
}

// Active earth pressure: the wall yields away from the soil.
inline EarthPressureSolution sokolovski_active(const EarthPressureProblem& problem,
                                               const CharacteristicsResolution& resolution = {}) {
  return sokolovski(EarthPressureCase::active, problem, resolution);
}

}  // namespace cosmpm::analysis
