// Example 01: an elastic soil column settling under its own weight.
//
// The smallest complete cosmpm program: compose a simulation from policies, seed particles,
// set boundary conditions, relax to equilibrium with local damping and compare with the
// analytic solution sigma_yy = -rho g (H - y), settlement rho g (H y - y^2 / 2) / M.
//
//   example_01_elastic_column [--cells 32] [--out out/01_elastic_column] [--replace true]
//   example_01_elastic_column --help
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "cosmpm/cosmpm.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"

int main(int argc, char** argv) {
  using namespace cosmpm;
  long cells = 32;
  std::string out = "out/01_elastic_column";
  bool replace = false;
  io::Options options("example_01_elastic_column",
                      "An elastic column of corn (E = 2.76 MPa, nu = 0.2, rho = 778 kg/m^3, "
                      "H = 0.35 m) settling under its own weight, against the analytic "
                      "stress and settlement. Writes column_profile.csv.");
  options.group("Numerics");
  options.integer("cells", cells, 2, 4096, "cells over the column's height");
  options.group("Run control");
  options.text("out", out, "DIR", "output folder", io::Options::Role::control);
  options.flag("replace", replace, "delete an earlier run's results in the output folder first",
               io::Options::Role::control);
#ifdef SIGXFSZ
  // Beyond a file-size limit (ulimit -f) a write then fails with EFBIG, which the writers
  // report, instead of the signal killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  try {
    if (options.parse(argc, argv) == io::Options::Outcome::help) {
      std::fputs(options.help().c_str(), stdout);
      return 0;
    }
    // Corn of the paper's Table 1, elastic only.
    const double height = 0.35, density = 778.0, gravity = 9.81;
    const material::LinearElastic<> model(2.76e6, 0.2);
    const double h = height / static_cast<double>(cells);
    const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(2.0 * h, height + 2.0 * h), {2, cells + 2});

    using Sim = Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<>>,
                           contact::SingleField, integrator::USL>;
    SimulationParameters<2> parameters;
    parameters.gravity = Vec<2>(0.0, -gravity);
    parameters.damping = 0.3;  // local damping: we want the static state, not the waves
    Sim sim(grid, model, parameters);
    const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(2.0 * h, height), 2);
    sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
    using BC = grid::BoundaryConditions<2>;
    sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::roller);
    sim.boundary_conditions().set(BC::face(0, true), grid::BoundaryKind::roller);
    sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::fixed);

    // The output folder is checked (and locked) before the run, not after it.
    io::RunDirectory folder(
        out, replace ? io::RunDirectory::Mode::replace : io::RunDirectory::Mode::fresh,
        "example_01_elastic_column", options.given("out") ? "--out" : "--out (default)");
    io::StopRequest stop;
    const double dt = sim.time_step();
    const double end = 120.0 * height / std::sqrt(model.p_wave_modulus() / density);
    io::ProgressReporter progress("column", end, sim.particles().size());
    while (sim.time() < end && !stop.requested()) {
      sim.step(dt);
      progress.update(sim.time(), sim.step_count());
    }
    progress.finish(sim.time(), sim.step_count());
    if (stop.requested()) {
      std::printf("stopped by %s at t = %g s of %g s; nothing written\n", stop.signal_name(),
                  sim.time(), end);
      return stop.exit_status();
    }

    const auto& x0 = sim.particles().get<particles::field::InitialPosition<2>>();
    const auto& x = sim.particles().get<particles::field::Position<2>>();
    const auto& stress = sim.particles().get<particles::field::Stress<material::LinearElastic<>>>();
    std::vector<std::vector<double>> rows;
    double max_error = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) {
      const double y = x0[p][1];
      const double exact = -density * gravity * (height - y);
      const double settlement_exact =
          density * gravity * (height * y - 0.5 * y * y) / model.p_wave_modulus();
      rows.push_back({y, stress[p][1], exact, y - x[p][1], settlement_exact});
      max_error = std::max(max_error, std::abs(stress[p][1] - exact));
    }
    const auto profile = folder.claim("column_profile.csv");
    io::write_csv(
        profile, {"y0_m", "sigma_yy_Pa", "sigma_yy_exact_Pa", "settlement_m", "settlement_exact_m"},
        rows);
    const double top_exact = density * gravity * height * height / (2.0 * model.p_wave_modulus());
    std::printf("elastic column, %ld cells over %.3f m, %ld particles, %ld steps\n", cells, height,
                static_cast<long>(sim.particles().size()), static_cast<long>(sim.step_count()));
    std::printf(
        "  max |sigma_yy - exact| = %.4g Pa (%.2f %% of rho g H; stress tension "
        "positive)\n",
        max_error, 100.0 * max_error / (density * gravity * height));
    std::printf("  analytic top settlement rho g H^2 / (2 M) = %.6g m\n", top_exact);
    std::printf("results in %s: column_profile.csv\n", folder.path().c_str());
    return 0;
  } catch (const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory; lower --cells\n");
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  }
  return 1;
}
