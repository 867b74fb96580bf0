#pragma once
// The net of characteristics of Sokolovski's method (analysis/sokolovski.hpp): its points, the
// march from the surface to the wall, and the checks of a finished net.
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

}  // namespace cosmpm::analysis

namespace cosmpm::analysis::detail {

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

}  // namespace cosmpm::analysis::detail
