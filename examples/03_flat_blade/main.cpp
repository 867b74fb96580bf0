// Example 03: the flat blade of Coetzee (2014) pushed through corn grains, nonpolar
// (Mohr-Coulomb or Drucker-Prager) or polar (Cosserat Drucker-Prager) MPM, from one driver.
//
//   example_03_flat_blade [--case FILE] [--depth 0.25] [--mesh 120x70] [--polar true] ...
//   example_03_flat_blade --help
//
// Writes to out/flat_blade/<tag>/ (or --out): forces.csv (draft and vertical force against
// blade travel), blade_stress.csv (normal and shear traction along the blade at
// --profile-at), sokolovski_wall.csv and sokolovski_slip_line.csv (the reference),
// summary.csv, case.used (the settings, a case file), checkpoint.h5 (with --checkpoint-every
// or when stopped) and frames/flat_blade.xdmf (ParaView; the blade in
// frames/flat_blade_bodies.xdmf) with one HDF5 frame per --frame-interval of travel.
// scripts/plot_flat_blade.py turns them into PNG plots; docs/usage.md describes them.
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <variant>

#include "case.hpp"
#include "compositions.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"
#include "cosmpm/version.hpp"
#include "dem_flat_blade.hpp"
#include "feasibility.hpp"
#include "rig.hpp"

namespace {
using namespace cosmpm;
namespace fs = std::filesystem;

constexpr const char* program = "example_03_flat_blade";

std::string version_text() {
  return std::to_string(version_major) + "." + std::to_string(version_minor) + "." +
         std::to_string(version_patch);
}

// With --restart, the settings must be those of the run in the folder.
void check_restart_settings(const fs::path& out, const std::string& parameters) {
  const fs::path used = out / "case.used";
  std::ifstream in(used, std::ios::binary);
  if (!in) {
    throw Error("--restart: the output folder '" + out.string() +
                "' holds no stopped run (no case.used); give the --out of the run to continue");
  }
  std::stringstream text;
  text << in.rdbuf();
  if (text.str() == parameters) return;
  std::istringstream ours(parameters);
  std::istringstream theirs(text.str());
  std::string a;
  std::string b;
  while (std::getline(ours, a) && std::getline(theirs, b)) {
    if (a != b && a.rfind('#', 0) != 0) {
      throw Error("--restart: the settings differ from those of the run in '" + out.string() +
                  "': '" + a + "' here, '" + b +
                  "' in its case.used; restart with its settings: " + program + " --case " +
                  used.string() + " --out " + out.string() + " --restart true");
    }
  }
  throw Error("--restart: the settings differ from those of the run in '" + out.string() +
              "' (its case.used); restart with --case " + used.string());
}

// The closing list: files written, relative to the output folder, frames counted.
std::string written_list(const io::RunDirectory& folder) {
  std::string list;
  long frames = 0;
  for (const auto& file : folder.written()) {
    const std::string name = fs::relative(file, folder.path()).generic_string();
    if (name.rfind("frames/flat_blade_0", 0) == 0) {
      ++frames;
      continue;
    }
    list += (list.empty() ? "" : ", ") + name;
  }
  if (frames > 0) list += " (" + std::to_string(frames) + " frames)";
  return list;
}

// summary.csv holds numbers only: the rotation condition at the blade as a code.
double blade_rotation_code(const std::string& rotation) {
  return rotation == "free" ? 0.0 : rotation == "held" ? 1.0 : 2.0;
}
}  // namespace

int main(int argc, char** argv) {
  if (const auto dem_exit = flat_blade_dem::run_if_requested(argc, argv)) return *dem_exit;
  flat_blade::Case c;
  io::Options options(program,
                      "The flat blade of Coetzee (2014): a vertical blade pushed through a layer "
                      "of corn grains, nonpolar or polar MPM, against Sokolovski's passive "
                      "earth pressure. Defaults are the paper's Table 1 (h = 250 mm, 120 x 70 "
                      "cells); the paper's cases are in examples/03_flat_blade/cases/.");
  std::optional<io::RunDirectory> folder;
#ifdef SIGXFSZ
  // Beyond a file-size limit (ulimit -f) a write then fails with EFBIG, which the writers
  // report, instead of the signal killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  try {
    flat_blade::declare_options(options, c);
    if (options.parse(argc, argv) == io::Options::Outcome::help) {
      std::fputs(options.help().c_str(), stdout);
      std::printf("\nCompositions built in:%s\n", flat_blade::compositions_text().c_str());
      return 0;
    }
    flat_blade::validate(options, c);
    const auto composition = flat_blade::find_composition(c);
    flat_blade::check_memory(c, options);
    const fs::path out = c.output_directory.empty() ? fs::path("out/flat_blade") / c.tag()
                                                    : fs::path(c.output_directory);
    const std::string parameters =
        options.case_text(std::string(program) + " (cosmpm " + version_text() +
                          "): the settings of a run.\nRun it again: " + program +
                          " --case case.used --out NEW_FOLDER");
    if (c.restart) check_restart_settings(out, parameters);

    std::printf("flat blade: %s, h = %.0f mm, mesh %ldx%ld, psi = %g deg, delta = %g deg\n",
                c.polar                          ? "polar (Cosserat Drucker-Prager)"
                : c.material == "drucker-prager" ? "nonpolar (Drucker-Prager)"
                                                 : "nonpolar (Mohr-Coulomb)",
                c.soil_depth * 1000, c.cells_x, c.cells_y, c.dilatancy_angle_deg,
                c.wall_friction_deg);
    if (c.polar) {
      std::printf("  micro-inertia J = %g m^2, x %g in the dynamics%s\n", c.micro_inertia,
                  c.micro_inertia_scale,
                  c.micro_inertia_scale != 1.0
                      ? " (quasi-static scaling, --micro-inertia-scale: a shorter run, the "
                        "draft within 0.03 %)"
                      : "");
    }
    if (c.separation) {
      std::printf("  separation: stress-free where the grains came apart, until compressed\n");
    }
    if (c.polar) {
      std::printf("  rotation at the blade: %s", c.blade_rotation.c_str());
      if (c.blade_rotation == "coupled") {
        std::printf(" (wall friction on the slip v_t - r w, r = %g mm)", c.grain_radius * 1000);
      }
      std::printf("\n");
    }
    if (c.dilatancy_cutoff > 0.0) {
      std::printf("  dilatancy cut-off: psi = 0 from a plastic shear strain of %g\n",
                  c.dilatancy_cutoff);
    }
    if (c.floor == "friction") {
      std::printf("  rig floor: Coulomb friction, %g deg\n", c.floor_friction_deg);
    }
    if (c.rig_angle_deg != 0.0) {
      const flat_blade::Rig rig(c);
      std::printf(
          "  rig turned %g deg against the grid (%ld x %ld cells), floor and sides as "
          "rigid bodies; forces in rig axes\n",
          c.rig_angle_deg, static_cast<long>(rig.grid().cells(0)),
          static_cast<long>(rig.grid().cells(1)));
    }
    if (c.start_of_step_contact) std::printf("  contact corrects the start-of-step velocity\n");
    if (c.gap_check) std::printf("  contact checks the gap between blade and particles\n");
    if (c.shape != "linear" || c.integrator != "musl" || c.transfer != "flip-blend" ||
        c.antilocking != "none") {
      std::printf("  shape functions %s, integrator %s, transfer %s, anti-locking %s\n",
                  c.shape.c_str(), c.integrator.c_str(), c.transfer.c_str(), c.antilocking.c_str());
    }
    io::StopRequest stop;
    const auto mode = c.restart   ? io::RunDirectory::Mode::resume
                      : c.replace ? io::RunDirectory::Mode::replace
                                  : io::RunDirectory::Mode::fresh;
    flat_blade::RunContext context{
        options, parameters,
        [&]() -> io::RunDirectory& {
          folder.emplace(out, mode, program,
                         options.given("out") ? "--out" : "--out (default out/flat_blade/<tag>)");
          return *folder;
        },
        stop};
    const flat_blade::Outcome o = std::visit(
        [&](auto composition_type) { return flat_blade::run(c, context, composition_type); },
        composition);
    if (o.checked) {
      std::printf(
          "case checked: %ld particles, %ld steps of %.3g s; at least %.0f s of "
          "computing on %d thread(s); nothing written\n",
          o.particles, o.steps, o.time_step, o.run_seconds, resolve_thread_count(c.threads));
      return 0;
    }
    if (o.stopped) {
      std::printf(
          "stopped by %s at %.2f mm of travel (t = %.6g s, step %ld); checkpoint written.\n"
          "Continue with the same options and --restart true.\n",
          stop.signal_name(), o.travel * 1000, static_cast<double>(o.steps) * o.time_step, o.steps);
      if (o.overrun_particles > 0) {
        std::printf("  %ld particles (%.3g kg/m) ended inside or behind the blade, passed over\n",
                    o.overrun_particles, o.overrun_mass);
      }
      std::printf("results in %s: %s\n", out.c_str(), written_list(*folder).c_str());
      return stop.exit_status();
    }
    const double difference =
        100.0 * (o.average_draft_per_width - o.sokolovski_per_width) / o.sokolovski_per_width;
    {
      io::CsvWriter summary(folder->claim("summary.csv"), {"depth_m",
                                                           "cells_x",
                                                           "cells_y",
                                                           "polar",
                                                           "average_draft_N_per_m",
                                                           "average_vertical_N_per_m",
                                                           "sokolovski_draft_N_per_m",
                                                           "sokolovski_vertical_N_per_m",
                                                           "difference_percent",
                                                           "particles",
                                                           "steps",
                                                           "time_step_s",
                                                           "run_seconds",
                                                           "rig_width_m",
                                                           "average_from_m",
                                                           "average_to_m",
                                                           "profile_at_m",
                                                           "blade_face_x_m",
                                                           "blade_speed_m_per_s",
                                                           "cutting_start_s",
                                                           "stray_particles",
                                                           "stray_mass_kg_per_m",
                                                           "overrun_particles",
                                                           "overrun_mass_kg_per_m",
                                                           "micro_inertia_scale",
                                                           "blade_rotation_0free_1held_2coupled",
                                                           "grain_radius_m",
                                                           "max_rotation_rad",
                                                           "max_couple_stress_N_per_m",
                                                           "separated_particles",
                                                           "rig_angle_deg",
                                                           "rig_origin_x_m",
                                                           "rig_origin_y_m"});
      summary.write_row({c.soil_depth,
                         static_cast<double>(c.cells_x),
                         static_cast<double>(c.cells_y),
                         c.polar ? 1.0 : 0.0,
                         o.average_draft_per_width,
                         o.average_vertical_per_width,
                         o.sokolovski_per_width,
                         o.sokolovski_vertical_per_width,
                         difference,
                         static_cast<double>(o.particles),
                         static_cast<double>(o.steps),
                         o.time_step,
                         o.run_seconds,
                         c.rig_width,
                         c.average_from,
                         c.average_to,
                         c.profile_at,
                         c.blade_start + c.blade_thickness,
                         c.blade_speed,
                         c.equilibrium_time,
                         static_cast<double>(o.stray_particles),
                         o.stray_mass,
                         static_cast<double>(o.overrun_particles),
                         o.overrun_mass,
                         c.polar ? c.micro_inertia_scale : 0.0,
                         c.polar ? blade_rotation_code(c.blade_rotation) : 0.0,
                         c.polar && c.blade_rotation == "coupled" ? c.grain_radius : 0.0,
                         o.max_rotation,
                         o.max_couple_stress,
                         static_cast<double>(o.separated_particles),
                         c.rig_angle_deg,
                         flat_blade::Rig(c).origin()[0],
                         flat_blade::Rig(c).origin()[1]});
    }
    std::printf("  %ld particles, %ld steps of %.3g s, %.1f s of computing\n", o.particles, o.steps,
                o.time_step, o.run_seconds);
    if (c.polar) {
      std::printf("  at the end: largest Cosserat rotation %.3g rad, couple stress %.3g N/m\n",
                  o.max_rotation, o.max_couple_stress);
    }
    if (c.separation) {
      std::printf("  at the end: %ld particles with their grains apart (stress-free)\n",
                  o.separated_particles);
    }
    std::printf(
        "  average draft over %.0f-%.0f mm of travel: %.1f N/m (%.2f N for the %.0f mm rig)\n",
        c.average_from * 1000, c.average_to * 1000, o.average_draft_per_width,
        o.average_draft_per_width * c.rig_width, c.rig_width * 1000);
    std::printf("  Sokolovski (method of characteristics):     %.1f N/m (%.2f N); MPM %+.1f %%\n",
                o.sokolovski_per_width, o.sokolovski_per_width * c.rig_width, difference);
    std::printf("  average vertical force: %.1f N/m (Sokolovski %.1f N/m)\n",
                o.average_vertical_per_width, o.sokolovski_vertical_per_width);
    if (o.stray_particles > 0) {
      std::printf("  %ld particles (%.3g kg/m) left the rig and were %s\n", o.stray_particles,
                  o.stray_mass, c.stray_particles == "freeze" ? "frozen" : "removed");
    }
    std::printf("results in %s: %s\n", out.c_str(), written_list(*folder).c_str());
    return 0;
  } catch (const Error& error) {
    std::fprintf(stderr, "\nerror: %s\n", error.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "\nerror: out of memory (the case needs about %s particles); coarsen --mesh or "
                 "lower --particles-per-cell\n",
                 flat_blade::number(flat_blade::seeded_particles(c)).c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "\nerror: %s\n", error.what());
  }
  if (folder) {
    const std::string list = written_list(*folder);
    if (!list.empty())
      std::fprintf(stderr, "files written before the error in %s: %s\n", folder->path().c_str(),
                   list.c_str());
  }
  return 1;
}
