// Example 03: the flat blade of Coetzee (2014) pushed through corn grains, nonpolar
// (Mohr-Coulomb) or polar (Cosserat Drucker-Prager) MPM, from one driver.
//
//   example_03_flat_blade [--case FILE] [--depth 0.25] [--mesh 120x70] [--polar true] ...
//   example_03_flat_blade --help
//
// Writes to out/flat_blade/<tag>/: forces.csv (draft and vertical force against blade
// travel), blade_stress.csv (normal and shear traction along the blade at --profile-at),
// sokolovski_wall.csv and sokolovski_slip_line.csv (the reference), summary.csv, and
// frames/flat_blade.xdmf (ParaView) with one HDF5 frame per --frame-interval of travel.
// scripts/plot_flat_blade.py turns them into PNG plots.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>

#include "case.hpp"
#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/cosmpm.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "dem_flat_blade.hpp"

namespace {
using namespace cosmpm;
namespace fs = std::filesystem;

// MUSL, not the paper's USL: USL strains a particle with v_i + dt f_i / m_i, which grows
// without bound at nodes of tiny mass; at the blade's top corner that blew a surface particle
// off after 8 mm of travel (docs/theory/mpm.md, "Which to use").
using NonpolarSoil = material::MohrCoulomb<>;
using PolarSoil = material::CosseratDruckerPrager<>;
using NonpolarSim = Simulation<2, shape::Linear, continuum::Classical<NonpolarSoil>,
                               contact::RigidContact<2>, integrator::MUSL>;
using PolarSim = Simulation<2, shape::Linear, continuum::Cosserat<PolarSoil>,
                            contact::RigidContact<2>, integrator::MUSL>;

struct Outcome {
  double average_draft_per_width = 0.0;     // N/m over [average_from, average_to]
  double average_vertical_per_width = 0.0;  // N/m
  double sokolovski_per_width = 0.0;
  double sokolovski_vertical_per_width = 0.0;
  double run_seconds = 0.0;
  long steps = 0;
  long particles = 0;
  double time_step = 0.0;
};

NonpolarSoil make_model(const flat_blade::Case& c, std::false_type) {
  return NonpolarSoil(c.youngs_modulus, c.poisson_ratio, c.friction_angle_deg,
                      c.dilatancy_angle_deg, c.cohesion);
}
PolarSoil make_model(const flat_blade::Case& c, std::true_type) {
  const double shear = c.youngs_modulus / (2.0 * (1.0 + c.poisson_ratio));
  using material::DruckerPragerMatching;
  const DruckerPragerMatching cone = c.cone == "plane-strain" ? DruckerPragerMatching::plane_strain
                                     : c.cone == "outer"      ? DruckerPragerMatching::outer
                                     : c.cone == "inner"
                                         ? DruckerPragerMatching::inner
                                         : DruckerPragerMatching::plane_strain_per_angle;
  return PolarSoil(c.youngs_modulus, c.poisson_ratio, c.cosserat_shear_ratio * shear,
                   c.characteristic_length, c.friction_angle_deg, c.dilatancy_angle_deg, c.cohesion,
                   {}, cone);
}

template <class Sim>
Outcome run(const flat_blade::Case& c, const fs::path& out) {
  constexpr bool polar = Sim::is_cosserat;
  using Model = typename Sim::model_type;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(c.grid_length, c.grid_height),
                           {c.cells_x, c.cells_y});

  // The blade: a thin rectangle standing on the rig floor, still while the layer settles,
  // then moving at the blade speed. Its right edge (index 1) is the face that cuts.
  const double face_x = c.blade_start + c.blade_thickness;
  const double start_time = c.equilibrium_time;
  const double speed = c.blade_speed;
  auto blade =
      contact::RigidBody<2>::box(Vec<2>(c.blade_start, 0.0), Vec<2>(face_x, c.blade_height));
  blade.set_velocity(contact::RigidBody<2>::VelocityLaw(
      [start_time, speed](double t) { return Vec<2>(t < start_time ? 0.0 : speed, 0.0); }));
  contact::RigidContact<2> blade_contact;
  blade_contact.set_start_of_step_correction(c.start_of_step_contact);
  blade_contact.set_gap_check(c.gap_check);
  blade_contact.add_body(std::move(blade),
                         contact::Interface::coulomb_angle(c.wall_friction_deg)
                             .with_rotation_held(polar && c.blade_rotation_fixed));
  constexpr int blade_body = 0;
  constexpr int cutting_face = 1;

  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -c.gravity);
  parameters.damping = c.equilibrium_damping;
  parameters.flip_fraction = c.flip_fraction;
  parameters.cfl = c.cfl;
  parameters.threads = c.threads;
  using Continuum = typename Sim::continuum_type;
  const Continuum continuum = [&] {
    if constexpr (polar) {
      // Rotation held on the rig floor and sides, as the paper does.
      using BC = grid::BoundaryConditions<2>;
      continuum::CosseratSettings settings{.micro_inertia = c.micro_inertia};
      for (int face : {BC::face(1, false), BC::face(0, false), BC::face(0, true)}) {
        settings.rotation_fixed[static_cast<std::size_t>(face)] = true;
      }
      return Continuum(make_model(c, std::true_type{}), settings);
    } else {
      return Continuum(make_model(c, std::false_type{}));
    }
  }();
  Sim sim(grid, continuum, parameters, std::move(blade_contact));

  // The soil layer in front of the blade, at rest under K0 = 1 - sin(phi) (Jaky).
  const auto soil =
      particles::seed_box(grid, Vec<2>(face_x, 0.0), Vec<2>(c.grid_length, c.soil_depth),
                          static_cast<int>(c.particles_per_cell));
  sim.add_particles(soil.positions, soil.volume, c.density, soil.half_width);
  const double k0 = initial::jaky_k0(c.friction_angle_deg);
  {
    const auto& x = sim.particles().template get<particles::field::Position<2>>();
    auto& stress = sim.particles().template get<particles::field::Stress<Model>>();
    for (Index p = 0; p < sim.particles().size(); ++p) {
      const double depth = c.soil_depth - x[p][1];
      if constexpr (polar) {
        stress[p] = initial::geostatic_cosserat_stress(c.density, c.gravity, depth, k0);
      } else {
        stress[p] = initial::geostatic_stress(c.density, c.gravity, depth, k0);
      }
    }
  }
  using BC = grid::BoundaryConditions<2>;
  auto& bc = sim.boundary_conditions();
  if (c.floor == "friction") {
    bc.set(BC::face(1, false), grid::BoundaryKind::friction,
           std::tan(c.floor_friction_deg * std::numbers::pi / 180.0));
  } else {
    bc.set(BC::face(1, false), grid::BoundaryKind::fixed);  // rig floor, the paper's
  }
  bc.set(BC::face(0, false), grid::BoundaryKind::roller);
  bc.set(BC::face(0, true), grid::BoundaryKind::roller);

  // The reference: Sokolovski's passive pressure on a vertical wall of height h.
  const auto reference = analysis::sokolovski_passive({.friction_angle_deg = c.friction_angle_deg,
                                                       .wall_friction_deg = c.wall_friction_deg,
                                                       .unit_weight = c.density * c.gravity,
                                                       .height = c.soil_depth,
                                                       .cohesion = c.cohesion});
  {
    io::CsvWriter wall(out / "sokolovski_wall.csv",
                       {"depth_m", "normal_pressure_Pa", "shear_stress_Pa"});
    for (const auto& w : reference.wall) {
      wall.write_row({w.depth, w.normal_pressure, w.shear_stress});
    }
    io::CsvWriter slip(out / "sokolovski_slip_line.csv", {"distance_m", "depth_m"});
    for (const auto& s : reference.slip_line) slip.write_row({s.distance, s.depth});
  }

  const double dt = sim.time_step();
  const double end_time = start_time + c.travel / speed;
  io::CsvWriter forces(out / "forces.csv", {"time_s", "displacement_m", "draft_N_per_m",
                                            "vertical_N_per_m", "draft_N_rig", "vertical_N_rig"});
  std::optional<io::ParticleFrameWriter> frames;
  if (c.write_frames) frames.emplace(out / "frames", "flat_blade");
  double next_frame = 0.0;  // blade travel of the next frame
  bool profile_written = false;
  double draft_sum = 0.0, vertical_sum = 0.0;
  long averaged_steps = 0;
  // Forces are averaged over the steps between two CSV rows (0.1 mm of travel) so the CSV
  // is smooth but loses nothing; the 15-35 mm average uses every step.
  const double row_interval = 1e-4;
  double next_row = 0.0, row_draft = 0.0, row_vertical = 0.0;
  long row_steps = 0;

  io::ProgressReporter progress(polar ? "flat blade (polar)" : "flat blade (nonpolar)", end_time,
                                sim.particles().size());
  const auto wall_start = std::chrono::steady_clock::now();
  bool cutting = false;
  while (sim.time() < end_time - 0.5 * dt) {
    if (!cutting && sim.time() >= start_time - 0.5 * dt) {
      cutting = true;
      sim.set_damping(c.damping);
      if (frames) frames->write(sim);
      next_frame = c.frame_interval;
    }
    sim.step(dt);
    progress.update(sim.time(), sim.step_count());
    if (!cutting) continue;
    const double travel = (sim.time() - start_time) * speed;
    const Vec<2> force = sim.contact().force_on_material(blade_body);
    row_draft += force[0];
    row_vertical += force[1];
    ++row_steps;
    if (travel >= c.average_from - 1e-12 && travel <= c.average_to + 1e-12) {
      draft_sum += force[0];
      vertical_sum += force[1];
      ++averaged_steps;
    }
    if (travel >= next_row - 1e-12) {
      const double draft = row_draft / static_cast<double>(row_steps);
      const double vertical = row_vertical / static_cast<double>(row_steps);
      forces.write_row(
          {sim.time(), travel, draft, vertical, draft * c.rig_width, vertical * c.rig_width});
      row_draft = row_vertical = 0.0;
      row_steps = 0;
      next_row += row_interval;
    }
    if (!profile_written && travel >= c.profile_at - 1e-12) {
      profile_written = true;
      io::CsvWriter profile(
          out / "blade_stress.csv",
          {"height_above_tip_m", "depth_m", "normal_traction_Pa", "shear_traction_Pa", "nodes"});
      for (const auto& bin : sim.contact().traction_profile(blade_body, cutting_face)) {
        // Edge 1 runs up the face from the tip: `centre` is the height above the tip.
        profile.write_row({bin.centre, c.soil_depth - bin.centre, bin.normal_traction,
                           bin.shear_traction, static_cast<double>(bin.nodes)});
      }
    }
    if (frames && travel >= next_frame - 1e-12) {
      frames->write(sim);
      next_frame += c.frame_interval;
    }
  }
  progress.finish(sim.time(), sim.step_count());
  // The end of travel always gets a frame, even when rounding left it just short.
  if (frames && next_frame - c.frame_interval < c.travel - 1e-9) frames->write(sim);

  Outcome outcome;
  const double averaged = static_cast<double>(averaged_steps);
  outcome.average_draft_per_width = averaged_steps > 0 ? draft_sum / averaged : 0.0;
  outcome.average_vertical_per_width = averaged_steps > 0 ? vertical_sum / averaged : 0.0;
  outcome.sokolovski_per_width = reference.horizontal_force_per_width;
  outcome.sokolovski_vertical_per_width = reference.vertical_force_per_width;
  outcome.run_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  outcome.steps = static_cast<long>(sim.step_count());
  outcome.particles = static_cast<long>(sim.particles().size());
  outcome.time_step = dt;
  return outcome;
}
}  // namespace

int main(int argc, char** argv) {
  if (const auto dem_exit = flat_blade_dem::run_if_requested(argc, argv)) return *dem_exit;
  flat_blade::Case c;
  try {
    flat_blade::Parser parser(c);
    if (!parser.parse_command_line(argc, argv)) {
      parser.print_help(argv[0]);
      return 0;
    }
    flat_blade::validate(c);
    const fs::path out = c.output_directory.empty() ? fs::path("out/flat_blade") / c.tag()
                                                    : fs::path(c.output_directory);
    fs::create_directories(out);
    std::printf("flat blade: %s, h = %.0f mm, mesh %ldx%ld, psi = %g deg, delta = %g deg\n",
                c.polar ? "polar (Cosserat Drucker-Prager)" : "nonpolar (Mohr-Coulomb)",
                c.soil_depth * 1000, c.cells_x, c.cells_y, c.dilatancy_angle_deg,
                c.wall_friction_deg);
    if (c.floor == "friction") {
      std::printf("  rig floor: Coulomb friction, %g deg\n", c.floor_friction_deg);
    }
    if (c.start_of_step_contact) std::printf("  contact corrects the start-of-step velocity\n");
    if (c.gap_check) std::printf("  contact checks the gap between blade and particles\n");
    const Outcome o = c.polar ? run<PolarSim>(c, out) : run<NonpolarSim>(c, out);
    const double difference =
        100.0 * (o.average_draft_per_width - o.sokolovski_per_width) / o.sokolovski_per_width;
    {
      io::CsvWriter summary(out / "summary.csv", {"depth_m",
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
                                                  "cutting_start_s"});
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
                         c.equilibrium_time});
    }
    std::printf("  %ld particles, %ld steps of %.3g s, %.1f s of computing\n", o.particles, o.steps,
                o.time_step, o.run_seconds);
    std::printf(
        "  average draft over %.0f-%.0f mm of travel: %.1f N/m (%.2f N for the %.0f mm rig)\n",
        c.average_from * 1000, c.average_to * 1000, o.average_draft_per_width,
        o.average_draft_per_width * c.rig_width, c.rig_width * 1000);
    std::printf("  Sokolovski (method of characteristics):     %.1f N/m (%.2f N); MPM %+.1f %%\n",
                o.sokolovski_per_width, o.sokolovski_per_width * c.rig_width, difference);
    std::printf("  average vertical force: %.1f N/m (Sokolovski %.1f N/m)\n",
                o.average_vertical_per_width, o.sokolovski_vertical_per_width);
    std::printf("results in %s: forces.csv, blade_stress.csv, summary.csv%s\n", out.c_str(),
                c.write_frames ? ", frames/flat_blade.xdmf (ParaView)" : "");
    return 0;
  } catch (const Error& error) {
    std::fprintf(stderr, "\nerror: %s\n", error.what());
    return 1;
  }
}
