// Passive earth pressure on a vertical blade by Sokolovski's method of characteristics, beside
// the Rankine, Coulomb and weightless log-spiral closed forms. Defaults are the corn of
// Coetzee (2014): phi = 26 deg, delta = 14 deg, gamma = 778 x 9.81 N/m^3, blade depths
// h = 150, 250 and 350 mm, rig width 0.2 m. Writes the wall stresses and the slip line per depth
// as CSV; scripts/plot_earth_pressure.py turns them into a PNG.
//
//   example_02_earth_pressure [--phi DEG] [--delta DEG] [--gamma N/m^3] [--height M,M...]
//                             [--width M] [--surcharge PA] [--cohesion PA] [--active]
//                             [--wall-lines N] [--fan-rays N] [--out DIR] [--replace true]
//   example_02_earth_pressure --help
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "case.hpp"
#include "cosmpm/analysis.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/run_directory.hpp"

namespace {

namespace ca = cosmpm::analysis;
namespace io = cosmpm::io;
using earth_pressure::Case;

// Rankine slip line from the tip: straight at 45 -+ phi/2 to the horizontal.
double rankine_exit_factor(bool passive, double phi_deg) {
  return std::tan(cosmpm::degrees_to_radians(passive ? 45 + phi_deg / 2 : 45 - phi_deg / 2));
}

int run(const Case& c, const io::Options& options) {
  const ca::EarthPressureProblem pr{.friction_angle_deg = c.friction_angle_deg,
                                    .wall_friction_deg = c.wall_friction_deg,
                                    .unit_weight = c.unit_weight,
                                    .height = c.heights.front(),
                                    .surcharge = c.surcharge,
                                    .cohesion = c.cohesion};
  const ca::CharacteristicsResolution resolution{.wall_lines = c.wall_lines,
                                                 .fan_rays = c.fan_rays};
  const double phi = pr.friction_angle_deg, delta = pr.wall_friction_deg;
  const bool passive = !c.active;
  const char* k_name = passive ? "K_p" : "K_a";
  io::RunDirectory folder(
      c.out, c.replace ? io::RunDirectory::Mode::replace : io::RunDirectory::Mode::fresh,
      "example_02_earth_pressure", options.given("out") ? "--out" : "--out (default)");

  std::printf("%s earth pressure, Sokolovski's method of characteristics (net %d x %d)\n",
              passive ? "Passive" : "Active", resolution.wall_lines, resolution.fan_rays);
  std::printf(
      "phi = %g deg, delta = %g deg, gamma = %g N/m^3, q = %g Pa, c = %g Pa, width = %g m\n", phi,
      delta, pr.unit_weight, pr.surcharge, pr.cohesion, c.width);
  const double estimate = earth_pressure::estimated_seconds_per_depth(c);
  if (estimate > 10.0) {
    std::printf("a net of %d x %d takes about %.0f s per depth here (%zu depths)\n",
                resolution.wall_lines, resolution.fan_rays, estimate, c.heights.size());
  }
  const double rankine = passive ? ca::rankine_kp(phi) : ca::rankine_ka(phi);
  const double spiral =
      passive ? ca::log_spiral_kp_weightless(phi, delta) : ca::log_spiral_ka_weightless(phi, delta);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const bool coulomb_exists = !passive || phi + delta < 90;
  const ca::CoulombWedge coulomb = coulomb_exists
                                       ? ca::coulomb_wedge(passive ? ca::EarthPressureCase::passive
                                                                   : ca::EarthPressureCase::active,
                                                           phi, delta)
                                       : ca::CoulombWedge{nan, nan, nan};
  std::printf(
      "Coefficients (normal component; divide by cos(delta) = %.4f for the inclined resultant):\n",
      std::cos(cosmpm::degrees_to_radians(delta)));
  std::printf("  Rankine (smooth wall)         %s = %.4f\n", k_name, rankine);
  std::printf("  Coulomb (planar wedge)        %s = %.4f\n", k_name, coulomb.k);
  std::printf("  log-spiral, weightless (q)    %s = %.4f\n", k_name, spiral);

  std::printf("\n%8s %9s %12s %12s %11s %11s %9s %10s %10s\n", "h [mm]", k_name, "H/b [N/m]",
              "V/b [N/m]", "H [N]", "V [N]", "z_H [mm]", "exit [mm]", "Coul.[mm]");
  std::vector<std::vector<double>> summary;
  for (double height : c.heights) {
    ca::EarthPressureProblem problem = pr;
    problem.height = height;
    const ca::EarthPressureSolution s =
        ca::sokolovski(passive ? ca::EarthPressureCase::passive : ca::EarthPressureCase::active,
                       problem, resolution);
    std::printf("%8.1f %9.4f %12.2f %12.2f %11.3f %11.3f %9.1f %10.1f %10.1f\n", height * 1e3,
                s.k_gamma, s.horizontal_force_per_width, s.vertical_force_per_width,
                s.horizontal_force_per_width * c.width, s.vertical_force_per_width * c.width,
                s.resultant_depth * 1e3, s.slip_exit_distance * 1e3,
                coulomb.exit_distance_per_height * height * 1e3);
    std::fflush(stdout);  // a long net shows each depth as it is done
    summary.push_back({height, s.k_gamma, s.horizontal_force_per_width, s.vertical_force_per_width,
                       s.horizontal_force_per_width * c.width, s.vertical_force_per_width * c.width,
                       s.resultant_depth, s.slip_exit_distance,
                       height * rankine_exit_factor(passive, phi),
                       height * coulomb.exit_distance_per_height});

    // File tag: the depth in whole millimetres (std::format-free to dodge a GCC 12 -Wrestrict
    // false positive on "literal" + std::string).
    char tag[32];
    std::snprintf(tag, sizeof tag, "h%ld", std::lround(height * 1e3));
    std::vector<std::vector<double>> wall, slip;
    for (const auto& point : s.wall) {
      wall.push_back({point.depth, point.normal_pressure, point.shear_stress});
    }
    for (const auto& point : s.slip_line) slip.push_back({point.distance, point.depth});
    io::write_csv(
        folder.claim(std::string("wall_") + tag + ".csv"),
        {"depth_m", "normal_pressure_Pa_compression_positive", "shear_stress_Pa_on_wall_upward"},
        wall);
    io::write_csv(folder.claim(std::string("slip_line_") + tag + ".csv"),
                  {"distance_from_wall_m", "depth_m"}, slip);
  }
  io::write_csv(folder.claim("summary.csv"),
                {"height_m", "k_gamma", "horizontal_force_per_width_N_per_m",
                 "vertical_force_per_width_N_per_m", "horizontal_force_N", "vertical_force_N",
                 "resultant_depth_m", "slip_exit_m", "rankine_exit_m", "coulomb_exit_m"},
                summary);
  std::printf(
      "\nH, V: force the blade applies to the soil (H into the soil, V upward; V < 0 when "
      "passive:\n"
      "the soil pushes the blade up). b = unit width; H [N], V [N] for width %g m.\n"
      "z_H: depth of the horizontal resultant. exit: where the slip line from the blade tip\n"
      "reaches the surface (Sokolovski; Coulomb plane for comparison).\n"
      "CSV files written to %s\n"
      "Plot: /usr/bin/python3 scripts/plot_earth_pressure.py %s\n",
      c.width, folder.path().c_str(), folder.path().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Case c;
  io::Options options("example_02_earth_pressure",
                      "Passive (or active) earth pressure on a vertical blade by Sokolovski's "
                      "method of characteristics, beside Rankine, Coulomb and the weightless "
                      "log-spiral; defaults: the corn of Coetzee (2014). Writes the wall "
                      "stresses and slip line per depth and a summary as CSV.");
#ifdef SIGXFSZ
  // Beyond a file-size limit (ulimit -f) a write then fails with EFBIG, which the writers
  // report, instead of the signal killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  try {
    earth_pressure::declare_options(options, c);
    if (options.parse(argc, argv) == io::Options::Outcome::help) {
      std::fputs(options.help().c_str(), stdout);
      return 0;
    }
    earth_pressure::validate(options, c);
    return run(c, options);
  } catch (const cosmpm::Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  }
  return 1;
}
