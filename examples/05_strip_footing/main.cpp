// Prandtl's strip footing on a weightless Tresca layer: the verification case of volumetric
// anti-locking (antilocking::FBar). A rigid footing is pushed into a nearly incompressible
// (nu = 0.49) Tresca layer at a constant slow velocity; its pressure against settlement is
// compared with the collapse pressure (2 + pi) c, on several meshes, with and without F-bar.
// Writes one CSV per mesh and policy (settlement / B, pressure / c) and summary.csv (the limit
// pressure of each run: the mean over the last fifth of the settlement); plot them with
//   /usr/bin/python3 scripts/plot_strip_footing.py OUT_DIR
// See docs/verification/strip_footing.md.
//
//   example_05_strip_footing [--meshes 4,8,16] [--antilocking both|none|fbar]
//                            [--footing smooth|rough] [--velocity M/S] [--settlement S/B] ...
//   example_05_strip_footing --help
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "footing.hpp"

namespace {

namespace io = cosmpm::io;
using cosmpm::Bounds;

struct Settings {
  strip_footing::Case base;
  std::vector<int> meshes{4, 8, 16};  // cells per footing half-width b
  std::string antilocking = "both";
  std::string footing = "smooth";
  std::string shape = "linear";
  // The limit pressure: the mean over settlements in [limit_from, limit_to] B, after the
  // collapse (the plateau starts near 0.025 B on every mesh) and before the footing has sunk
  // far (unset: to the end of the run).
  double limit_from = 0.04;
  double limit_to = -1;
  std::string out = "strip_footing";
  bool replace = false;
};

void declare(io::Options& o, Settings& s) {
  strip_footing::Case& c = s.base;
  const io::RealRange positive = io::RealRange::positive();
  o.group("Meshes and policies");
  o.custom(
      "meshes", "N,N,...", "cells per footing half-width b, one run per value (h = B / (2 N))",
      "whole numbers in [1, 256]",
      [&s](std::string_view value, const std::string& where) {
        s.meshes.clear();
        std::size_t start = 0;
        while (start <= value.size()) {
          const std::size_t comma = std::min(value.find(',', start), value.size());
          const std::string item(value.substr(start, comma - start));
          std::size_t used = 0;
          int n = 0;
          try {
            n = std::stoi(item, &used);
          } catch (const std::exception&) {
            used = 0;
          }
          if (used == 0 || used != item.size() || n < 1 || n > 256) {
            throw cosmpm::Error(where + " = '" + std::string(value) + "': '" + item +
                                "' is not a whole number in the valid range [1, 256]");
          }
          s.meshes.push_back(n);
          start = comma + 1;
        }
      },
      [&s] {
        std::string text;
        for (const int n : s.meshes) {
          if (!text.empty()) text += ',';
          text += std::to_string(n);
        }
        return text;
      });
  o.choice("antilocking", s.antilocking, {"both", "none", "fbar"},
           "volumetric anti-locking: both (each mesh without and with F-bar), none or fbar");
  o.choice("footing", s.footing, {"smooth", "rough"},
           "footing base: smooth (frictionless contact) or rough (no slip); both collapse at "
           "(2 + pi) c on a weightless layer");
  o.choice("shape", s.shape, {"linear", "gimp"},
           "shape functions: linear (bilinear, the paper's) or gimp (uGIMP: smoother cell "
           "crossings)");
  o.group("Soil (Tresca: MohrCoulomb with phi = psi = 0)");
  o.real("cohesion", c.cohesion, positive, "Pa", "undrained strength c");
  o.real("stiffness-ratio", c.stiffness_ratio, positive, "", "E / c");
  o.real("poisson-ratio", c.poisson_ratio, {-1.0, 0.5}, "", "Poisson's ratio (undrained: -> 0.5)");
  o.real("density", c.density, positive, "kg/m^3", "density (weightless: sets the time scale)");
  o.group("Geometry and loading");
  o.real("width", c.width, positive, "m", "footing width B");
  o.real("half-domain", c.half_domain, {1.5, 100.0, Bounds::closed}, "B",
         "soil half-width from the axis");
  o.real("depth", c.depth, {0.75, 100.0, Bounds::closed}, "B", "soil depth");
  o.real("velocity", c.velocity, positive, "m/s", "footing velocity");
  o.real("settlement", c.settlement, {0.0, 0.5, Bounds::right_closed}, "B", "final settlement");
  o.real("sample-every", c.sample_every, positive, "B",
         "settlement between samples of the averaged pressure");
  o.real("limit-from", s.limit_from, {0.0, 0.5, Bounds::left_closed}, "B",
         "the limit pressure is the mean over settlements from here to --limit-to");
  o.real("limit-to", s.limit_to, {-1.0, 0.5, Bounds::closed}, "B",
         "end of the limit pressure's window (-1: --settlement)");
  o.group("Numerics");
  o.real("damping", c.damping, {0.0, 1.0, Bounds::left_closed}, "", "Cundall local damping");
  o.flag("gap-check", c.gap_check,
         "contact only where the material would reach the footing within the step");
  o.flag("start-of-step-contact", c.start_of_step_contact,
         "contact also corrects the start-of-step velocity (Nairn, Hammerquist and Smith 2020)");
  o.real("flip", c.flip_fraction, {0.0, 1.0, Bounds::closed}, "",
         "FLIP fraction of the PIC/FLIP velocity blend");
  o.integer("particles-per-cell", c.particles_per_cell, 1, 8, "particles per cell and direction");
  o.integer("threads", c.threads, 0, 4096, "OpenMP threads (0: OpenMP's default)",
            io::Options::Role::control);
  o.group("Output");
  o.text("out", s.out, "DIR", "output folder", io::Options::Role::control);
  o.flag("replace", s.replace, "replace an earlier run's files in --out",
         io::Options::Role::control);
}

struct Row {
  int cells = 0;
  std::string policy;
  double limit = 0.0;
  strip_footing::Result result;
  double seconds = 0.0;
};

// One run, its curve written sample by sample (an unstable run keeps what it wrote).
template <class AntiLocking, class Kernel>
Row run_one(const strip_footing::Case& c, const std::string& policy, double from, double to,
            io::RunDirectory& folder) {
  char name[64];
  std::snprintf(name, sizeof name, "strip_footing b/h=%d %s", c.cells_per_half_width,
                policy.c_str());
  const double end_time = c.settlement * c.width / c.velocity;
  io::ProgressReporter progress(name, end_time, strip_footing::particle_count(c));
  char file[64];
  std::snprintf(file, sizeof file, "curve_n%d_%s.csv", c.cells_per_half_width, policy.c_str());
  io::CsvWriter curve(folder.claim(file),
                      {"settlement_over_B", "pressure_over_c", "stress_pressure_over_c"});
  const auto start = std::chrono::steady_clock::now();
  Row row;
  row.cells = c.cells_per_half_width;
  row.policy = policy;
  row.result = strip_footing::run<AntiLocking, Kernel>(
      c, {.progress = [&](double time, double, std::int64_t step) { progress.update(time, step); },
          .sample =
              [&](const strip_footing::Sample& sample) {
                curve.write_row({sample.settlement, sample.pressure, sample.stress_pressure});
              }});
  progress.finish(end_time, row.result.steps);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.limit = strip_footing::mean_pressure(row.result.curve, from, to);
  std::vector<std::vector<double>> particles;
  for (const auto& p : row.result.final_particles) {
    particles.push_back({p.position[0], p.position[1], p.displacement[0], p.displacement[1],
                         p.plastic_shear_strain, p.volume_ratio, p.mean_stress});
  }
  std::snprintf(file, sizeof file, "particles_n%d_%s.csv", c.cells_per_half_width, policy.c_str());
  io::write_csv(
      folder.claim(file),
      {"x_m", "y_m", "ux_m", "uy_m", "plastic_shear_strain", "volume_ratio", "mean_stress_over_c"},
      particles);
  return row;
}

int run(const Settings& s, const io::Options& options) {
  strip_footing::Case c = s.base;
  c.rough = s.footing == "rough";
  strip_footing::validate(c);
  const double limit_to = s.limit_to < 0 ? c.settlement : s.limit_to;
  if (!(s.limit_from < limit_to && limit_to <= c.settlement)) {
    throw cosmpm::Error("--limit-from = " + cosmpm::detail::format_number(s.limit_from) +
                        " B and --limit-to = " + cosmpm::detail::format_number(limit_to) +
                        " B: the window must satisfy limit-from < limit-to <= --settlement = " +
                        cosmpm::detail::format_number(c.settlement) + " B");
  }
  io::RunDirectory folder(
      s.out, s.replace ? io::RunDirectory::Mode::replace : io::RunDirectory::Mode::fresh,
      "example_05_strip_footing", options.given("out") ? "--out" : "--out (default)");
  std::printf(
      "Strip footing on a weightless Tresca layer: %s footing, B = %g m, c = %g Pa, E = %g c, "
      "nu = %g,\nvelocity %g m/s to a settlement of %g B, damping %g, FLIP fraction %g, %s "
      "shape functions; (2 + pi) c = %.4f c\n",
      s.footing.c_str(), c.width, c.cohesion, c.stiffness_ratio, c.poisson_ratio, c.velocity,
      c.settlement, c.damping, c.flip_fraction, s.shape.c_str(), strip_footing::prandtl_factor);
  std::printf("%6s %10s %8s %10s %12s %10s %10s %9s\n", "b/h", "h/B", "policy", "q/c", "error [%]",
              "particles", "steps", "time [s]");
  std::vector<std::vector<double>> summary;
  // Printed and written after every run, so a stopped sweep keeps what it finished.
  const auto report = [&](const Row& row) {
    const double error = 100 * (row.limit / strip_footing::prandtl_factor - 1);
    std::printf("%6d %10.5f %8s %10.4f %+12.2f %10ld %10ld %9.1f\n", row.cells, c.cell() / c.width,
                row.policy.c_str(), row.limit, error, static_cast<long>(row.result.particles),
                static_cast<long>(row.result.steps), row.seconds);
    std::fflush(stdout);
    summary.push_back({static_cast<double>(row.cells), c.cell() / c.width,
                       row.policy == "fbar" ? 1.0 : 0.0, row.limit, error,
                       static_cast<double>(row.result.particles),
                       static_cast<double>(row.result.steps), row.seconds});
    io::write_csv(folder.claim("summary.csv"),
                  {"cells_per_half_width", "h_over_B", "fbar", "limit_pressure_over_c",
                   "error_percent", "particles", "steps", "seconds"},
                  summary);
  };
  const auto sweep = [&]<class Kernel>() {
    for (const int n : s.meshes) {
      c.cells_per_half_width = n;
      if (s.antilocking != "fbar") {
        report(
            run_one<cosmpm::antilocking::None, Kernel>(c, "none", s.limit_from, limit_to, folder));
      }
      if (s.antilocking != "none") {
        report(
            run_one<cosmpm::antilocking::FBar, Kernel>(c, "fbar", s.limit_from, limit_to, folder));
      }
    }
  };
  if (s.shape == "gimp") {
    sweep.template operator()<cosmpm::shape::GIMP>();
  } else {
    sweep.template operator()<cosmpm::shape::Linear>();
  }
  std::printf(
      "limit pressure: mean q / c over settlements in [%g, %g] B\nCSV files in %s\n"
      "Plot: /usr/bin/python3 scripts/plot_strip_footing.py %s\n",
      s.limit_from, limit_to, folder.path().c_str(), folder.path().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  io::Options options("example_05_strip_footing",
                      "Prandtl's strip footing on a weightless Tresca layer, with and without "
                      "F-bar anti-locking, on several meshes; the collapse pressure is "
                      "(2 + pi) c. Writes the pressure-settlement curves and a summary as CSV.");
#ifdef SIGXFSZ
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  try {
    declare(options, settings);
    if (options.parse(argc, argv) == io::Options::Outcome::help) {
      std::fputs(options.help().c_str(), stdout);
      return 0;
    }
    return run(settings, options);
  } catch (const cosmpm::Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  }
  return 1;
}
