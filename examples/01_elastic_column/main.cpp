// Example 01: an elastic soil column settling under its own weight.
//
// The smallest complete cosmpm program: compose a simulation from policies, seed particles,
// set boundary conditions, relax to equilibrium with local damping and compare with the
// analytic solution sigma_yy = -rho g (H - y), settlement rho g H^2 / (2 M).
//
//   example_01_elastic_column [cells_over_height=32] [out_dir=out/01_elastic_column]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cosmpm/cosmpm.hpp"

int main(int argc, char** argv) {
  using namespace cosmpm;
  try {
    const long cells = argc > 1 ? std::stol(argv[1]) : 32;
    const std::filesystem::path out = argc > 2 ? argv[2] : "out/01_elastic_column";
    require_in_range("example_01 argument 1", "cells_over_height", static_cast<double>(cells), 2,
                     4096, Bounds::closed);
    std::filesystem::create_directories(out);

    // Corn of the paper's Table 1, elastic only: E = 2.76 MPa, nu = 0.2, rho = 778 kg/m^3.
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

    const double dt = sim.time_step();
    const double end = 120.0 * height / std::sqrt(model.p_wave_modulus() / density);
    io::ProgressReporter progress("column", end, sim.particles().size());
    while (sim.time() < end) {
      sim.step(dt);
      progress.update(sim.time(), sim.step_count());
    }
    progress.finish(sim.time(), sim.step_count());

    const auto& x0 = sim.particles().get<particles::field::InitialPosition<2>>();
    const auto& x = sim.particles().get<particles::field::Position<2>>();
    const auto& stress = sim.particles().get<particles::field::Stress<material::LinearElastic<>>>();
    std::ofstream csv(out / "column_profile.csv");
    csv << "y0,sigma_yy,sigma_yy_exact,settlement,settlement_exact\n";
    double max_error = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) {
      const double y = x0[p][1];
      const double exact = -density * gravity * (height - y);
      const double settlement_exact =
          density * gravity * (height * y - 0.5 * y * y) / model.p_wave_modulus();
      csv << y << ',' << stress[p][1] << ',' << exact << ',' << (y - x[p][1]) << ','
          << settlement_exact << '\n';
      max_error = std::max(max_error, std::abs(stress[p][1] - exact));
    }
    const double top_exact = density * gravity * height * height / (2.0 * model.p_wave_modulus());
    std::printf("elastic column, %ld cells over %.3f m, %ld particles, %ld steps\n", cells, height,
                static_cast<long>(sim.particles().size()), static_cast<long>(sim.step_count()));
    std::printf("  max |sigma_yy - exact| = %.4g Pa (%.2f %% of rho g H)\n", max_error,
                100.0 * max_error / (density * gravity * height));
    std::printf("  analytic top settlement rho g H^2 / (2 M) = %.6g m\n", top_exact);
    std::printf("  profile written to %s\n", (out / "column_profile.csv").c_str());
    return 0;
  } catch (const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
