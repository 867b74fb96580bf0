// Example 06: the flat blade of Coetzee (2014) in 3D, between the rig's glass side walls.
// The paper's rig is 200 mm wide between glass panels; its plane-strain models cannot see the
// corn's friction on the glass, which it names as one cause of its MPM drafts lying 9-25 %
// below the measured ones (its Sect. 4). Here the soil is a 3D Mohr-Coulomb continuum, the
// blade a rigid box (contact::RigidBody<3>) with Coulomb friction delta, and each glass panel
// a Coulomb friction wall of the grid with friction angle --glass-friction. By default half
// the width is modelled, with a symmetry plane (a roller face) at mid-width.
//
// The composition is the 2D driver's default (example 03): MUSL, linear shape functions, FLIP,
// Mohr-Coulomb with separation, K0 = 1 - sin(phi) settled for 0.25 s with local damping 0.5,
// a fixed floor, 10 mm cells, 2 x 2 x 2 particles per cell; the blade then moves at 10 mm/s.
//
//   example_06_flat_blade_3d [--depth 0.25] [--glass-friction 0] [--width 0.2]
//                            [--half-width true] [--travel 0.035] [--out DIR] ...
//   example_06_flat_blade_3d --help
//
// With --glass-friction 0 the side walls are frictionless and the draft per metre of width is
// the plane-strain draft (the 2D driver's, within 2 %: docs/validation.md, "3D flat blade");
// --width 0.01 then runs a one-cell slab. Writes forces.csv, width_profile.csv (the blade's
// normal force per node column, mean over the drafts' window and at --profile-at),
// blade_traction.csv (at --profile-at), surface.csv (the free surface across the width at the
// end), summary.txt, and frames/flat_blade_3d.xdmf (ParaView) unless --frames false.
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/contact.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/initial/geostatic.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Model = material::MohrCoulomb<double, 3>;
using Sim = Simulation<3, shape::Linear, continuum::Classical<Model>, contact::RigidContact<3>,
                       integrator::MUSL>;
using BC = grid::BoundaryConditions<3>;

struct Case {
  double youngs_modulus = 2.76e6, poisson_ratio = 0.2, density = 778.0;  // corn, Table 1
  double phi = 26.0, psi = 2.0, delta = 14.0;                            // deg
  double glass_friction = 0.0;  // deg, corn on the glass panels
  double depth = 0.25;          // h, m
  double width = 0.2;           // between the glass panels, m
  bool half_width = true;       // model y in [0, width / 2], a symmetry plane at y = 0
  double rig_length = 1.2, rig_height = 0.7;                                           // m
  double blade_height = 0.35, blade_thickness = 0.01, blade_start = 0.05;              // m
  double blade_speed = 0.01;                                                           // m/s
  double travel = 0.035, average_from = 0.015, average_to = 0.035, profile_at = 0.02;  // m
  double cell = 0.01;                                                                  // m
  long particles_per_cell = 2;                                                         // per axis
  double settle_time = 0.25, settle_damping = 0.5, flip = 1.0, cfl = 0.5;
  bool separated_pic = false;     // points whose grains came apart take the grid's velocity
  double frame_interval = 0.005;  // m of travel
  bool frames = true;
  long threads = 0;
  std::string out = "out/06_flat_blade_3d";
  bool replace = false;
};

void declare(io::Options& o, Case& c) {
  using io::RealRange;
  const auto positive = RealRange::positive();
  o.group("Soil and interfaces (corn, Table 1 of Coetzee 2014)");
  o.real("youngs-modulus", c.youngs_modulus, {0.0, 1e12, Bounds::right_closed}, "Pa", "E");
  o.real("poisson-ratio", c.poisson_ratio, {-1.0, 0.5}, "", "nu");
  o.real("density", c.density, {0.0, 1e5, Bounds::right_closed}, "kg/m^3", "rho");
  o.real("phi", c.phi, {0.0, 60.0, Bounds::right_closed}, "deg", "friction angle");
  o.real("psi", c.psi, {0.0, 60.0, Bounds::closed}, "deg", "dilatancy angle, at most --phi");
  o.real("delta", c.delta, {0.0, 60.0, Bounds::closed}, "deg", "soil-blade friction angle");
  o.real("glass-friction", c.glass_friction, {0.0, 90.0, Bounds::left_closed}, "deg",
         "soil-glass friction angle of the side walls (0: frictionless, plane strain)");
  o.group("Rig and blade");
  o.real("depth", c.depth, {0.0, 0.7, Bounds::right_closed}, "m", "soil depth h");
  o.real("width", c.width, positive, "m", "rig width between the glass panels");
  o.flag("half-width", c.half_width, "model half the width with a symmetry plane");
  o.real("rig-length", c.rig_length, positive, "m", "rig length (grid along x)");
  o.real("rig-height", c.rig_height, positive, "m", "grid height");
  o.real("blade-height", c.blade_height, positive, "m", "blade height");
  o.real("blade-speed", c.blade_speed, positive, "m/s", "blade speed");
  o.real("travel", c.travel, positive, "m", "blade travel simulated");
  o.real("average-from", c.average_from, RealRange::non_negative(), "m", "draft average from");
  o.real("average-to", c.average_to, positive, "m", "draft average to");
  o.real("profile-at", c.profile_at, positive, "m", "travel of the blade traction map");
  o.group("Numerics");
  o.real("cell", c.cell, {0.0, 0.1, Bounds::right_closed}, "m", "cell size (x and z; y fits)");
  o.integer("ppc", c.particles_per_cell, 1, 4, "particles per cell and axis");
  o.real("settle-time", c.settle_time, RealRange::non_negative(), "s", "K0 settling time");
  o.real("flip", c.flip, {0.0, 1.0, Bounds::closed}, "", "FLIP fraction of the velocity update");
  o.flag("separated-pic", c.separated_pic,
         "points whose grains have come apart take the grid's velocity (PIC) instead of FLIP's, "
         "so corn falling behind the blade lands instead of bouncing (docs/theory/mpm.md)");
  o.real("cfl", c.cfl, {0.0, 1.0, Bounds::right_closed}, "", "time step / critical step");
  o.group("Output and run control");
  o.real("frame-interval", c.frame_interval, positive, "m", "travel between ParaView frames",
         io::Options::Role::control);
  o.flag("frames", c.frames, "write ParaView frames", io::Options::Role::control);
  o.integer("threads", c.threads, 0, 1024, "OpenMP threads (0: all)", io::Options::Role::control);
  o.text("out", c.out, "DIR", "output folder", io::Options::Role::control);
  o.flag("replace", c.replace, "delete an earlier run's results in the output folder first",
         io::Options::Role::control);
}

void check(const Case& c) {
  const auto fail = [](const std::string& what) { throw Error("command line: " + what); };
  if (c.psi > c.phi) fail("--psi " + detail::format_number(c.psi) + " exceeds --phi");
  if (c.depth > c.blade_height || c.depth >= c.rig_height)
    fail("--depth " + detail::format_number(c.depth) +
         " must lie below --blade-height and --rig-height");
  if (!(c.average_from < c.average_to && c.average_to <= c.travel && c.profile_at < c.travel))
    fail("need --average-from < --average-to <= --travel and --profile-at < --travel");
  if (c.blade_start + c.blade_thickness + c.travel > 0.8 * c.rig_length)
    fail("--travel " + detail::format_number(c.travel) +
         " brings the blade within 20 % of the "
         "rig's end (valid: blade start 0.06 m + travel <= 0.8 --rig-length)");
}

// The highest particle per (x, y) column of cells: the free surface across the width.
std::vector<std::vector<double>> surface_rows(const Sim& sim, double cell, double spacing) {
  const auto& x = sim.particles().get<particles::field::Position<3>>();
  std::map<std::pair<long, long>, double> top;
  for (const auto& p : x) {
    const auto key =
        std::make_pair(std::lround(std::floor(p[0] / cell)), std::lround(std::floor(p[1] / cell)));
    auto [it, fresh] = top.try_emplace(key, p[2]);
    if (!fresh) it->second = std::max(it->second, p[2]);
  }
  std::vector<std::vector<double>> rows;
  for (const auto& [key, z] : top) {
    rows.push_back({(static_cast<double>(key.first) + 0.5) * cell,
                    (static_cast<double>(key.second) + 0.5) * cell, z + 0.5 * spacing});
  }
  return rows;
}

int run(const Case& c, const io::Options& options) {
  check(c);
  const double modelled = c.half_width ? 0.5 * c.width : c.width;
  const Index cells_y = std::max<Index>(1, std::lround(modelled / c.cell));
  const grid::Grid<3> grid(
      Vec<3>::Zero(), Vec<3>(c.rig_length, modelled, c.rig_height),
      {std::lround(c.rig_length / c.cell), cells_y, std::lround(c.rig_height / c.cell)});
  material::MohrCoulombParameters mc{.youngs_modulus = c.youngs_modulus,
                                     .poisson_ratio = c.poisson_ratio,
                                     .friction_angle_deg = c.phi,
                                     .dilatancy_angle_deg = c.psi};
  mc.separation = true;
  contact::RigidContact<3> law;
  // The blade spans the grid's width and a cell beyond it, so the nodes on the side faces
  // meet its cutting face, not its ends.
  const double face_x = c.blade_start + c.blade_thickness;
  auto blade =
      contact::RigidBody<3>::box(Vec<3>(c.blade_start, -grid.cell_size()[1], 0.0),
                                 Vec<3>(face_x, modelled + grid.cell_size()[1], c.blade_height));
  const double start = c.settle_time;
  const Vec<3> speed(c.blade_speed, 0.0, 0.0);
  blade.set_velocity(
      [start, speed](double t) { return t < start ? Vec<3>(Vec<3>::Zero()) : speed; });
  const int body = law.add_body(std::move(blade), contact::Interface::coulomb_angle(c.delta));
  constexpr int cutting_face = 1;  // +x

  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  parameters.damping = c.settle_damping;
  parameters.flip_fraction = c.flip;
  parameters.pic_where_separated = c.separated_pic;
  parameters.cfl = c.cfl;
  parameters.threads = static_cast<int>(c.threads);
  Sim sim(grid, Model(mc), parameters, std::move(law));
  const auto soil =
      particles::seed_box(grid, Vec<3>(face_x, 0.0, 0.0), Vec<3>(c.rig_length, modelled, c.depth),
                          static_cast<int>(c.particles_per_cell));
  sim.add_particles(soil.positions, soil.volume, c.density, soil.half_width);
  initial::set_geostatic_stress(sim, c.depth, initial::jaky_k0(c.phi));
  auto& bc = sim.boundary_conditions();
  bc.set(BC::face(2, false), grid::BoundaryKind::fixed);  // the rig floor, the paper's
  bc.set(BC::face(0, false), grid::BoundaryKind::roller);
  bc.set(BC::face(0, true), grid::BoundaryKind::roller);
  const double glass_mu = std::tan(degrees_to_radians(c.glass_friction));
  bc.set(BC::face(1, true), grid::BoundaryKind::friction, glass_mu);
  bc.set(BC::face(1, false),
         c.half_width ? grid::BoundaryKind::roller : grid::BoundaryKind::friction,
         c.half_width ? 0.0 : glass_mu);

  const auto reference = analysis::sokolovski_passive({.friction_angle_deg = c.phi,
                                                       .wall_friction_deg = c.delta,
                                                       .unit_weight = c.density * 9.81,
                                                       .height = c.depth});
  io::RunDirectory folder(
      c.out, c.replace ? io::RunDirectory::Mode::replace : io::RunDirectory::Mode::fresh,
      "example_06_flat_blade_3d", options.given("out") ? "--out" : "--out (default)");
  io::write_file_atomically(folder.claim("case.used"),
                            options.case_text("# example_06_flat_blade_3d"));
  const double dt = sim.time_step();
  const double end = start + c.travel / c.blade_speed;
  std::printf(
      "3D flat blade: h = %g m, %s width %g m (%ld x %ld x %ld cells), glass %g deg, "
      "%ld particles, %ld steps\n",
      c.depth, c.half_width ? "half" : "full", modelled, static_cast<long>(grid.cells(0)),
      static_cast<long>(grid.cells(1)), static_cast<long>(grid.cells(2)), c.glass_friction,
      static_cast<long>(sim.particles().size()), std::lround(end / dt));
  std::fflush(stdout);

  io::CsvWriter forces(folder.claim("forces.csv"),
                       {"time_s", "travel_m", "draft_N", "vertical_N", "draft_N_per_m",
                        "vertical_N_per_m", "draft_N_rig"});
  std::optional<io::ParticleFrameWriter> frames;
  if (c.frames) {
    frames.emplace(folder.path() / "frames", "flat_blade_3d",
                   io::FrameOptions{.body_names = {"blade"}});
    folder.claim("frames/flat_blade_3d.xdmf");
    folder.claim("frames/flat_blade_3d_bodies.xdmf");
  }
  const auto write_frame = [&](double travel) {
    folder.claim(std::filesystem::path("frames") /
                 frames->frame_path(frames->frame_count()).filename());
    frames->write(sim, {{"blade_travel", travel, "m", "blade travel since the blade started"}});
  };
  io::StopRequest stop;
  io::ProgressReporter progress("flat blade 3D", end, sim.particles().size());
  bool cutting = false, profiled = false;
  double next_frame = 0.0, next_row = 0.0;
  Vec<3> row_sum = Vec<3>::Zero(), average_sum = Vec<3>::Zero();
  double row_steps = 0.0, average_steps = 0.0, travel = 0.0;
  std::map<double, double> width_sum, width_at_profile;  // per node column y [N/m]
  const double rig_factor = c.width / modelled;
  while (sim.time() < end - 0.5 * dt && !stop.requested()) {
    if (!cutting && sim.time() >= start - 0.5 * dt) {
      cutting = true;
      sim.set_damping(0.0);
    }
    sim.step(dt);
    progress.update(sim.time(), sim.step_count());
    if (!cutting) continue;
    travel = (sim.time() - start) * c.blade_speed;
    const Vec<3> force = sim.contact().force_on_material(body);
    row_sum += force;
    row_steps += 1.0;
    const bool in_window = travel >= c.average_from - 1e-12 && travel <= c.average_to + 1e-12;
    if (in_window) {
      average_sum += force;
      average_steps += 1.0;
    }
    if (travel >= next_row - 1e-12) {  // rows every 0.1 mm, averaged over their steps
      const Vec<3> f = row_sum / row_steps;
      forces.write_row(
          {sim.time(), travel, f[0], f[2], f[0] / modelled, f[2] / modelled, f[0] * rig_factor});
      row_sum.setZero();
      row_steps = 0.0;
      next_row += 1e-4;
    }
    const bool profile_now = !profiled && travel >= c.profile_at - 1e-12;
    if (in_window || profile_now) {
      const auto patches = sim.contact().traction_map(body, cutting_face);
      const auto& face = sim.contact().body(body).shape();
      std::vector<std::vector<double>> rows;
      std::map<double, double> per_width;  // normal force per metre of width, per node column y
      for (const auto& p : patches) {
        // Face 1 runs up from the tip (u = z) and across the width (v = y from its start).
        const double y = face.face_origin(cutting_face)[1] + p.centre[1];
        // A patch is a cell wide; a node column on the grid's side face carries half a cell.
        const bool on_side = std::abs(y) < 1e-9 || std::abs(y - modelled) < 1e-9;
        const double scale = on_side ? 2.0 : 1.0;
        if (y < -1e-9 || y > modelled + 1e-9) continue;  // beyond the grid: no nodes
        if (profile_now)
          rows.push_back({p.centre[0], c.depth - p.centre[0], y, scale * p.normal_traction,
                          scale * p.shear_traction[0], scale * p.shear_traction[1],
                          static_cast<double>(p.nodes)});
        per_width[y] += scale * p.normal_traction * p.size[0];
      }
      // One step's nodal forces are noisy; the window's mean is what the draft is.
      if (in_window)
        for (const auto& [y, n] : per_width) width_sum[y] += n;
      if (profile_now) {
        profiled = true;
        width_at_profile = per_width;
        io::write_csv(folder.claim("blade_traction.csv"),
                      {"height_above_tip_m", "depth_m", "y_m", "normal_traction_Pa", "shear_up_Pa",
                       "shear_across_Pa", "nodes"},
                      rows);
      }
    }
    if (frames && travel >= next_frame - 1e-12) {
      write_frame(travel);
      next_frame += c.frame_interval;
    }
  }
  progress.finish(sim.time(), sim.step_count());
  // The end of travel always gets a frame, also when rounding left it just short of the next
  // mark or a signal stopped the run: the frames end on the state surface.csv describes.
  if (frames && cutting && next_frame - c.frame_interval < travel - 1e-9) write_frame(travel);
  const double spacing = c.cell / static_cast<double>(c.particles_per_cell);
  std::vector<std::vector<double>> width_rows;
  double width_integral = 0.0;  // trapezoid rule over the node columns [N]
  for (auto it = width_sum.begin(); it != width_sum.end(); ++it) {
    const double mean_force = it->second / average_steps;
    const auto snapshot = width_at_profile.find(it->first);
    width_rows.push_back({it->first, mean_force,
                          snapshot == width_at_profile.end() ? std::nan("") : snapshot->second});
    const auto next = std::next(it);
    if (next != width_sum.end())
      width_integral +=
          0.5 * (mean_force + next->second / average_steps) * (next->first - it->first);
  }
  io::write_csv(folder.claim("width_profile.csv"),
                {"y_m", "normal_force_N_per_m", "normal_force_at_profile_N_per_m"}, width_rows);
  io::write_csv(folder.claim("surface.csv"), {"x_m", "y_m", "z_top_m"},
                surface_rows(sim, c.cell, spacing));
  const Vec<3> mean = average_steps > 0 ? Vec<3>(average_sum / average_steps) : Vec<3>::Zero();
  const double draft_per_m = mean[0] / modelled;
  const double sokolovski = reference.horizontal_force_per_width;
  io::write_file_atomically(
      folder.claim("summary.txt"),
      "depth_m = " + detail::format_number(c.depth) +
          "\nglass_friction_deg = " + detail::format_number(c.glass_friction) +
          "\nwidth_m = " + detail::format_number(c.width) +
          "\nmodelled_width_m = " + detail::format_number(modelled) +
          "\ntravel_reached_m = " + detail::format_number(travel) +
          "\nblade_face_end_m = " + detail::format_number(face_x + travel) +
          "\ndraft_N_per_m = " + detail::format_number(draft_per_m) +
          "\nvertical_N_per_m = " + detail::format_number(mean[2] / modelled) +
          "\ndraft_N_rig = " + detail::format_number(mean[0] * rig_factor) +
          "\nsokolovski_N_per_m = " + detail::format_number(sokolovski) +
          "\nwidth_profile_mean_N_per_m = " + detail::format_number(width_integral / modelled) +
          "\nparticles = " + std::to_string(sim.particles().size()) +
          "\nsteps = " + std::to_string(sim.step_count()) + "\n");
  std::printf(
      "  draft over %g-%g mm: %.1f N/m of width (%.2f N on the %g m rig); Sokolovski "
      "%.1f N/m (%+.1f %%)\n",
      c.average_from * 1e3, c.average_to * 1e3, draft_per_m, mean[0] * rig_factor, c.width,
      sokolovski, 100.0 * (draft_per_m / sokolovski - 1.0));
  if (average_steps > 0)
    std::printf(
        "  blade normal force across the width, mean over the window: %.1f N/m (the "
        "draft: %.1f)\n",
        width_integral / modelled, draft_per_m);
  std::printf("results in %s\n", folder.path().c_str());
  if (stop.requested()) {
    std::printf("stopped by %s at %.2f mm of travel\n", stop.signal_name(), travel * 1e3);
    return stop.exit_status();
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef SIGXFSZ
  std::signal(SIGXFSZ, SIG_IGN);
#endif
  Case c;
  io::Options options("example_06_flat_blade_3d",
                      "The flat blade of Coetzee (2014) in 3D between the rig's glass side "
                      "walls: draft per metre of width against Sokolovski's plane-strain "
                      "passive force, the traction over the blade's face and the free surface "
                      "across the width.");
  declare(options, c);
  try {
    if (options.parse(argc, argv) == io::Options::Outcome::help) {
      std::fputs(options.help().c_str(), stdout);
      return 0;
    }
    return run(c, options);
  } catch (const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
  }
  return 1;
}
