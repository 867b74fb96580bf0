#pragma once
// The flat blade of Coetzee (2014) by DEM, the paper's discrete model, from the same driver as
// the MPM runs:
//
//   example_03_flat_blade --method dem [--depth 0.25] [--travel 0.035] [--name value]...
//   example_03_flat_blade --method dem --experiment biaxial [--particles 2000] ...
//   example_03_flat_blade --method dem --help
//
// Flat blade: corn grains (two-disk clumps with Table 1's micro properties, calibrated) are
// rained into the rig from a fixed height, settled, trimmed to the layer depth h, and the blade
// is pushed through them at 10 mm/s. Writes to out/flat_blade_dem/<tag>/ (or --out): packing.csv
// (porosity, bulk density), forces.csv (draft and vertical force of the blade on the soil
// against travel, per metre of width), blade_stress.csv (normal and shear stress on the blade
// over 18-22 mm of travel, the paper's estimate and the binned one: its Fig. 10),
// particles_<mm>mm.csv (per disk: position, radius, initial layer, displacement ratio) at the
// PDR travel (Fig. 11) and the layer snapshots (Figs. 1-2), sokolovski_wall.csv,
// sokolovski_slip_line.csv, summary.csv, frames/dem_flat_blade.xdmf (ParaView).
// Biaxial: a servo-controlled biaxial test of the same grains: biaxial.csv, summary.csv.
// scripts/plot_dem_flat_blade.py turns them into PNG plots.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/dem.hpp"
#include "cosmpm/dem/hdf5_frames.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/run_directory.hpp"

namespace flat_blade_dem {

struct Config {
  std::string experiment = "flat-blade";  // or "biaxial"
  // DEM micro properties (Table 1): per particle, in series at a contact (PFC), unit thickness.
  double particle_stiffness = 420e3;  // k_n = k_s, N/m
  double particle_density = 855.0;    // kg/m^3
  double particle_friction = 0.1;
  // Grains: two-disk clumps (docs/theory/dem.md, "Grain shape and the calibration"), 8-12 mm
  // long, 0.6 as wide; "disk" gives disks of 8-12 mm diameter instead. Calibrated to the corn
  // (docs/validation.md, "DEM"): Table 1's k and mu, rolling resistance 0.2 for the kernels'
  // angularity and a dense packing; biaxial peak 25-27 deg against the corn's 26.
  std::string shape = "clump";
  double size_min = 0.008;        // m
  double size_max = 0.012;        // m
  double aspect = 0.6;            // clump width / length
  double rolling_friction = 0.2;  // mu_r of dem::RollingResistance (0: none, as PFC2D 2.0)
  // Packing friction (PFC's practice for a dense packing): the grains are rained and settled
  // (biaxial: compacted) with this particle friction and no rolling resistance, and the
  // calibrated law above takes over before the layer is trimmed (biaxial: sheared).
  // `--packing-friction none`: the calibrated law throughout (a looser packing).
  std::optional<double> packing_friction = 0.0;
  double local_damping = 0.7;    // PFC's default
  double viscous_damping = 0.0;  // fraction of critical, normal and shear
  // Walls: PFC walls with the particles' stiffness; the blade steel (the continuum's 14 deg,
  // Table 1); the floor rough, as the MPM's fixed bottom (with a steel floor the wedge slides
  // along it instead of failing through the corn: 18 % less draft at h = 150 mm); the rig's
  // end walls smooth (the MPM's rollers).
  double wall_stiffness = 420e3;
  double blade_friction_deg = 14.0;
  double floor_friction_deg = 45.0;
  double side_friction = 0.0;
  // Rig and blade (Sect. 2, as the MPM case): 350 mm blade at 10 mm/s, layer depth h.
  double rig_length = 1.2;
  double rig_height = 2.5;  // height of the end walls: the rain column must fit below it
  double depth = 0.25;
  double blade_height = 0.35;
  double blade_thickness = 0.01;
  double blade_start = 0.05;
  double speed = 0.01;
  double travel = 0.035;
  double gravity = 9.81;
  // Packing: rained from a fixed height, settled, trimmed to the depth, settled again.
  long particles = 0;         // 0: enough to fill depth + fill_margin (about 10,000 at 350 mm)
  double rain_height = 0.4;   // m: the lattice's lowest row
  double fill_margin = 0.03;  // m of layer above the depth before trimming
  // For the default particle count only. Unset: 0.12 for a frictionless rain (the dense
  // packing: 0.111-0.117 measured), 0.17 otherwise; with 0.17 the dense layer at h = 350 mm
  // reached only 5 mm above h before trimming.
  std::optional<double> porosity_guess;
  double settle_ratio = 1e-3;  // PFC's mean unbalanced force ratio
  double settle_time = 4.0;    // s, at most, for the rain
  double resettle_time = 1.0;  // s, at most, after trimming
  double time_step_fraction = 0.8;
  // Analysis (the paper): draft averaged over 15-35 mm, blade stresses over 18-22 mm in bins,
  // PDR >= 0.15 at 15 mm, coloured layers at 100-400 mm.
  double average_from = 0.015;
  double average_to = 0.035;
  double stress_from = 0.018;
  double stress_to = 0.022;
  double stress_bin = 0.01;
  double pdr_at = 0.015;
  double layer_thickness = 0.05;
  std::string snapshots = "0.1,0.2,0.3,0.4";  // m of travel (those within --travel are written)
  // Output.
  double frame_interval = 0.005;  // m of travel
  bool frames = true;
  std::string output_directory;
  bool replace = false;  // delete an earlier run's results in the output folder first
  bool check = false;    // validate, print the particle and step counts, write nothing
  int threads = 0;
  long seed = 1;
  // Biaxial test.
  long biaxial_particles = 2000;
  double confining_stress = 5e3;  // Pa
  double axial_strain = 0.2;
  double strain_rate = 0.1;  // 1/s (slow: local damping adds strength to fast flows)

  std::string tag() const {
    std::ostringstream name;
    if (experiment == "biaxial") {
      name << "biaxial_" << shape << "_s" << std::lround(confining_stress);
    } else {
      name << "h" << std::lround(depth * 1000) << "_" << shape;
    }
    name << "_mu" << particle_friction;
    if (rolling_friction > 0.0) name << "_rolling" << rolling_friction;
    if (packing_friction) name << "_packed" << *packing_friction;
    if (experiment != "biaxial") name << "_travel" << std::lround(travel * 1000);
    return name.str();
  }
  double blade_face() const { return blade_start + blade_thickness; }
  double planned_porosity() const {
    if (porosity_guess) return *porosity_guess;
    return packing_friction && *packing_friction == 0.0 ? 0.12 : 0.17;
  }
};

namespace detail {

inline double number(const std::string& text, const std::string& where) {
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

inline std::vector<double> number_list(const std::string& text, const std::string& where) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(number(item, where));
  return out;
}

// --name value pairs onto the config; returns false for --help.
inline bool parse(Config& c, const std::vector<std::string>& args) {
  std::map<std::string, std::function<void(const std::string&, const std::string&)>> set;
  auto real = [&](const char* name, double& target) {
    set[name] = [&target](const std::string& v, const std::string& w) { target = number(v, w); };
  };
  auto whole = [&](const char* name, long& target) {
    set[name] = [&target](const std::string& v, const std::string& w) {
      const double value = number(v, w);
      if (value != std::floor(value)) throw cosmpm::Error(w + ": " + v + " is not a whole number");
      target = static_cast<long>(value);
    };
  };
  auto text = [&](const char* name, std::string& target) {
    set[name] = [&target](const std::string& v, const std::string&) { target = v; };
  };
  text("experiment", c.experiment);
  real("stiffness", c.particle_stiffness);
  real("density", c.particle_density);
  real("friction", c.particle_friction);
  text("shape", c.shape);
  real("size-min", c.size_min);
  real("size-max", c.size_max);
  real("aspect", c.aspect);
  real("local-damping", c.local_damping);
  real("rolling-friction", c.rolling_friction);
  set["packing-friction"] = [&c](const std::string& v, const std::string& w) {
    if (v == "none") {
      c.packing_friction.reset();
    } else {
      c.packing_friction = number(v, w);
    }
  };
  real("viscous-damping", c.viscous_damping);
  real("wall-stiffness", c.wall_stiffness);
  real("delta", c.blade_friction_deg);
  real("floor-friction-deg", c.floor_friction_deg);
  real("floor-friction", c.floor_friction_deg);  // the MPM runs' name for it
  real("side-friction", c.side_friction);
  real("rig-length", c.rig_length);
  real("rig-height", c.rig_height);
  real("depth", c.depth);
  real("blade-height", c.blade_height);
  real("blade-thickness", c.blade_thickness);
  real("blade-start", c.blade_start);
  real("speed", c.speed);
  real("travel", c.travel);
  real("gravity", c.gravity);
  whole("particles", c.particles);
  real("rain-height", c.rain_height);
  real("fill-margin", c.fill_margin);
  set["porosity-guess"] = [&c](const std::string& v, const std::string& w) {
    c.porosity_guess = number(v, w);
  };
  real("settle-ratio", c.settle_ratio);
  real("settle-time", c.settle_time);
  real("resettle-time", c.resettle_time);
  real("time-step-fraction", c.time_step_fraction);
  real("average-from", c.average_from);
  real("average-to", c.average_to);
  real("stress-from", c.stress_from);
  real("stress-to", c.stress_to);
  real("stress-bin", c.stress_bin);
  real("pdr-at", c.pdr_at);
  real("layer-thickness", c.layer_thickness);
  text("snapshots", c.snapshots);
  real("frame-interval", c.frame_interval);
  std::vector<std::string> flags;  // may stand alone: `--check` is `--check true`
  auto flag = [&](const char* name, bool& target) {
    flags.emplace_back(name);
    set[name] = [&target](const std::string& v, const std::string& w) {
      if (v != "true" && v != "false") throw cosmpm::Error(w + ": '" + v + "' is not true/false");
      target = v == "true";
    };
  };
  flag("frames", c.frames);
  flag("replace", c.replace);
  flag("check", c.check);
  text("out", c.output_directory);
  set["threads"] = [&c](const std::string& v, const std::string& w) {
    c.threads = static_cast<int>(number(v, w));
  };
  whole("seed", c.seed);
  whole("biaxial-particles", c.biaxial_particles);
  real("confining-stress", c.confining_stress);
  real("axial-strain", c.axial_strain);
  real("strain-rate", c.strain_rate);
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") {
      std::printf(
          "usage: example_03_flat_blade --method dem [--name value]...\nparameters "
          "(defaults: Table 1 of Coetzee 2014; see dem_flat_blade.hpp):\n");
      for (const auto& [name, setter] : set) std::printf("  --%s\n", name.c_str());
      return false;
    }
    const std::string name = args[i].rfind("--", 0) == 0 ? args[i].substr(2) : std::string();
    const bool alone = std::find(flags.begin(), flags.end(), name) != flags.end() &&
                       (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0);
    if (name.empty() || (i + 1 >= args.size() && !alone)) {
      throw cosmpm::Error("command line: expected '--name value' at '" + args[i] + "'");
    }
    const auto it = set.find(name);
    if (it == set.end()) {
      throw cosmpm::Error("command line: unknown DEM parameter '--" + name + "' (run with --help)");
    }
    it->second(alone ? "true" : args[i + 1], "command line --" + name);
    if (!alone) ++i;
  }
  return true;
}

inline void validate(const Config& c) {
  using cosmpm::Bounds;
  using cosmpm::require_in_range;
  using cosmpm::require_positive;
  const char* where = "DEM flat-blade case";
  if (c.experiment != "flat-blade" && c.experiment != "biaxial") {
    throw cosmpm::Error(std::string(where) + ": experiment '" + c.experiment +
                        "' is not one of flat-blade, biaxial");
  }
  if (c.shape != "clump" && c.shape != "disk") {
    throw cosmpm::Error(std::string(where) + ": shape '" + c.shape + "' is not clump or disk");
  }
  require_positive(where, "stiffness", c.particle_stiffness);
  require_positive(where, "density", c.particle_density);
  cosmpm::require_non_negative(where, "friction", c.particle_friction);
  cosmpm::require_non_negative(where, "rolling-friction", c.rolling_friction);
  if (c.packing_friction)
    cosmpm::require_non_negative(where, "packing-friction", *c.packing_friction);
  require_positive(where, "size-min", c.size_min);
  require_in_range(where, "size-max", c.size_max, c.size_min, 1.0, Bounds::left_closed);
  require_in_range(where, "aspect", c.aspect, 0.0, 1.0, Bounds::right_closed);
  require_positive(where, "wall-stiffness", c.wall_stiffness);
  require_in_range(where, "delta", c.blade_friction_deg, 0.0, 90.0, Bounds::left_closed);
  require_in_range(where, "floor-friction-deg", c.floor_friction_deg, 0.0, 90.0,
                   Bounds::left_closed);
  cosmpm::require_non_negative(where, "side-friction", c.side_friction);
  require_positive(where, "rig-length", c.rig_length);
  require_in_range(where, "depth", c.depth, 0.0, c.blade_height, Bounds::right_closed);
  require_in_range(where, "blade-start", c.blade_start, 0.0, c.rig_length);
  require_in_range(where, "blade-thickness", c.blade_thickness, 0.0, c.rig_length);
  require_in_range(where, "blade-height", c.blade_height, 0.0, c.rig_height);
  require_in_range(where, "rain-height", c.rain_height, 0.0, c.rig_height);
  require_positive(where, "speed", c.speed);
  require_in_range(where, "travel", c.travel, 0.0, c.rig_length - c.blade_face() - 2.0 * c.size_max,
                   Bounds::right_closed);
  require_in_range(where, "particles", static_cast<double>(c.particles), 0.0, 1e8, Bounds::closed);
  require_positive(where, "fill-margin", c.fill_margin);
  require_in_range(where, "porosity-guess", c.planned_porosity(), 0.0, 1.0);
  require_positive(where, "settle-ratio", c.settle_ratio);
  require_positive(where, "settle-time", c.settle_time);
  require_positive(where, "resettle-time", c.resettle_time);
  require_in_range(where, "time-step-fraction", c.time_step_fraction, 0.0, 1.0,
                   Bounds::right_closed);
  require_in_range(where, "average-from", c.average_from, 0.0, c.travel, Bounds::left_closed);
  require_in_range(where, "average-to", c.average_to, c.average_from, c.travel,
                   Bounds::right_closed);
  require_in_range(where, "stress-from", c.stress_from, 0.0, c.travel, Bounds::left_closed);
  require_in_range(where, "stress-to", c.stress_to, c.stress_from, c.travel, Bounds::right_closed);
  require_positive(where, "stress-bin", c.stress_bin);
  require_in_range(where, "pdr-at", c.pdr_at, 0.0, c.travel, Bounds::right_closed);
  require_positive(where, "layer-thickness", c.layer_thickness);
  require_positive(where, "frame-interval", c.frame_interval);
  require_in_range(where, "threads", c.threads, 0, 4096, Bounds::closed);
  require_in_range(where, "biaxial-particles", static_cast<double>(c.biaxial_particles), 16, 1e8,
                   Bounds::closed);
  for (const double s : number_list(c.snapshots, "snapshots")) {
    require_positive(where, "snapshot travel", s);
  }
}

}  // namespace detail

inline cosmpm::dem::Grains grains(const Config& c) {
  cosmpm::dem::Grains g;
  g.shape = c.shape == "clump" ? cosmpm::dem::ClumpShape::two_disks(1.0, c.aspect)
                               : cosmpm::dem::ClumpShape({{cosmpm::Vec<2>::Zero(), 0.5}});
  g.min_size = c.size_min;
  g.max_size = c.size_max;
  g.density = c.particle_density;
  return g;
}

inline cosmpm::dem::LinearSpring law(const Config& c) {
  return cosmpm::dem::LinearSpring(
      {c.particle_stiffness, c.particle_stiffness, c.particle_friction},
      {c.viscous_damping, c.viscous_damping, true});
}

namespace fs = std::filesystem;

// Per disk: position, radius, body, initial layer, displacement ratio (PDR) and displacement.
template <class Sim>
void write_particles(const fs::path& path, const Sim& sim, const std::vector<double>& layer,
                     double travel) {
  using namespace cosmpm;
  io::CsvWriter csv(path, {"x_m", "y_m", "radius_m", "body", "layer", "pdr", "ux_m", "uy_m"});
  const dem::Assembly& a = sim.assembly();
  const auto& x = a.elements().get<particles::field::Position<2>>();
  const auto& r = a.elements().get<dem::field::Radius>();
  const auto& body = a.elements().get<particles::field::Body>();
  const auto& xb = a.bodies().get<particles::field::Position<2>>();
  const auto& xb0 = a.bodies().get<particles::field::InitialPosition<2>>();
  for (std::size_t k = 0; k < x.size(); ++k) {
    const auto b = static_cast<std::size_t>(body[k]);
    const Vec<2> u = xb[b] - xb0[b];
    csv.write_row({x[k][0], x[k][1], r[k], static_cast<double>(b), layer[k],
                   travel > 0.0 ? u.norm() / travel : 0.0, u[0], u[1]});
  }
}

// `folder` is null for --check true: the run stops before it writes anything.
template <class Law>
int run_flat_blade(const Config& c, cosmpm::io::RunDirectory* folder, const Law& contact_law,
                   const std::optional<Law>& packing_law) {
  using namespace cosmpm;
  using Sim = dem::Simulation<Law, dem::LocalDamping>;
  const auto wall_start = std::chrono::steady_clock::now();
  const dem::Grains g = grains(c);
  const double face = c.blade_face();
  Index count = c.particles;
  if (count == 0) {
    const double area = (c.rig_length - face) * (c.depth + c.fill_margin);
    count = static_cast<Index>(std::ceil(area * (1.0 - c.planned_porosity()) / g.mean_area()));
  }
  dem::Assembly assembly;
  dem::rain(assembly, g, count, {face, c.rig_length, c.rain_height, c.rig_height},
            static_cast<std::uint64_t>(c.seed));

  dem::Parameters parameters;
  parameters.gravity = Vec<2>(0.0, -c.gravity);
  parameters.threads = c.threads;
  Sim sim(std::move(assembly), contact_law, dem::LocalDamping(c.local_damping), parameters);
  const double k = c.wall_stiffness;
  const dem::LinearSpringMaterial steel{k, k, std::tan(degrees_to_radians(c.blade_friction_deg))};
  const dem::LinearSpringMaterial floor_steel{k, k,
                                              std::tan(degrees_to_radians(c.floor_friction_deg))};
  const dem::LinearSpringMaterial smooth{k, k, c.side_friction};
  const Index floor = sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), floor_steel);
  sim.add_plane_wall("left end", Vec<2>(0, 0), Vec<2>(1, 0), smooth);
  const Index right =
      sim.add_plane_wall("right end", Vec<2>(c.rig_length, 0), Vec<2>(-1, 0), smooth);
  // The blade stands on the floor, still until the layer is ready; its right edge (index 1,
  // running up from the tip) is the face that cuts.
  auto start = std::make_shared<double>(1e300);
  auto blade_body =
      contact::RigidBody<2>::box(Vec<2>(c.blade_start, 0.0), Vec<2>(face, c.blade_height));
  const double speed = c.speed;
  blade_body.set_velocity(contact::RigidBody<2>::VelocityLaw(
      [start, speed](double t) { return Vec<2>(t < *start ? 0.0 : speed, 0.0); }));
  const Index blade = sim.add_polygon_wall("blade", std::move(blade_body), steel);
  constexpr int cutting_face = 1;
  // Above the blade while raining, so no grain bounces over it.
  const Index retainer = sim.add_polygon_wall(
      "retainer",
      contact::RigidBody<2>::box(Vec<2>(c.blade_start, c.blade_height), Vec<2>(face, c.rig_height)),
      smooth);
  const double dt = c.time_step_fraction * sim.critical_time_step();
  if (c.check) {
    // At most: the whole rain and resettle time, then the cut.
    const double seconds = c.settle_time + c.resettle_time + c.travel / c.speed;
    std::printf("case checked: %ld particles, %ld steps of %.3g s; nothing written\n",
                static_cast<long>(sim.assembly().body_count()),
                static_cast<long>(std::ceil(seconds / dt)), dt);
    return 0;
  }
  if (packing_law) sim.set_law(*packing_law);
  std::printf("DEM flat blade: h = %.0f mm, %ld %s (%ld disks), dt = %.3g s\n", c.depth * 1000,
              static_cast<long>(sim.assembly().body_count()),
              c.shape == "clump" ? "two-disk clumps" : "disks",
              static_cast<long>(sim.assembly().element_count()), dt);

  // Rain, trim, settle.
  {
    io::ProgressReporter progress("DEM rain", c.settle_time, sim.assembly().body_count());
    const auto rained = dem::settle(sim, dt, c.settle_time, c.settle_ratio, 0.3, [&](const Sim& s) {
      progress.update(s.time(), s.step_count());
    });
    progress.finish(sim.time(), sim.step_count());
    double top = 0.0;
    for (Index b = 0; b < sim.assembly().body_count(); ++b) {
      top = std::max(top, sim.assembly().position(b)[1]);
    }
    std::printf(
        "  rained and settled in %.2f s (unbalanced force ratio %.2g%s), surface at %.0f mm\n",
        rained.time, rained.unbalanced_force_ratio, rained.settled ? "" : ", NOT settled",
        top * 1000);
    if (top < c.depth) {
      throw Error("DEM flat blade: the rained layer reaches only " +
                  cosmpm::detail::format_number(top) +
                  " m, below the depth h = " + cosmpm::detail::format_number(c.depth) +
                  " m (raise --particles, now " + std::to_string(count) + ")");
    }
  }
  if (packing_law) sim.set_law(contact_law);
  const Index removed = dem::trim_above(sim.assembly(), c.depth);
  const auto resettled = dem::settle(sim, dt, c.resettle_time, c.settle_ratio, 0.1);
  const Vec<2> lower(face + 0.05, 0.02), upper(c.rig_length - 0.05, c.depth - 0.03);
  const double porosity =
      dem::porosity(sim.assembly(), lower, upper, 0.2 * sim.assembly().min_radius());
  const double bulk_density = c.particle_density * (1.0 - porosity);
  std::printf(
      "  trimmed %ld above h, %ld left; resettled in %.2f s; porosity %.3f, bulk density "
      "%.0f kg/m^3\n",
      static_cast<long>(removed), static_cast<long>(sim.assembly().body_count()), resettled.time,
      porosity, bulk_density);
  {
    io::CsvWriter packing(folder->claim("packing.csv"),
                          {"bodies", "elements", "porosity", "bulk_density_kg_m3", "rain_time_s",
                           "resettle_time_s", "unbalanced_force_ratio"});
    packing.write_row({static_cast<double>(sim.assembly().body_count()),
                       static_cast<double>(sim.assembly().element_count()), porosity, bulk_density,
                       sim.time() - resettled.time, resettled.time,
                       resettled.unbalanced_force_ratio});
  }
  const double packing_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  // The reference: Sokolovski for the continuum's corn (778 kg/m^3, the paper's Fig. 8) and for
  // this packing's bulk density.
  auto sokolovski = [&](double density) {
    return analysis::sokolovski_passive({.friction_angle_deg = 26.0,
                                         .wall_friction_deg = c.blade_friction_deg,
                                         .unit_weight = density * c.gravity,
                                         .height = c.depth});
  };
  const auto reference = sokolovski(778.0);
  const auto reference_dem = sokolovski(bulk_density);
  {
    io::CsvWriter wall(folder->claim("sokolovski_wall.csv"),
                       {"depth_m", "normal_pressure_Pa", "shear_stress_Pa"});
    for (const auto& w : reference.wall)
      wall.write_row({w.depth, w.normal_pressure, w.shear_stress});
    io::CsvWriter slip(folder->claim("sokolovski_slip_line.csv"), {"distance_m", "depth_m"});
    for (const auto& s : reference.slip_line) slip.write_row({s.distance, s.depth});
  }

  // Cut.
  sim.walls().set_enabled(retainer, false);
  sim.assembly().reset_initial_positions();
  *start = sim.time();
  const dem::Assembly& grains_now = sim.assembly();  // not dependent: plain get<>
  std::vector<double> layer(static_cast<std::size_t>(grains_now.element_count()));
  {
    const auto& body = grains_now.elements().get<particles::field::Body>();
    for (std::size_t e = 0; e < layer.size(); ++e) {
      layer[e] = std::floor(grains_now.position(body[e])[1] / c.layer_thickness);
    }
  }
  std::vector<double> pdr(layer.size(), 0.0);
  std::optional<dem::FrameWriter> frames;
  if (c.frames) {
    frames.emplace(folder->path() / "frames", "dem_flat_blade");
    folder->claim("frames/dem_flat_blade.xdmf");
  }
  auto write_frame = [&](double travel) {
    folder->claim(fs::path("frames") / frames->frame_path(frames->frame_count()).filename());
    const auto& body = grains_now.elements().get<particles::field::Body>();
    const auto& start_position = grains_now.bodies().get<particles::field::InitialPosition<2>>();
    for (std::size_t e = 0; e < pdr.size(); ++e) {
      const Index b = body[e];
      const Vec<2> u = grains_now.position(b) - start_position[static_cast<std::size_t>(b)];
      pdr[e] = travel > 0.0 ? u.norm() / travel : 0.0;
    }
    frames->write(sim, {{"layer", &layer}, {"pdr", &pdr}});
  };
  if (frames) write_frame(0.0);
  std::vector<double> snapshots;
  for (const double s : detail::number_list(c.snapshots, "snapshots")) {
    if (s <= c.travel + 1e-12) snapshots.push_back(s);
  }
  snapshots.push_back(c.pdr_at);
  std::sort(snapshots.begin(), snapshots.end());
  std::size_t next_snapshot = 0;
  // The snapshots due up to `through` [m of travel], written as at `travel`.
  auto write_snapshots = [&](double through, double travel) {
    for (; next_snapshot < snapshots.size() && snapshots[next_snapshot] <= through;
         ++next_snapshot) {
      const long mm = std::lround(snapshots[next_snapshot] * 1000);
      write_particles(folder->claim("particles_" + std::to_string(mm) + "mm.csv"), sim, layer,
                      travel);
    }
  };
  double next_frame = c.frame_interval;
  io::CsvWriter forces(
      folder->claim("forces.csv"),
      {"time_s", "displacement_m", "draft_N_per_m", "vertical_N_per_m", "floor_x_N_per_m",
       "floor_y_N_per_m", "right_end_x_N_per_m", "blade_contacts"});
  dem::FaceStressAverage stress(c.blade_height, c.stress_bin);
  const double row_interval = 1e-4;
  double next_row = row_interval, row_draft = 0.0, row_vertical = 0.0;
  long row_steps = 0;
  double draft_sum = 0.0, vertical_sum = 0.0;
  long averaged = 0;
  const double end_time = *start + c.travel / c.speed;
  io::ProgressReporter progress("DEM flat blade", end_time, sim.assembly().body_count());
  const auto cut_start = std::chrono::steady_clock::now();
  const std::int64_t steps_before = sim.step_count();
  while (sim.time() < end_time - 0.5 * dt) {
    sim.step(dt);
    progress.update(sim.time(), sim.step_count());
    const double travel = (sim.time() - *start) * c.speed;
    const Vec<2> on_blade = sim.wall_force(blade);  // the particles' force on the blade
    const double draft = -on_blade[0], vertical = -on_blade[1];
    row_draft += draft;
    row_vertical += vertical;
    ++row_steps;
    if (travel >= c.average_from - 1e-12 && travel <= c.average_to + 1e-12) {
      draft_sum += draft;
      vertical_sum += vertical;
      ++averaged;
    }
    if (travel >= c.stress_from - 1e-12 && travel <= c.stress_to + 1e-12) {
      std::vector<dem::FaceContact> on_face;
      sim.for_each_wall_contact([&](const dem::WallContact& w) {
        // Soil on blade: compression, and the drag up the face (-shear on the grain along t).
        if (w.wall == blade && w.edge == cutting_face) {
          on_face.push_back({w.along, w.normal_force, -w.shear_force});
        }
      });
      stress.add(on_face);
    }
    if (travel >= next_row - 1e-12) {
      forces.write_row({sim.time(), travel, row_draft / static_cast<double>(row_steps),
                        row_vertical / static_cast<double>(row_steps), sim.wall_force(floor)[0],
                        sim.wall_force(floor)[1], sim.wall_force(right)[0],
                        static_cast<double>(sim.walls()[blade].contacts)});
      row_draft = row_vertical = 0.0;
      row_steps = 0;
      next_row += row_interval;
    }
    write_snapshots(travel + 1e-12, travel);
    if (frames && travel >= next_frame - 1e-12) {
      write_frame(travel);
      next_frame += c.frame_interval;
    }
  }
  progress.finish(sim.time(), sim.step_count());
  // Rounding can end the loop a hair short of --travel (399.99 of 400 mm): the snapshots and
  // the frame due at the end of travel are still written, at the travel reached.
  const double reached = (sim.time() - *start) * c.speed;
  write_snapshots(c.travel + 1e-12, reached);
  if (frames && next_frame - c.frame_interval < c.travel - 1e-9) write_frame(reached);
  const double cut_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - cut_start).count();
  {
    io::CsvWriter profile(folder->claim("blade_stress.csv"),
                          {"height_above_tip_m", "depth_m", "neighbour_normal_Pa",
                           "neighbour_shear_Pa", "samples", "binned_normal_Pa", "binned_shear_Pa"});
    for (const auto& bin : stress.bins()) {
      if (bin.centre > c.depth + c.stress_bin) continue;  // above the soil
      profile.write_row({bin.centre, c.depth - bin.centre, bin.neighbour_normal,
                         bin.neighbour_shear, static_cast<double>(bin.samples), bin.binned_normal,
                         bin.binned_shear});
    }
  }
  const double draft = averaged > 0 ? draft_sum / static_cast<double>(averaged) : 0.0;
  const double vertical = averaged > 0 ? vertical_sum / static_cast<double>(averaged) : 0.0;
  const double difference =
      100.0 * (draft - reference.horizontal_force_per_width) / reference.horizontal_force_per_width;
  const double total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  {
    io::CsvWriter summary(folder->claim("summary.csv"), {"depth_m",
                                                         "bodies",
                                                         "elements",
                                                         "clumps",
                                                         "porosity",
                                                         "bulk_density_kg_m3",
                                                         "average_draft_N_per_m",
                                                         "average_vertical_N_per_m",
                                                         "sokolovski_draft_N_per_m",
                                                         "sokolovski_vertical_N_per_m",
                                                         "sokolovski_dem_density_draft_N_per_m",
                                                         "difference_percent",
                                                         "time_step_s",
                                                         "cutting_steps",
                                                         "packing_seconds",
                                                         "cutting_seconds",
                                                         "total_seconds",
                                                         "threads",
                                                         "blade_face_x_m",
                                                         "speed_m_per_s",
                                                         "travel_m",
                                                         "average_from_m",
                                                         "average_to_m",
                                                         "friction",
                                                         "aspect",
                                                         "rolling_friction",
                                                         "packing_friction"});
    summary.write_row({c.depth,
                       static_cast<double>(sim.assembly().body_count()),
                       static_cast<double>(sim.assembly().element_count()),
                       c.shape == "clump" ? 1.0 : 0.0,
                       porosity,
                       bulk_density,
                       draft,
                       vertical,
                       reference.horizontal_force_per_width,
                       reference.vertical_force_per_width,
                       reference_dem.horizontal_force_per_width,
                       difference,
                       dt,
                       static_cast<double>(sim.step_count() - steps_before),
                       packing_seconds,
                       cut_seconds,
                       total_seconds,
                       static_cast<double>(resolve_thread_count(c.threads)),
                       face,
                       c.speed,
                       c.travel,
                       c.average_from,
                       c.average_to,
                       c.particle_friction,
                       c.shape == "clump" ? c.aspect : 1.0,
                       c.rolling_friction,
                       c.packing_friction.value_or(c.particle_friction)});
  }
  std::printf("  %ld cutting steps, %.1f s packing + %.1f s cutting\n",
              static_cast<long>(sim.step_count() - steps_before), packing_seconds, cut_seconds);
  std::printf("  average draft over %.0f-%.0f mm of travel: %.1f N/m (%.2f N for the 200 mm rig)\n",
              c.average_from * 1000, c.average_to * 1000, draft, 0.2 * draft);
  std::printf(
      "  Sokolovski (778 kg/m^3): %.1f N/m; DEM %+.1f %%; at the packing's %.0f kg/m^3: "
      "%.1f N/m\n",
      reference.horizontal_force_per_width, difference, bulk_density,
      reference_dem.horizontal_force_per_width);
  std::printf("  average vertical force: %.1f N/m (Sokolovski %.1f N/m)\n", vertical,
              reference.vertical_force_per_width);
  std::printf(
      "results in %s: forces.csv, blade_stress.csv, summary.csv, frames/dem_flat_blade.xdmf\n",
      folder->path().c_str());
  return 0;
}

template <class Law>
int run_biaxial(const Config& c, cosmpm::io::RunDirectory* folder, const Law& contact_law,
                const std::optional<Law>& packing_law) {
  using namespace cosmpm;
  if (c.check) {
    std::printf("case checked: %ld particles; nothing written\n",
                static_cast<long>(c.biaxial_particles));
    return 0;
  }
  dem::BiaxialSettings s;
  s.particles = c.biaxial_particles;
  s.confining_stress = c.confining_stress;
  s.axial_strain = c.axial_strain;
  s.strain_rate = c.strain_rate;
  s.local_damping = c.local_damping;
  s.time_step_fraction = c.time_step_fraction;
  s.threads = c.threads;
  s.seed = static_cast<std::uint64_t>(c.seed);
  io::ProgressReporter progress("DEM biaxial", 1.0, s.particles);
  std::int64_t calls = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  const auto result = dem::biaxial_test(
      contact_law, grains(c), s, [&](double fraction) { progress.update(fraction, ++calls); },
      packing_law);
  progress.finish(1.0, calls);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  {
    io::CsvWriter curve(
        folder->claim("biaxial.csv"),
        {"axial_strain", "volumetric_strain", "sigma1_Pa", "sigma3_Pa", "friction_angle_deg"});
    for (const auto& p : result.curve) {
      curve.write_row(
          {p.axial_strain, p.volumetric_strain, p.sigma1, p.sigma3, p.friction_angle_deg});
    }
    io::CsvWriter summary(
        folder->claim("summary.csv"),
        {"particles", "friction", "confining_stress_Pa", "peak_angle_deg", "peak_strain",
         "critical_angle_deg", "critical_dilatancy", "porosity", "compacted", "steps",
         "run_seconds", "aspect", "rolling_friction", "packing_friction"});
    summary.write_row({static_cast<double>(result.particles), c.particle_friction,
                       c.confining_stress, result.peak_angle_deg, result.peak_strain,
                       result.critical_angle_deg, result.critical_dilatancy, result.porosity,
                       result.compacted ? 1.0 : 0.0, static_cast<double>(result.steps), seconds,
                       c.shape == "clump" ? c.aspect : 1.0, c.rolling_friction,
                       c.packing_friction.value_or(c.particle_friction)});
  }
  std::printf("DEM biaxial test: %ld %s, mu = %g, s3 = %.0f Pa%s\n",
              static_cast<long>(result.particles), c.shape == "clump" ? "two-disk clumps" : "disks",
              c.particle_friction, c.confining_stress,
              result.compacted ? "" : " (compaction did NOT converge)");
  std::printf(
      "  porosity after compaction %.3f; peak friction angle %.1f deg at %.1f %% strain; "
      "critical state %.1f deg (dilatancy %.3f); %.1f s\n",
      result.porosity, result.peak_angle_deg, 100 * result.peak_strain, result.critical_angle_deg,
      result.critical_dilatancy, seconds);
  std::printf("results in %s: biaxial.csv, summary.csv\n", folder->path().c_str());
  return 0;
}

// The hook of the driver's main(): with `--method dem` runs the DEM and returns its exit code;
// with `--method mpm` (or no --method) removes the option and returns nothing, so the MPM
// driver goes on with the remaining arguments.
inline std::optional<int> run_if_requested(int& argc, char** argv) {
  int at = -1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--method") == 0) at = i;
  }
  if (at < 0) return std::nullopt;
  if (at + 1 >= argc) {
    std::fprintf(stderr, "error: command line: --method needs a value (mpm or dem)\n");
    return 1;
  }
  const std::string method = argv[at + 1];
  for (int i = at; i + 2 < argc; ++i) argv[i] = argv[i + 2];
  argc -= 2;
  if (method == "mpm") return std::nullopt;
  if (method != "dem") {
    std::fprintf(stderr, "error: command line --method: '%s' is not mpm or dem\n", method.c_str());
    return 1;
  }
  try {
    Config c;
    if (!detail::parse(c, std::vector<std::string>(argv + 1, argv + argc))) return 0;
    detail::validate(c);
    const fs::path out = c.output_directory.empty() ? fs::path("out/flat_blade_dem") / c.tag()
                                                    : fs::path(c.output_directory);
    // As the MPM runs: a fresh run refuses a folder holding an earlier run's results.
    std::optional<cosmpm::io::RunDirectory> folder;
    if (!c.check) {
      using Mode = cosmpm::io::RunDirectory::Mode;
      folder.emplace(
          out, c.replace ? Mode::replace : Mode::fresh, "example_03_flat_blade --method dem",
          c.output_directory.empty() ? "--out (default out/flat_blade_dem/<tag>)" : "--out");
    }
    cosmpm::io::RunDirectory* run_folder = folder ? &*folder : nullptr;
    auto run = [&](const auto& contact_law, const auto& packing_law) {
      return c.experiment == "biaxial" ? run_biaxial(c, run_folder, contact_law, packing_law)
                                       : run_flat_blade(c, run_folder, contact_law, packing_law);
    };
    Config packing = c;  // the packing law: the packing friction, no rolling resistance
    packing.particle_friction = c.packing_friction.value_or(c.particle_friction);
    if (c.rolling_friction > 0.0) {
      using Rolling = cosmpm::dem::RollingResistance<cosmpm::dem::LinearSpring>;
      return run(
          Rolling(law(c), c.rolling_friction),
          c.packing_friction ? std::optional<Rolling>(Rolling(law(packing), 0.0)) : std::nullopt);
    }
    return run(law(c), c.packing_friction ? std::optional(law(packing)) : std::nullopt);
  } catch (const cosmpm::Error& error) {
    std::fprintf(stderr, "\nerror: %s\n", error.what());
    return 1;
  }
}

}  // namespace flat_blade_dem
