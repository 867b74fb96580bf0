// Passive earth pressure on a vertical blade by Sokolovski's method of characteristics, beside
// the Rankine, Coulomb and weightless log-spiral closed forms. Defaults are the corn of
// Coetzee (2014): phi = 26 deg, delta = 14 deg, gamma = 778 x 9.81 N/m^3, blade depths
// h = 150, 250 and 350 mm, rig width 0.2 m. Writes the wall stresses and the slip line per depth
// as CSV; scripts/plot_earth_pressure.py turns them into a PNG.
//
//   example_02_earth_pressure [--phi DEG] [--delta DEG] [--gamma N/m^3] [--height M]...
//                             [--width M] [--surcharge PA] [--cohesion PA] [--active]
//                             [--wall-lines N] [--fan-rays N] [--out DIR]
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "cosmpm/analysis.hpp"
#include "cosmpm/core/error.hpp"

namespace {

namespace ca = cosmpm::analysis;

struct Options {
  ca::EarthPressureProblem problem{
      .friction_angle_deg = 26, .wall_friction_deg = 14, .unit_weight = 778 * 9.81, .height = 0.25};
  std::vector<double> heights;  // empty: the paper's three depths
  double width = 0.2;
  bool active = false;
  ca::CharacteristicsResolution resolution{};
  std::filesystem::path out = "out/earth_pressure";
};

const char* usage =
    "usage: example_02_earth_pressure [options]\n"
    "  --phi DEG         soil friction angle, (0, 60]           [26]\n"
    "  --delta DEG       wall friction angle, [0, phi]          [14]\n"
    "  --gamma N/m^3     soil unit weight, >= 0                 [778 x 9.81]\n"
    "  --height M        blade depth in soil, > 0; repeatable   [0.15 0.25 0.35]\n"
    "  --width M         rig (blade) width for total forces     [0.2]\n"
    "  --surcharge PA    load on the soil surface, >= 0         [0]\n"
    "  --cohesion PA     soil cohesion, >= 0                    [0]\n"
    "  --active          active case instead of passive\n"
    "  --wall-lines N    characteristics reaching the wall      [80]\n"
    "  --fan-rays N      rays of the fan at the blade top       [40]\n"
    "  --out DIR         output directory for the CSV files     [out/earth_pressure]\n";

double parse_number(std::string_view flag, std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) {
    throw cosmpm::Error("command line: " + std::string(flag) + " = '" + std::string(text) +
                        "' is not a number");
  }
  return value;
}

int parse_count(std::string_view flag, std::string_view text) {
  const double value = parse_number(flag, text);
  cosmpm::require_in_range("command line", flag, value, 2, 20000, cosmpm::Bounds::closed);
  if (value != std::floor(value)) {
    throw cosmpm::Error("command line: " + std::string(flag) + " = " + std::string(text) +
                        " must be a whole number in [2, 20000]");
  }
  return static_cast<int>(value);
}

Options parse(int argc, char** argv) {
  Options options;
  using cosmpm::Bounds;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::cout << usage;
      std::exit(0);
    }
    if (flag == "--active") {
      options.active = true;
      continue;
    }
    if (i + 1 >= argc) throw cosmpm::Error("command line: " + std::string(flag) + " needs a value");
    const std::string_view text = argv[++i];
    if (flag == "--phi") {
      options.problem.friction_angle_deg = parse_number(flag, text);
      cosmpm::require_in_range("command line", flag, options.problem.friction_angle_deg, 0, 60,
                               Bounds::right_closed);
    } else if (flag == "--delta") {
      options.problem.wall_friction_deg = parse_number(flag, text);
    } else if (flag == "--gamma") {
      options.problem.unit_weight = parse_number(flag, text);
      cosmpm::require_non_negative("command line", flag, options.problem.unit_weight);
    } else if (flag == "--height") {
      options.heights.push_back(parse_number(flag, text));
      cosmpm::require_positive("command line", flag, options.heights.back());
    } else if (flag == "--width") {
      options.width = parse_number(flag, text);
      cosmpm::require_positive("command line", flag, options.width);
    } else if (flag == "--surcharge") {
      options.problem.surcharge = parse_number(flag, text);
      cosmpm::require_non_negative("command line", flag, options.problem.surcharge);
    } else if (flag == "--cohesion") {
      options.problem.cohesion = parse_number(flag, text);
      cosmpm::require_non_negative("command line", flag, options.problem.cohesion);
    } else if (flag == "--wall-lines") {
      options.resolution.wall_lines = parse_count(flag, text);
    } else if (flag == "--fan-rays") {
      options.resolution.fan_rays = parse_count(flag, text);
    } else if (flag == "--out") {
      options.out = std::string(text);
    } else {
      throw cosmpm::Error("command line: unknown option '" + std::string(flag) + "'\n" + usage);
    }
  }
  // delta is checked against the final phi, whatever the order of the flags.
  cosmpm::require_in_range("command line", "--delta", options.problem.wall_friction_deg, 0,
                           options.problem.friction_angle_deg, Bounds::closed);
  if (options.heights.empty()) options.heights = {0.15, 0.25, 0.35};
  return options;
}

// Rankine slip line from the tip: straight at 45 -+ phi/2 to the horizontal.
double rankine_exit_factor(bool passive, double phi_deg) {
  return std::tan(cosmpm::degrees_to_radians(passive ? 45 + phi_deg / 2 : 45 - phi_deg / 2));
}

// Written to a temporary name and renamed, so a reader never sees a half-written file.
void write_csv(const std::filesystem::path& path, const std::string& header,
               const std::vector<std::vector<double>>& rows) {
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream file(partial);
    if (!file) throw cosmpm::Error("cannot open '" + partial.string() + "' for writing");
    file.precision(10);
    file << header << '\n';
    for (const auto& row : rows) {
      for (std::size_t i = 0; i < row.size(); ++i) file << (i ? "," : "") << row[i];
      file << '\n';
    }
    if (!file) throw cosmpm::Error("failed writing '" + partial.string() + "'");
  }
  std::filesystem::rename(partial, path);
}

int run(const Options& options) {
  const auto& pr = options.problem;
  const double phi = pr.friction_angle_deg, delta = pr.wall_friction_deg;
  const bool passive = !options.active;
  const char* k_name = passive ? "K_p" : "K_a";
  std::filesystem::create_directories(options.out);

  std::printf("%s earth pressure, Sokolovski's method of characteristics (net %d x %d)\n",
              passive ? "Passive" : "Active", options.resolution.wall_lines,
              options.resolution.fan_rays);
  std::printf(
      "phi = %g deg, delta = %g deg, gamma = %g N/m^3, q = %g Pa, c = %g Pa, width = %g m\n", phi,
      delta, pr.unit_weight, pr.surcharge, pr.cohesion, options.width);
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
  for (double height : options.heights) {
    ca::EarthPressureProblem problem = pr;
    problem.height = height;
    const ca::EarthPressureSolution s =
        ca::sokolovski(passive ? ca::EarthPressureCase::passive : ca::EarthPressureCase::active,
                       problem, options.resolution);
    std::printf("%8.1f %9.4f %12.2f %12.2f %11.3f %11.3f %9.1f %10.1f %10.1f\n", height * 1e3,
                s.k_gamma, s.horizontal_force_per_width, s.vertical_force_per_width,
                s.horizontal_force_per_width * options.width,
                s.vertical_force_per_width * options.width, s.resultant_depth * 1e3,
                s.slip_exit_distance * 1e3, coulomb.exit_distance_per_height * height * 1e3);
    summary.push_back({height, s.k_gamma, s.horizontal_force_per_width, s.vertical_force_per_width,
                       s.horizontal_force_per_width * options.width,
                       s.vertical_force_per_width * options.width, s.resultant_depth,
                       s.slip_exit_distance, height * rankine_exit_factor(passive, phi),
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
    write_csv(options.out / (std::string("wall_") += tag) += ".csv",
              "depth_m,normal_pressure_Pa_compression_positive,shear_stress_Pa_on_wall_upward",
              wall);
    write_csv(options.out / (std::string("slip_line_") += tag) += ".csv",
              "distance_from_wall_m,depth_m", slip);
  }
  write_csv(options.out / "summary.csv",
            "height_m,k_gamma,horizontal_force_per_width_N_per_m,vertical_force_per_width_N_per_m,"
            "horizontal_force_N,vertical_force_N,resultant_depth_m,slip_exit_m,rankine_exit_m,"
            "coulomb_exit_m",
            summary);
  std::printf(
      "\nH, V: force the blade applies to the soil (H into the soil, V upward; V < 0 when "
      "passive:\n"
      "the soil pushes the blade up). b = unit width; H [N], V [N] for width %g m.\n"
      "z_H: depth of the horizontal resultant. exit: where the slip line from the blade tip\n"
      "reaches the surface (Sokolovski; Coulomb plane for comparison).\n"
      "CSV files written to %s\n"
      "Plot: /usr/bin/python3 scripts/plot_earth_pressure.py %s\n",
      options.width, options.out.string().c_str(), options.out.string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const cosmpm::Error& error) {
    std::cerr << "error: " << error.what() << '\n';
    return 2;
  } catch (const std::filesystem::filesystem_error& error) {
    std::cerr << "error: " << error.what() << '\n';
    return 2;
  }
}
