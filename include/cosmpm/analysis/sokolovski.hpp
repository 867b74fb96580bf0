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

// Resolution of the characteristics net. `wall_lines` characteristics run from the Rankine
// zone to the wall (the wall profile has wall_lines + 1 points, top included); the fan at the
// top of the wall has `fan_rays` + 1 rays (they matter only with a surcharge or cohesion).
// K_gamma converges at an observed order of about 2.6 (delta well below phi) to 1.2 (delta =
// phi, phi = 26 deg). The defaults keep its error below 0.1 % for phi <= 30 deg at any delta
// (1e-5 for the corn, 2.5e-4 at delta = phi) and for phi <= 45 deg with delta <= phi / 2, in
// about 10-20 ms; larger phi with delta near phi needs a finer net (docs/theory/earth_pressure.md
// has the error table).
struct CharacteristicsResolution {
  int wall_lines = 80;
  int fan_rays = 40;
};

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

// A node of the net: position, shifted mean stress p = (sigma_1 + sigma_3)/2 + c cot phi
// (compression positive) and the angle theta from the x axis to the major principal stress,
// towards z. The stresses are sigma_x = p (1 + sin phi cos 2 theta), sigma_z = p (1 - sin phi
// cos 2 theta), sigma_xz = p sin phi sin 2 theta (compression positive, z down).
struct NetPoint {
  double x, z, p, theta;
};

// Along the characteristic of direction theta + e mu (e = +-1, mu = pi/4 - phi/2):
//   dp + 2 e p tan(phi) dtheta = gamma (dz + e tan(phi) dx).
// The wall-bound family has e = eps_wall (-1 passive, +1 active), the fan family e = -eps_wall.
struct NetConstants {
  double tan_phi;
  double mu;
  double gamma;
  double eps_wall;
};

// The relations are integrated with the factor exp(2 e tan(phi) theta), which makes the
// p-theta coupling exact (the weightless fan is reproduced to rounding) and leaves only the
// weight term to the trapezoidal rule:
//   p_P = p_A u + gamma (1 + u) / 2 (dz + e tan(phi) dx),  u = exp(-2 e tan(phi) (theta_P -
//   theta_A)).
struct ReachedBy {
  double p;      // p at the new point along this characteristic
  double slope;  // d p / d theta_P at fixed geometry
};

inline ReachedBy reach(const NetPoint& from, double e, double theta, double x, double z,
                       const NetConstants& k) {
  const double u = std::exp(-2 * e * k.tan_phi * (theta - from.theta));
  const double weight = 0.5 * k.gamma * ((z - from.z) + e * k.tan_phi * (x - from.x));
  return {from.p * u + weight * (1 + u), -2 * e * k.tan_phi * u * (from.p + weight)};
}

// Where the wall-bound characteristic through `a` meets the fan-family characteristic through
// `b`: the directions are averaged over each segment (second order) and the point is found by
// fixed-point iteration on the geometry with a Newton step on theta.
inline NetPoint net_interior_point(const NetPoint& a, const NetPoint& b, const NetConstants& k) {
  const double ea = k.eps_wall, eb = -k.eps_wall;
  NetPoint out{0.5 * (a.x + b.x), 0.5 * (a.z + b.z), 0.5 * (a.p + b.p), 0.5 * (a.theta + b.theta)};
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double dir_a = 0.5 * (a.theta + out.theta) + ea * k.mu;
    const double dir_b = 0.5 * (b.theta + out.theta) + eb * k.mu;
    // a + t (cos dir_a, sin dir_a) = b + s (cos dir_b, sin dir_b); the directions differ by
    // about 2 mu = pi/2 - phi > 0, so the intersection is well conditioned.
    const double det = std::sin(dir_a - dir_b);
    const double t = (-(b.x - a.x) * std::sin(dir_b) + (b.z - a.z) * std::cos(dir_b)) / det;
    const double x = a.x + t * std::cos(dir_a);
    const double z = a.z + t * std::sin(dir_a);
    // One Newton step on theta per geometry update; the two converge together.
    const ReachedBy along_a = reach(a, ea, out.theta, x, z, k);
    const ReachedBy along_b = reach(b, eb, out.theta, x, z, k);
    const double theta = out.theta - (along_a.p - along_b.p) / (along_a.slope - along_b.slope);
    const double p = reach(a, ea, theta, x, z, k).p;
    const double change = std::abs(theta - out.theta) + std::abs(x - out.x) + std::abs(z - out.z) +
                          std::abs(p - out.p) / std::max(std::abs(p), 1e-300);
    out = {x, z, p, theta};
    if (change < 1e-14 * (1 + std::abs(x) + std::abs(z))) break;
  }
  return out;
}

// Where the wall-bound characteristic through `a` reaches the wall x = 0, on which the wall
// friction fixes theta = theta_wall: explicit.
inline NetPoint net_wall_point(const NetPoint& a, double theta_wall, const NetConstants& k) {
  const double dir = 0.5 * (a.theta + theta_wall) + k.eps_wall * k.mu;
  const double t = -a.x / std::cos(dir);
  const double z = a.z + t * std::sin(dir);
  return {0.0, z, reach(a, k.eps_wall, theta_wall, 0.0, z, k).p, theta_wall};
}

struct NetSetup {
  NetConstants constants;
  double sin_phi;
  double theta_rankine;  // 0 passive, pi/2 active
  double theta_wall;
  double surface_load;  // q + c cot(phi), the shifted vertical stress at the surface
  int wall_lines;
  int fan_rays;
};

struct NetResult {
  std::vector<NetPoint> wall;       // wall nodes, top (the fan centre) to the deepest
  std::vector<NetPoint> last_line;  // the deepest wall-bound characteristic, surface to wall
};

// Marches the net line by line: each wall-bound characteristic starts on the boundary of the
// Rankine zone (the fan-family line from the wall top, where the Rankine state is exact),
// crosses the fan's rays and then the fan-family lines leaving the wall points above it, and
// ends on the wall. `boundary_length` is the length of the Rankine boundary the net covers.
inline NetResult march_net(const NetSetup& setup, double boundary_length) {
  const NetConstants& k = setup.constants;
  const int n = setup.wall_lines, m = setup.fan_rays;
  const double s = setup.sin_phi;
  const double boundary_dir = setup.theta_rankine - k.eps_wall * k.mu;
  const double rankine_factor = 1 - s * std::cos(2 * setup.theta_rankine);  // sigma_z / p
  const double p_top = setup.surface_load / rankine_factor;

  // Line 0 is the fan centre: the top of the wall carries every theta of the fan, with p from
  // the weightless relation along the degenerate wall-bound characteristic.
  std::vector<NetPoint> previous(static_cast<std::size_t>(m + 1));
  for (int ray = 0; ray <= m; ++ray) {
    const double theta = setup.theta_rankine + (setup.theta_wall - setup.theta_rankine) * ray / m;
    const double p = p_top * std::exp(-2 * k.eps_wall * k.tan_phi * (theta - setup.theta_rankine));
    previous[static_cast<std::size_t>(ray)] = {0.0, 0.0, p, theta};
  }
  NetResult result;
  result.wall.reserve(static_cast<std::size_t>(n + 1));
  result.wall.push_back(previous.back());

  std::vector<NetPoint> line;
  for (int i = 1; i <= n; ++i) {
    const double along = boundary_length * i / n;
    const double x = along * std::cos(boundary_dir), z = along * std::sin(boundary_dir);
    line.clear();
    line.push_back(
        {x, z, (setup.surface_load + k.gamma * z) / rankine_factor, setup.theta_rankine});
    for (int ray = 1; ray <= m; ++ray) {
      line.push_back(net_interior_point(line.back(), previous[static_cast<std::size_t>(ray)], k));
    }
    // Zone next to the wall: cross the fan-family lines from the wall points 1 .. i-1. At
    // delta = phi this zone is infinitely thin (the last ray runs down the wall) but still
    // carries the jump of theta onto its wall value, so it is kept.
    for (int j = 1; j < i; ++j) {
      line.push_back(net_interior_point(line.back(), previous[static_cast<std::size_t>(m + j)], k));
    }
    line.push_back(net_wall_point(line.back(), setup.theta_wall, k));
    result.wall.push_back(line.back());
    std::swap(previous, line);
  }
  result.last_line = std::move(previous);
  return result;
}

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

// Finds the Rankine-boundary length whose deepest characteristic ends exactly at the wall tip
// (depth h) by the secant method. Without a surface load the net is self-similar and the
// first rescaling is exact.
inline NetResult solve_net(const NetSetup& setup, double height) {
  // Smooth wall: straight characteristics meet the Rankine boundary at depth h/2.
  double length_a = height / (2 * std::sin(setup.constants.mu));
  NetResult net = march_net(setup, length_a);
  double miss_a = net.wall.back().z - height;
  double length_b = length_a * height / net.wall.back().z;
  for (int iteration = 0; iteration < 60; ++iteration) {
    net = march_net(setup, length_b);
    const double miss_b = net.wall.back().z - height;
    if (std::abs(miss_b) <= 1e-13 * height || miss_b == miss_a) break;
    const double next = length_b - miss_b * (length_b - length_a) / (miss_b - miss_a);
    length_a = length_b, miss_a = miss_b;
    length_b = next;
  }
  require(std::abs(net.wall.back().z - height) <= 1e-9 * height,
          "analysis::sokolovski: the characteristics net did not close on the wall tip");
  return net;
}

// A net that folds over itself (wall nodes out of depth order) or loses its stresses cannot be
// refined into an answer; say so instead of returning it.
inline void check_net(std::string_view where, const NetResult& net) {
  for (std::size_t i = 1; i < net.wall.size(); ++i) {
    const NetPoint& node = net.wall[i];
    if (!(node.z > net.wall[i - 1].z) || !(node.p > 0) || !std::isfinite(node.p)) {
      throw Error(std::string(where) +
                  ": the characteristics net folded or lost its stresses at wall node " +
                  std::to_string(i) + " (depth " + cosmpm::detail::format_number(node.z) +
                  ", p = " + cosmpm::detail::format_number(node.p) +
                  "); phi and delta are outside what the net resolves");
    }
  }
}

inline NetSetup make_net_setup(EarthPressureCase kind, double phi, double delta, double gamma,
                               double surface_load, const CharacteristicsResolution& resolution) {
  NetSetup setup{};
  const bool passive = kind == EarthPressureCase::passive;
  setup.constants = {std::tan(phi), 0.25 * pi - 0.5 * phi, gamma, passive ? -1.0 : 1.0};
  setup.sin_phi = std::sin(phi);
  setup.theta_rankine = passive ? 0.0 : 0.5 * pi;
  setup.theta_wall = wall_stress_direction(kind, phi, delta);
  setup.surface_load = surface_load;
  setup.wall_lines = resolution.wall_lines;
  setup.fan_rays = resolution.fan_rays;
  return setup;
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
