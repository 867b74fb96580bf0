#pragma once
// The flat-blade case of Coetzee (2014): every parameter of the paper's Table 1 as a default,
// each overridable from the command line (--name value) or a case file (name = value lines,
// # comments), the command line winning. Every value is checked; a bad one raises
// cosmpm::Error naming it, its valid range and where it came from.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"

namespace flat_blade {

struct Case {
  // Continuum (Table 1, corn).
  double youngs_modulus = 2.76e6;  // Pa
  double poisson_ratio = 0.2;
  double density = 778.0;  // kg/m^3
  double friction_angle_deg = 26.0;
  double dilatancy_angle_deg = 2.0;  // the paper also runs 10 and 26
  double cohesion = 0.0;             // Pa
  double wall_friction_deg = 14.0;   // corn on steel
  // The rig floor under the soil: "fixed" (the paper's: no velocity at the floor nodes) or
  // "friction" (a Coulomb wall, no penetration, friction angle floor_friction_deg), on which
  // the blade scrapes the floor clean.
  std::string floor = "fixed";
  double floor_friction_deg = 14.0;  // steel floor: the blade's corn-on-steel value
  // Cosserat (Table 1): Gc = 2 G, l = 10 mm, J = 0.5 (0.5 l)^2.
  bool polar = false;
  double cosserat_shear_ratio = 2.0;    // Gc / G
  double characteristic_length = 0.01;  // m
  double micro_inertia = 12.5e-6;       // m^2
  bool blade_rotation_fixed = true;     // omega = 0 at the blade (the paper's default)
  // How the Cosserat Drucker-Prager cone is fitted to phi and psi: plane-strain-per-angle
  // (our reading of Tejchman, the default), plane-strain, outer or inner.
  std::string cone = "plane-strain-per-angle";
  // Geometry (Sect. 2): rig 1.2 m x 0.7 m, blade 350 mm high moving at 10 mm/s.
  double grid_length = 1.2;  // m
  double grid_height = 0.7;  // m
  long cells_x = 120;
  long cells_y = 70;
  long particles_per_cell = 2;    // per axis
  double soil_depth = 0.25;       // h, m: 0.15, 0.25 or 0.35 in the paper
  double blade_height = 0.35;     // m
  double blade_thickness = 0.01;  // m
  double blade_start = 0.05;      // x of the blade's back face, m
  double blade_speed = 0.01;      // m/s
  double travel = 0.035;          // m of blade travel simulated
  double rig_width = 0.2;         // m between the glass panels, for forces in N
  double gravity = 9.81;          // m/s^2
  // Numerics.
  double equilibrium_time = 0.25;    // s of damped settling under K0 before the blade moves
  double equilibrium_damping = 0.5;  // local damping while settling
  double damping = 0.0;              // local damping while cutting
  double flip_fraction = 1.0;
  double cfl = 0.5;
  // Contact also corrects the start-of-step velocity (Nairn, Hammerquist and Smith 2020).
  bool start_of_step_contact = false;
  // Contact only where the material would reach the blade within the step (gap check).
  bool gap_check = false;
  double frame_interval = 0.005;  // m of blade travel between ParaView frames
  double average_from = 0.015;    // m: the paper averages the draft over 15-35 mm
  double average_to = 0.035;
  double profile_at = 0.020;  // m: blade stress profile (the paper's Fig. 9)
  // 0: OpenMP's default (every core). Results are bit-identical for any thread count. On
  // the 2-core development VM the default run took 23 s on two threads against 32 s on one,
  // but only while the host kept the two vCPUs on separate cores (docs/architecture.md).
  int threads = 0;
  std::string output_directory;  // default: out/flat_blade/<tag>
  bool write_frames = true;

  std::string tag() const {
    std::ostringstream name;
    name << "h" << std::lround(soil_depth * 1000) << "_" << cells_x << "x" << cells_y << "_"
         << (polar ? "polar" : "nonpolar") << "_psi" << dilatancy_angle_deg;
    if (polar) name << (blade_rotation_fixed ? "_wfixed" : "_wfree");
    if (polar && cone != "plane-strain-per-angle") name << "_" << cone;
    if (floor == "friction") name << "_floor" << floor_friction_deg;
    if (start_of_step_contact) name << "_startcontact";
    if (gap_check) name << "_gapcheck";
    return name.str();
  }
};

namespace detail {
inline double parse_number(const std::string& text, const std::string& where) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) {
    throw cosmpm::Error(where + ": '" + text + "' is not a number");
  }
  return value;
}
inline bool parse_bool(const std::string& text, const std::string& where) {
  if (text == "1" || text == "true" || text == "yes" || text == "on") return true;
  if (text == "0" || text == "false" || text == "no" || text == "off") return false;
  throw cosmpm::Error(where + ": '" + text + "' is not a boolean (valid: true/false, 1/0)");
}
}  // namespace detail

class Parser {
 public:
  explicit Parser(Case& c) : case_(c) {
    number("youngs-modulus", c.youngs_modulus);
    number("poisson-ratio", c.poisson_ratio);
    number("density", c.density);
    number("phi", c.friction_angle_deg);
    number("psi", c.dilatancy_angle_deg);
    number("cohesion", c.cohesion);
    number("delta", c.wall_friction_deg);
    setters_["floor"] = [&c](const std::string& v, const std::string& where) {
      if (v != "fixed" && v != "friction") {
        throw cosmpm::Error(where + ": floor '" + v + "' is not one of fixed, friction");
      }
      c.floor = v;
    };
    number("floor-friction", c.floor_friction_deg);
    flag("start-of-step-contact", c.start_of_step_contact);
    flag("gap-check", c.gap_check);
    flag("polar", c.polar);
    number("gc-over-g", c.cosserat_shear_ratio);
    number("length-scale", c.characteristic_length);
    number("micro-inertia", c.micro_inertia);
    flag("blade-rotation-fixed", c.blade_rotation_fixed);
    setters_["cone"] = [&c](const std::string& v, const std::string& where) {
      if (v != "plane-strain-per-angle" && v != "plane-strain" && v != "outer" && v != "inner") {
        throw cosmpm::Error(where + ": cone '" + v +
                            "' is not one of plane-strain-per-angle, plane-strain, outer, inner");
      }
      c.cone = v;
    };
    number("grid-length", c.grid_length);
    number("grid-height", c.grid_height);
    integer("cells-x", c.cells_x);
    integer("cells-y", c.cells_y);
    integer("particles-per-cell", c.particles_per_cell);
    number("depth", c.soil_depth);
    number("blade-height", c.blade_height);
    number("blade-thickness", c.blade_thickness);
    number("blade-start", c.blade_start);
    number("speed", c.blade_speed);
    number("travel", c.travel);
    number("rig-width", c.rig_width);
    number("gravity", c.gravity);
    number("equilibrium-time", c.equilibrium_time);
    number("equilibrium-damping", c.equilibrium_damping);
    number("damping", c.damping);
    number("flip", c.flip_fraction);
    number("cfl", c.cfl);
    number("frame-interval", c.frame_interval);
    number("average-from", c.average_from);
    number("average-to", c.average_to);
    number("profile-at", c.profile_at);
    setters_["threads"] = [&c](const std::string& v, const std::string& where) {
      c.threads = static_cast<int>(detail::parse_number(v, where));
    };
    setters_["out"] = [&c](const std::string& v, const std::string&) { c.output_directory = v; };
    flag("frames", c.write_frames);
    setters_["mesh"] = [&c](const std::string& v, const std::string& where) {
      const auto x = v.find('x');
      if (x == std::string::npos) throw cosmpm::Error(where + ": mesh '" + v + "' is not NXxNY");
      c.cells_x = std::lround(detail::parse_number(v.substr(0, x), where));
      c.cells_y = std::lround(detail::parse_number(v.substr(x + 1), where));
    };
  }

  // Applies `name = value`; `where` says where the pair came from.
  void set(const std::string& name, const std::string& value, const std::string& where) {
    const auto it = setters_.find(name);
    if (it == setters_.end()) {
      throw cosmpm::Error(where + ": unknown parameter '" + name + "' (run with --help)");
    }
    it->second(value, where + " (" + name + ")");
  }

  void read_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw cosmpm::Error("case file '" + path + "' cannot be opened");
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      const auto eq = line.find('=');
      const std::string where = "case file " + path + " line " + std::to_string(number);
      if (eq == std::string::npos) {
        if (line.find_first_not_of(" \t\r") != std::string::npos) {
          throw cosmpm::Error(where + ": expected 'name = value'");
        }
        continue;
      }
      set(trim(line.substr(0, eq)), trim(line.substr(eq + 1)), where);
    }
  }

  // Returns false when --help was asked for.
  bool parse_command_line(int argc, char** argv) {
    std::vector<std::pair<std::string, std::string>> pairs;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") return false;
      if (arg.rfind("--", 0) != 0 || i + 1 >= argc) {
        throw cosmpm::Error("command line: expected '--name value' at '" + arg + "'");
      }
      pairs.emplace_back(arg.substr(2), argv[++i]);
    }
    for (const auto& [name, value] : pairs) {
      if (name == "case") read_file(value);
    }
    for (const auto& [name, value] : pairs) {
      if (name != "case") set(name, value, "command line --" + name);
    }
    return true;
  }

  void print_help(const char* program) const {
    std::printf(
        "usage: %s [--case FILE] [--name value]...\nparameters (defaults: Table 1 of Coetzee "
        "2014):\n",
        program);
    for (const auto& [name, setter] : setters_) std::printf("  --%s\n", name.c_str());
  }

 private:
  static std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
  }
  void number(const char* name, double& target) {
    setters_[name] = [&target](const std::string& v, const std::string& where) {
      target = detail::parse_number(v, where);
    };
  }
  void integer(const char* name, long& target) {
    setters_[name] = [&target](const std::string& v, const std::string& where) {
      const double value = detail::parse_number(v, where);
      if (value != std::floor(value)) {
        throw cosmpm::Error(where + ": " + v + " is not a whole number");
      }
      target = static_cast<long>(value);
    };
  }
  void flag(const char* name, bool& target) {
    setters_[name] = [&target](const std::string& v, const std::string& where) {
      target = detail::parse_bool(v, where);
    };
  }

  Case& case_;
  std::map<std::string, std::function<void(const std::string&, const std::string&)>> setters_;
};

// Checks ranges that need the whole case (blade inside the grid, depth below the grid top).
inline void validate(const Case& c) {
  using cosmpm::Bounds;
  using cosmpm::require_in_range;
  using cosmpm::require_positive;
  const char* where = "flat-blade case";
  require_positive(where, "grid-length", c.grid_length);
  require_positive(where, "grid-height", c.grid_height);
  require_in_range(where, "cells-x", static_cast<double>(c.cells_x), 4, 100000, Bounds::closed);
  require_in_range(where, "cells-y", static_cast<double>(c.cells_y), 4, 100000, Bounds::closed);
  require_in_range(where, "particles-per-cell", static_cast<double>(c.particles_per_cell), 1, 8,
                   Bounds::closed);
  require_in_range(where, "depth", c.soil_depth, 0.0, std::min(c.grid_height, c.blade_height),
                   Bounds::right_closed);
  require_in_range(where, "blade-height", c.blade_height, 0.0, c.grid_height, Bounds::right_closed);
  require_in_range(where, "blade-thickness", c.blade_thickness, 0.0, c.grid_length);
  require_positive(where, "speed", c.blade_speed);
  require_positive(where, "travel", c.travel);
  require_in_range(where, "blade-start", c.blade_start, 0.0,
                   c.grid_length - c.blade_thickness - c.travel);
  require_positive(where, "rig-width", c.rig_width);
  require_in_range(where, "gravity", c.gravity, 0.0, 1e3, Bounds::left_closed);
  require_in_range(where, "equilibrium-time", c.equilibrium_time, 0.0, 1e3, Bounds::left_closed);
  require_in_range(where, "equilibrium-damping", c.equilibrium_damping, 0.0, 1.0,
                   Bounds::left_closed);
  require_in_range(where, "damping", c.damping, 0.0, 1.0, Bounds::left_closed);
  require_positive(where, "frame-interval", c.frame_interval);
  require_in_range(where, "average-from", c.average_from, 0.0, c.travel, Bounds::left_closed);
  require_in_range(where, "average-to", c.average_to, c.average_from, c.travel,
                   Bounds::right_closed);
  require_in_range(where, "profile-at", c.profile_at, 0.0, c.travel, Bounds::right_closed);
  require_in_range(where, "threads", c.threads, 0, 4096, Bounds::closed);
  require_in_range(where, "floor-friction", c.floor_friction_deg, 0.0, 90.0, Bounds::left_closed);
  if (c.polar) {
    require_positive(where, "gc-over-g", c.cosserat_shear_ratio);
    require_positive(where, "length-scale", c.characteristic_length);
    require_positive(where, "micro-inertia", c.micro_inertia);
  }
}

}  // namespace flat_blade
