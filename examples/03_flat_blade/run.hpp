#pragma once
// The flat-blade run of one composition: set-up, the checks that the case can keep its
// promises, the time loop with its outputs, checkpoints and restart. Included only by the
// run_*.cpp files, each of which compiles it for some compositions.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>

#include "compositions.hpp"
#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/initial/geostatic.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/simulation.hpp"
#include "feasibility.hpp"
#include "rig.hpp"

namespace flat_blade {

namespace detail {
using namespace cosmpm;

// Classical<M> may not even be named for a Cosserat model: picked by specialisation.
template <class Model, class AntiLocking, bool polar = Model::is_cosserat>
struct ContinuumFor {
  using type = continuum::Classical<Model, AntiLocking>;
};
template <class Model, class AntiLocking>
struct ContinuumFor<Model, AntiLocking, true> {
  using type = continuum::Cosserat<Model>;
};
template <class C>
using SimulationOf =
    Simulation<2, typename C::kernel,
               typename ContinuumFor<typename C::model, typename C::antilocking>::type,
               contact::RigidContact<2>, typename C::scheme, typename C::transfer>;

inline material::DruckerPragerMatching cone_of(const Case& c,
                                               material::DruckerPragerMatching fallback) {
  using material::DruckerPragerMatching;
  if (c.cone == "plane-strain") return DruckerPragerMatching::plane_strain;
  if (c.cone == "plane-strain-per-angle") return DruckerPragerMatching::plane_strain_per_angle;
  if (c.cone == "outer") return DruckerPragerMatching::outer;
  if (c.cone == "inner") return DruckerPragerMatching::inner;
  return fallback;
}

template <class Model>
Model make_model(const Case& c) {
  using material::DruckerPragerMatching;
  if constexpr (std::is_same_v<Model, MohrCoulomb>) {
    material::MohrCoulombParameters p{.youngs_modulus = c.youngs_modulus,
                                      .poisson_ratio = c.poisson_ratio,
                                      .friction_angle_deg = c.friction_angle_deg,
                                      .dilatancy_angle_deg = c.dilatancy_angle_deg,
                                      .cohesion = c.cohesion};
    if (c.dilatancy_cutoff > 0.0) p.dilatancy_cutoff_strain = c.dilatancy_cutoff;
    p.separation = c.separation;
    return Model(p);
  } else if constexpr (std::is_same_v<Model, DruckerPrager>) {
    return Model(c.youngs_modulus, c.poisson_ratio, c.friction_angle_deg, c.dilatancy_angle_deg,
                 c.cohesion, cone_of(c, DruckerPragerMatching::plane_strain));
  } else {
    const double shear = c.youngs_modulus / (2.0 * (1.0 + c.poisson_ratio));
    return Model(c.youngs_modulus, c.poisson_ratio, c.cosserat_shear_ratio * shear,
                 c.characteristic_length, c.friction_angle_deg, c.dilatancy_angle_deg, c.cohesion,
                 {}, cone_of(c, DruckerPragerMatching::plane_strain_per_angle));
  }
}

// The running state of the loop that a checkpoint keeps (names in CheckpointValues).
struct LoopState {
  bool cutting = false;
  bool profile_written = false;
  double next_frame = 0.0;  // blade travel of the next frame
  double next_row = 0.0;    // of the next forces.csv row
  double next_checkpoint = 0.0;
  double draft_sum = 0.0, vertical_sum = 0.0;
  double averaged_steps = 0.0;
  double row_draft = 0.0, row_vertical = 0.0;
  double row_steps = 0.0;

  io::CheckpointValues values() const {
    io::CheckpointValues v;
    v.set("cutting", cutting ? 1.0 : 0.0);
    v.set("profile_written", profile_written ? 1.0 : 0.0);
    v.set("next_frame", next_frame);
    v.set("next_row", next_row);
    v.set("next_checkpoint", next_checkpoint);
    v.set("draft_sum", draft_sum);
    v.set("vertical_sum", vertical_sum);
    v.set("averaged_steps", averaged_steps);
    v.set("row_draft", row_draft);
    v.set("row_vertical", row_vertical);
    v.set("row_steps", row_steps);
    return v;
  }
  void restore(const io::CheckpointValues& v, const std::string& where) {
    cutting = v.get("cutting", where) != 0.0;
    profile_written = v.get("profile_written", where) != 0.0;
    next_frame = v.get("next_frame", where);
    next_row = v.get("next_row", where);
    next_checkpoint = v.get("next_checkpoint", where);
    draft_sum = v.get("draft_sum", where);
    vertical_sum = v.get("vertical_sum", where);
    averaged_steps = v.get("averaged_steps", where);
    row_draft = v.get("row_draft", where);
    row_vertical = v.get("row_vertical", where);
    row_steps = v.get("row_steps", where);
  }
};

}  // namespace detail

template <class Kernel, class Scheme, class Model, class Transfer, class AntiLocking>
Outcome run(const Case& c, RunContext& context,
            Composition<Kernel, Scheme, Model, Transfer, AntiLocking>) {
  using namespace cosmpm;
  namespace fs = std::filesystem;
  using Sim = detail::SimulationOf<Composition<Kernel, Scheme, Model, Transfer, AntiLocking>>;
  constexpr bool polar = Model::is_cosserat;
  const io::Options& options = context.options;

  Model model = [&] {
    try {
      return detail::make_model<Model>(c);
    } catch (const Error& error) {
      throw Error(std::string("the soil options do not make a valid ") + option_name<Model>() +
                  " model (--youngs-modulus, --poisson-ratio, --phi, --psi, --cohesion" +
                  (polar ? ", --gc-over-g, --length-scale" : "") + "): " + error.what());
    }
  }();
  const Rig rig(c);
  const grid::Grid<2> grid = rig.grid();

  const double face_x = c.blade_start + c.blade_thickness;
  const double start_time = c.equilibrium_time;
  const double speed = c.blade_speed;
  contact::RigidContact<2> blade_contact;
  blade_contact.set_start_of_step_correction(c.start_of_step_contact);
  blade_contact.set_gap_check(c.gap_check);
  const int blade_body = rig.add_bodies(c, polar, blade_contact);
  constexpr int cutting_face = 1;

  SimulationParameters<2> parameters;
  parameters.gravity = rig.direction(Vec<2>(0.0, -c.gravity));
  parameters.damping = c.equilibrium_damping;
  parameters.flip_fraction = c.flip_fraction;
  parameters.pic_where_separated = c.separated_pic;
  parameters.cfl = c.cfl;
  parameters.threads = c.threads;
  parameters.stray_particles = c.stray_particles == "freeze"   ? StrayParticles::freeze
                               : c.stray_particles == "remove" ? StrayParticles::remove
                                                               : StrayParticles::stop;
  using Continuum = typename Sim::continuum_type;
  const Continuum continuum = [&] {
    if constexpr (polar) {
      // Rotation held on the rig floor and sides, as the paper does.
      using BC = grid::BoundaryConditions<2>;
      continuum::CosseratSettings settings{.micro_inertia = c.micro_inertia,
                                           .micro_inertia_scale = c.micro_inertia_scale};
      for (int face : {BC::face(1, false), BC::face(0, false), BC::face(0, true)}) {
        settings.rotation_fixed[static_cast<std::size_t>(face)] = !rig.turned();
      }
      return Continuum(model, settings);
    } else {
      return Continuum(model);
    }
  }();
  Sim sim(grid, continuum, parameters, std::move(blade_contact));

  // The soil layer in front of the blade, at rest under K0 = 1 - sin(phi) (Jaky).
  const int per_cell = static_cast<int>(c.particles_per_cell);
  const auto soil = rig.turned()
                        ? particles::seed_polygon(grid, rig.layer(c, face_x), per_cell)
                        : particles::seed_box(grid, Vec<2>(face_x, 0.0),
                                              Vec<2>(c.grid_length, c.soil_depth), per_cell);
  sim.add_particles(soil.positions, soil.volume, c.density, soil.half_width);
  const double k0 = initial::jaky_k0(c.friction_angle_deg);
  {
    const auto& x = sim.particles().template get<particles::field::Position<2>>();
    auto& stress = sim.particles().template get<particles::field::Stress<Model>>();
    for (Index p = 0; p < sim.particles().size(); ++p) {
      const double depth = c.soil_depth - rig.to_rig(x[p])[1];
      if constexpr (polar) {
        stress[p] = initial::geostatic_cosserat_stress(c.density, c.gravity, depth, k0);
      } else {
        stress[p] = initial::geostatic_stress(c.density, c.gravity, depth, k0);
      }
      if (rig.turned()) {  // K0 along the rig's axes: the principal axes turn with it
        const double rig_xx = stress[p][0];
        const double rig_yy = stress[p][1];
        rig.turn_stress(rig_xx, rig_yy, stress[p][0], stress[p][1], stress[p][3]);
        if constexpr (polar) stress[p][4] = stress[p][3];
      }
    }
  }
  using BC = grid::BoundaryConditions<2>;
  auto& bc = sim.boundary_conditions();
  if (rig.turned()) {
    // The walls are bodies; the grid's faces lie outside them and hold nothing.
  } else if (c.floor == "friction") {
    bc.set(BC::face(1, false), grid::BoundaryKind::friction,
           std::tan(c.floor_friction_deg * std::numbers::pi / 180.0));
  } else {
    bc.set(BC::face(1, false), grid::BoundaryKind::fixed);  // rig floor, the paper's
  }
  if (!rig.turned()) {
    bc.set(BC::face(0, false), grid::BoundaryKind::roller);
    bc.set(BC::face(0, true), grid::BoundaryKind::roller);
  }

  // The reference: Sokolovski's passive pressure on a vertical wall of height h.
  const auto reference = analysis::sokolovski_passive({.friction_angle_deg = c.friction_angle_deg,
                                                       .wall_friction_deg = c.wall_friction_deg,
                                                       .unit_weight = c.density * c.gravity,
                                                       .height = c.soil_depth,
                                                       .cohesion = c.cohesion});

  const double dt = sim.time_step();
  const double end_time = start_time + c.travel / speed;
  const int threads = resolve_thread_count(c.threads);
  check_promises(c, options, dt, sim.particles().size(), threads);
  if (c.check_only) {
    Outcome checked;
    checked.checked = true;
    checked.particles = static_cast<long>(sim.particles().size());
    checked.time_step = dt;
    checked.steps = static_cast<long>(std::ceil(end_time / dt));
    checked.run_seconds = static_cast<double>(checked.steps) *
                          static_cast<double>(checked.particles) /
                          (optimistic_particle_steps_per_second * threads);
    return checked;
  }

  // Only now, with a case that can keep its promises, is the output folder taken.
  io::RunDirectory& folder = context.open_folder();
  const fs::path out = folder.path();
  io::write_file_atomically(folder.claim("case.used"), context.parameters);
  {
    io::CsvWriter wall(folder.claim("sokolovski_wall.csv"),
                       {"depth_m", "normal_pressure_Pa", "shear_stress_Pa"});
    for (const auto& w : reference.wall) {
      wall.write_row({w.depth, w.normal_pressure, w.shear_stress});
    }
    io::CsvWriter slip(folder.claim("sokolovski_slip_line.csv"), {"distance_m", "depth_m"});
    for (const auto& s : reference.slip_line) slip.write_row({s.distance, s.depth});
  }

  detail::LoopState state;
  const fs::path checkpoint = folder.claim("checkpoint.h5");
  if (c.restart) {
    const std::string where = "--restart: checkpoint '" + checkpoint.string() + "'";
    if (!fs::exists(checkpoint)) {
      throw Error(where +
                  " does not exist: the run in this folder was not stopped with a "
                  "checkpoint (see --checkpoint-every)");
    }
    state.restore(io::load_checkpoint(sim, checkpoint), where);
    if (state.cutting) sim.set_damping(c.damping);
  }
  const std::vector<std::string> force_columns{"time_s",        "displacement_m",
                                               "draft_N_per_m", "vertical_N_per_m",
                                               "draft_N_rig",   "vertical_N_rig"};
  io::CsvWriter forces =
      c.restart ? io::CsvWriter::resume(folder.claim("forces.csv"), force_columns, sim.time())
                : io::CsvWriter(folder.claim("forces.csv"), force_columns);
  std::optional<io::ParticleFrameWriter> frames;
  if (c.write_frames) {
    frames.emplace(out / "frames", "flat_blade",
                   io::FrameOptions{
                       .run_parameters = context.parameters,
                       .body_names = rig.turned() ? std::vector<std::string>{"floor", "left_wall",
                                                                             "right_wall", "blade"}
                                                  : std::vector<std::string>{"blade"}});
    folder.claim("frames/flat_blade.xdmf");
    folder.claim("frames/flat_blade_bodies.xdmf");
    if (c.restart) frames->resume(sim);
  }
  auto write_frame = [&](double travel) {
    folder.claim(fs::path("frames") / frames->frame_path(frames->frame_count()).filename());
    frames->write(sim, {{"blade_travel", travel, "m",
                         "blade travel since the blade started (the paper's displacement)"}});
  };
  auto save_checkpoint = [&] { io::save_checkpoint(sim, checkpoint, state.values()); };

  // Forces are averaged over the steps between two CSV rows (0.1 mm of travel) so the CSV
  // is smooth but loses nothing; the 15-35 mm average uses every step.
  const double row_interval = forces_row_interval;
  io::ProgressReporter progress(polar ? "flat blade (polar)" : "flat blade (nonpolar)", end_time,
                                sim.particles().size());
  const auto wall_start = std::chrono::steady_clock::now();
  bool stopped = false;
  while (sim.time() < end_time - 0.5 * dt) {
    if (!state.cutting && sim.time() >= start_time - 0.5 * dt) {
      state.cutting = true;
      sim.set_damping(c.damping);
      if (frames) write_frame(0.0);
      state.next_frame = c.frame_interval;
      state.next_checkpoint = c.checkpoint_every;
    }
    sim.step(dt);
    progress.update(sim.time(), sim.step_count());
    const double travel = state.cutting ? (sim.time() - start_time) * speed : 0.0;
    if (state.cutting) {
      const Vec<2> force = rig.in_rig_axes(sim.contact().force_on_material(blade_body));
      state.row_draft += force[0];
      state.row_vertical += force[1];
      state.row_steps += 1.0;
      if (travel >= c.average_from - 1e-12 && travel <= c.average_to + 1e-12) {
        state.draft_sum += force[0];
        state.vertical_sum += force[1];
        state.averaged_steps += 1.0;
      }
      if (travel >= state.next_row - 1e-12) {
        const double draft = state.row_draft / state.row_steps;
        const double vertical = state.row_vertical / state.row_steps;
        forces.write_row(
            {sim.time(), travel, draft, vertical, draft * c.rig_width, vertical * c.rig_width});
        state.row_draft = state.row_vertical = 0.0;
        state.row_steps = 0.0;
        state.next_row += row_interval;
      }
      if (!state.profile_written && travel >= c.profile_at - 1e-12) {
        state.profile_written = true;
        io::CsvWriter profile(
            folder.claim("blade_stress.csv"),
            {"height_above_tip_m", "depth_m", "normal_traction_Pa", "shear_traction_Pa", "nodes"});
        for (const auto& bin : sim.contact().traction_profile(blade_body, cutting_face)) {
          // Edge 1 runs up the face from the tip: `centre` is the height above the tip.
          profile.write_row({bin.centre, c.soil_depth - bin.centre, bin.normal_traction,
                             bin.shear_traction, static_cast<double>(bin.nodes)});
        }
      }
      if (frames && travel >= state.next_frame - 1e-12) {
        write_frame(travel);
        state.next_frame += c.frame_interval;
      }
      if (c.checkpoint_every > 0.0 && travel >= state.next_checkpoint - 1e-12) {
        state.next_checkpoint += c.checkpoint_every;
        save_checkpoint();
      }
    }
    if (context.stop.requested()) {
      stopped = true;
      save_checkpoint();
      break;
    }
  }
  progress.finish(sim.time(), sim.step_count());
  const double reached = state.cutting ? (sim.time() - start_time) * speed : 0.0;
  // The end of travel always gets a frame, even when rounding left it just short.
  if (!stopped && frames && state.next_frame - c.frame_interval < c.travel - 1e-9) {
    write_frame(reached);
  }

  Outcome outcome;
  const double averaged = state.averaged_steps;
  outcome.average_draft_per_width = averaged > 0 ? state.draft_sum / averaged : 0.0;
  outcome.average_vertical_per_width = averaged > 0 ? state.vertical_sum / averaged : 0.0;
  outcome.sokolovski_per_width = reference.horizontal_force_per_width;
  outcome.sokolovski_vertical_per_width = reference.vertical_force_per_width;
  outcome.run_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  outcome.steps = static_cast<long>(sim.step_count());
  outcome.particles = static_cast<long>(sim.particles().size());
  outcome.time_step = dt;
  outcome.stopped = stopped;
  outcome.travel = reached;
  outcome.stray_particles = static_cast<long>(sim.stray_particles().count);
  outcome.stray_mass = sim.stray_particles().mass;
  {
    // Behind or under the blade, in rig axes: x below the blade's face, y below its top.
    const double final_face = face_x + reached;
    const auto& x = sim.particles().template get<particles::field::Position<2>>();
    const auto& mass = sim.particles().template get<particles::field::Mass>();
    for (std::size_t p = 0; p < x.size(); ++p) {
      const Vec<2> at = rig.to_rig(x[p]);
      if (at[0] < final_face && at[1] < c.blade_height) {
        ++outcome.overrun_particles;
        outcome.overrun_mass += mass[p];
      }
    }
  }
  {
    const auto& states = sim.particles().template get<particles::field::MaterialState<Model>>();
    for (const auto& s : states) {
      if constexpr (requires { s.separation; }) outcome.separated_particles += s.separation > 0.0;
    }
    if constexpr (polar) {
      const auto& rotation = sim.particles().template get<particles::field::MicroRotation>();
      const auto& stress = sim.particles().template get<particles::field::Stress<Model>>();
      for (std::size_t p = 0; p < rotation.size(); ++p) {
        outcome.max_rotation = std::max(outcome.max_rotation, std::abs(rotation[p]));
        outcome.max_couple_stress =
            std::max(outcome.max_couple_stress, std::hypot(stress[p][5], stress[p][6]));
      }
    }
  }
  if (!stopped && !state.profile_written) {
    // check_promises rules this out; a failure here is a bug, not bad input.
    throw Error("internal: the blade stress profile at --profile-at was not taken");
  }
  return outcome;
}

}  // namespace flat_blade
