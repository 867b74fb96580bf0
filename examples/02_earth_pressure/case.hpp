#pragma once
// The options of example 02: the soil, the blade depths and the net of characteristics. Light
// on purpose (no analysis headers): the option fuzz test includes it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/detail/option_values.hpp"
#include "cosmpm/io/options.hpp"

namespace earth_pressure {

struct Case {
  // Corn of Coetzee (2014).
  double friction_angle_deg = 26.0;
  double wall_friction_deg = 14.0;
  double unit_weight = 778 * 9.81;  // N/m^3
  double surcharge = 0.0;           // Pa
  double cohesion = 0.0;            // Pa
  std::vector<double> heights{0.15, 0.25, 0.35};
  double width = 0.2;  // m
  bool active = false;
  int wall_lines = 80;
  int fan_rays = 40;
  std::string out = "out/earth_pressure";
  bool replace = false;
};

inline void declare_options(cosmpm::io::Options& o, Case& c) {
  using cosmpm::Bounds;
  using cosmpm::io::RealRange;
  using Role = cosmpm::io::Options::Role;
  o.group("Soil (corn of Coetzee 2014)");
  o.real("phi", c.friction_angle_deg, {0.0, 60.0, Bounds::right_closed}, "deg",
         "soil friction angle (the method is verified up to 60 deg)");
  o.real("delta", c.wall_friction_deg, {0.0, 60.0, Bounds::closed}, "deg",
         "wall friction angle, at most --phi");
  o.real("gamma", c.unit_weight, {0.0, 1e7, Bounds::closed}, "N/m^3", "soil unit weight");
  o.real("surcharge", c.surcharge, {0.0, 1e9, Bounds::closed}, "Pa", "load on the soil surface");
  o.real("cohesion", c.cohesion, {0.0, 1e9, Bounds::closed}, "Pa", "soil cohesion");
  o.group("Blade");
  o.custom(
      "height", "M[,M...]", "blade depths in the soil, comma-separated", "each in (0, 100] m",
      [&c](std::string_view value, const std::string& where) {
        std::vector<double> heights;
        while (true) {
          const auto comma = value.find(',');
          const std::string_view item = value.substr(0, comma);
          const auto parsed = cosmpm::io::detail::parse_real(item);
          if (!parsed || !(*parsed > 0.0 && *parsed <= 100.0)) {
            throw cosmpm::Error(where + ": '" + cosmpm::io::detail::printable(item) +
                                "' is not a depth in (0, 100] m (give depths as 0.15,0.25)");
          }
          heights.push_back(*parsed);
          if (comma == std::string_view::npos) break;
          value.remove_prefix(comma + 1);
        }
        if (heights.size() > 100) throw cosmpm::Error(where + ": at most 100 depths");
        c.heights = heights;
      },
      [&c] {
        std::string text;
        for (const double h : c.heights) {
          if (!text.empty()) text += ',';
          text += cosmpm::io::detail::format_number_exact(h);
        }
        return text;
      });
  o.real("width", c.width, {0.0, 100.0, Bounds::right_closed}, "m",
         "blade (rig) width for total forces");
  o.flag("active", c.active, "active case instead of passive");
  o.group("Net of characteristics");
  o.integer("wall-lines", c.wall_lines, 2, 20000,
            "characteristics reaching the wall (time grows as its square)");
  o.integer("fan-rays", c.fan_rays, 2, 20000, "rays of the fan at the blade top");
  o.group("Run control");
  o.text("out", c.out, "DIR", "output folder for the CSV files", Role::control);
  o.flag("replace", c.replace, "delete an earlier run's results in the output folder first",
         Role::control);
}

inline void validate(const cosmpm::io::Options& o, const Case& c) {
  if (c.wall_friction_deg > c.friction_angle_deg) {
    o.fail("delta", "exceeds " + o.describe("phi") + "; lower --delta or raise --phi");
  }
  if (c.unit_weight == 0.0 && c.surcharge == 0.0 && c.cohesion == 0.0) {
    o.fail("gamma",
           "with --surcharge and --cohesion 0 leaves the soil without stress; give one "
           "of them a positive value");
  }
}

// Seconds the net takes per depth on the development VM: measured 0.6 s at 1000 x 40 and
// 4.7 s at 2000 x 2000 (about 5.3e-7 s per wall line and characteristic).
inline double estimated_seconds_per_depth(const Case& c) {
  return 5.3e-7 * c.wall_lines * (static_cast<double>(c.wall_lines) + c.fan_rays);
}

}  // namespace earth_pressure
