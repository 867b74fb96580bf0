#pragma once
// The flat-blade case of Coetzee (2014): every parameter of the paper's Table 1 as a default,
// each with its meaning, unit and valid range, set from the command line or a case file
// (cases/*.case are the paper's cases; docs/usage.md describes the format). Light on
// purpose (no engine headers): the option fuzz test includes it.
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/options.hpp"

namespace flat_blade {

using cosmpm::Bounds;
using cosmpm::io::Options;
using cosmpm::io::RealRange;

struct Case {
  // Soil (Table 1, corn).
  double youngs_modulus = 2.76e6;  // Pa
  double poisson_ratio = 0.2;
  double density = 778.0;  // kg/m^3
  double friction_angle_deg = 26.0;
  double dilatancy_angle_deg = 2.0;  // the paper also runs 10 and 26
  double dilatancy_cutoff = 0.0;     // plastic shear strain; 0: none (the paper)
  double cohesion = 0.0;             // Pa
  // Mohr-Coulomb: a point that dilated at the apex stays stress-free until compression closes
  // the gap (MohrCoulombParameters::separation). auto: on for cohesionless Mohr-Coulomb.
  std::string separation_choice = "auto";
  bool separation = false;          // the choice resolved (check_case)
  double wall_friction_deg = 14.0;  // corn on steel
  // The rig floor under the soil: "fixed" (the paper's: no velocity at the floor nodes) or
  // "friction" (a Coulomb wall, no penetration, friction angle floor_friction_deg), on which
  // the blade scrapes the floor clean.
  std::string floor = "fixed";
  double floor_friction_deg = 14.0;  // steel floor: the blade's corn-on-steel value
  // The whole rig turned against the grid (rig.hpp; the paper turned its mesh by 35 deg).
  double rig_angle_deg = 0.0;
  // Cosserat (Table 1): Gc = 2 G, l = 10 mm, J = 0.5 (0.5 l)^2.
  bool polar = false;
  double cosserat_shear_ratio = 2.0;    // Gc / G
  double characteristic_length = 0.01;  // m
  double micro_inertia = 12.5e-6;       // m^2
  // The micro-inertia the dynamics uses is micro_inertia x this (quasi-static scaling): 16
  // lifts the rotational step bound above the p-wave bound (2.7 x fewer steps) and changed
  // the 15-35 mm draft by at most 0.03 % at h = 150, 250 and 350 mm (docs/theory/mpm.md).
  double micro_inertia_scale = 16.0;
  // The Cosserat rotation at the blade (contact::Interface::Rotation): held (omega = 0 at the
  // nodes straddling the face, the paper's), free, or coupled (Coulomb friction on the grains'
  // slip v_t - r omega, its moment turning them) with the grain radius r = d50 / 2: the
  // paper's corn grains are about 10 mm (its Sect. 2.2, also its l).
  std::string blade_rotation = "held";
  double grain_radius = 0.005;       // m
  bool blade_rotation_fixed = true;  // older spelling: true = held, false = free
  std::string cone = "default";      // Drucker-Prager fit to phi and psi
  // Method: the composition of the simulation (compositions.hpp lists those built in).
  std::string material = "auto";  // mohr-coulomb, or cosserat-drucker-prager when polar
  std::string shape = "linear";   // the paper's bilinear shape functions
  // MUSL, not the paper's USL: USL strains a particle with v_i + dt f_i / m_i, which grows
  // without bound at nodes of tiny mass; at the blade's top corner that blew a surface
  // particle off after 8 mm of travel (docs/theory/mpm.md, "Which to use").
  std::string integrator = "musl";
  std::string transfer = "flip-blend";  // the paper's FLIP (--flip sets the blend)
  std::string antilocking = "none";
  // Rig and blade (Sect. 2): rig 1.2 m x 0.7 m, blade 350 mm high moving at 10 mm/s.
  double grid_length = 1.2;  // m
  double grid_height = 0.7;  // m
  double soil_depth = 0.25;  // h, m: 0.15, 0.25 or 0.35 in the paper
  double blade_height = 0.35;
  double blade_thickness = 0.01;
  double blade_start = 0.05;  // x of the blade's back face, m
  double blade_speed = 0.01;  // m/s
  double travel = 0.035;      // m of blade travel simulated
  double rig_width = 0.2;     // m between the glass panels, for forces in N
  double gravity = 9.81;      // m/s^2
  // Numerics.
  long cells_x = 120;
  long cells_y = 70;
  long particles_per_cell = 2;       // per axis
  double equilibrium_time = 0.25;    // s of damped settling under K0 before the blade moves
  double equilibrium_damping = 0.5;  // local damping while settling
  double damping = 0.0;              // local damping while cutting
  double flip_fraction = 1.0;
  // Points whose grains came apart take the grid's velocity (PIC), not FLIP's.
  bool separated_pic = false;
  double cfl = 0.5;
  // Contact also corrects the start-of-step velocity (Nairn, Hammerquist and Smith 2020).
  bool start_of_step_contact = false;
  // Contact only where the material would reach the blade within the step (gap check).
  bool gap_check = false;
  std::string stray_particles = "stop";  // a particle leaving the rig stops the run
  // Output.
  double frame_interval = 0.005;  // m of blade travel between ParaView frames
  double average_from = 0.015;    // m: the paper averages the draft over 15-35 mm
  double average_to = 0.035;
  double profile_at = 0.020;      // m: blade stress profile (the paper's Fig. 9)
  double checkpoint_every = 0.0;  // m of travel; 0: only when stopped by a signal
  bool write_frames = true;
  // Run control. Results are bit-identical for any thread count; on the 2-core development
  // VM the default run took 23 s on two threads against 32 s on one (docs/architecture.md).
  int threads = 0;
  std::string output_directory;  // default: out/flat_blade/<tag>
  bool replace = false;
  bool restart = false;
  bool allow_large_run = false;
  bool check_only = false;

  bool is_polar() const { return material == "cosserat-drucker-prager"; }

  // The default output folder's name: the case's depth, mesh, continuum and whatever differs
  // from the default method.
  std::string tag() const {
    std::ostringstream name;
    name << "h" << std::lround(soil_depth * 1000) << "_" << cells_x << "x" << cells_y << "_"
         << (is_polar() ? "polar" : "nonpolar") << "_psi" << dilatancy_angle_deg;
    if (is_polar()) {
      name << (blade_rotation == "held" ? "_wfixed" : "_w" + blade_rotation);
      if (blade_rotation == "coupled" && grain_radius != Case{}.grain_radius) {
        name << "_r" << grain_radius;
      }
    }
    if (is_polar() && micro_inertia_scale != Case{}.micro_inertia_scale) {
      name << "_jscale" << micro_inertia_scale;
    }
    if (cone != "default" && cone != (is_polar() ? "plane-strain-per-angle" : "plane-strain")) {
      name << "_" << cone;
    }
    if (dilatancy_cutoff > 0.0) name << "_cutoff" << dilatancy_cutoff;
    if (separation_choice != "auto") name << "_separation_" << separation_choice;
    if (material == "drucker-prager") name << "_dp";
    if (shape != "linear") name << "_" << shape;
    if (integrator != "musl") name << "_" << integrator;
    if (transfer != "flip-blend") name << "_" << transfer;
    if (antilocking != "none") name << "_" << antilocking;
    if (floor == "friction") name << "_floor" << floor_friction_deg;
    if (rig_angle_deg != 0.0) name << "_rig" << rig_angle_deg;
    if (start_of_step_contact) name << "_startcontact";
    if (gap_check) name << "_gapcheck";
    return name.str();
  }
};

inline void declare_options(Options& o, Case& c) {
  using Role = Options::Role;
  const RealRange positive = RealRange::positive();
  const RealRange non_negative = RealRange::non_negative();
  o.group("Soil (corn, Table 1 of Coetzee 2014)");
  o.real("youngs-modulus", c.youngs_modulus, {0.0, 1e12, Bounds::right_closed}, "Pa",
         "Young's modulus E");
  o.real("poisson-ratio", c.poisson_ratio, {-1.0, 0.5}, "", "Poisson's ratio nu");
  o.real("density", c.density, {0.0, 1e5, Bounds::right_closed}, "kg/m^3", "density rho");
  o.real("phi", c.friction_angle_deg, {0.0, 60.0, Bounds::right_closed}, "deg",
         "friction angle (the Sokolovski reference is verified up to 60 deg)");
  o.real("psi", c.dilatancy_angle_deg, {0.0, 60.0, Bounds::closed}, "deg",
         "dilatancy angle, at most --phi (the paper: 2, 10, 26)");
  o.real("dilatancy-cutoff", c.dilatancy_cutoff, {0.0, 1e3, Bounds::closed}, "",
         "Mohr-Coulomb only: the plastic shear strain from which the flow is isochoric (psi = "
         "0), a dilatancy cut-off at the critical state; 0: none (the paper's perfect "
         "plasticity)");
  o.real("cohesion", c.cohesion, {0.0, 1e9, Bounds::closed}, "Pa", "cohesion c");
  o.choice("separation", c.separation_choice, {"auto", "true", "false"},
           "Mohr-Coulomb, cohesion 0: a point that dilated at the apex (its grains apart) stays "
           "stress-free until compression has closed the gap, instead of being stressed again "
           "from its swollen volume (the heap spilling over the blade); auto: on for "
           "cohesionless Mohr-Coulomb");
  o.real("delta", c.wall_friction_deg, {0.0, 60.0, Bounds::closed}, "deg",
         "soil-blade friction angle, at most --phi");
  o.group("Cosserat soil (with --polar true)");
  o.flag("polar", c.polar,
         "polar soil: a Cosserat continuum with Drucker-Prager plasticity (same as "
         "--material cosserat-drucker-prager)");
  o.real("gc-over-g", c.cosserat_shear_ratio, {0.0, 1e3, Bounds::right_closed}, "",
         "Cosserat shear modulus over shear modulus, Gc / G");
  o.real("length-scale", c.characteristic_length, {0.0, 1.0, Bounds::right_closed}, "m",
         "characteristic length l");
  o.real("micro-inertia", c.micro_inertia, {0.0, 1.0, Bounds::right_closed}, "m^2",
         "micro-inertia J per unit mass (the paper: 0.5 (0.5 l)^2)");
  o.real("micro-inertia-scale", c.micro_inertia_scale, {0.0, 1e6, Bounds::right_closed}, "",
         "factor on J in the dynamics only (quasi-static scaling): the default 16 lifts the "
         "rotational step bound above the p-wave bound, 2.7 x fewer steps, and changed the "
         "draft by at most 0.03 % against 1 at h = 150-350 mm; 1: the paper's dynamics "
         "(docs/theory/mpm.md, \"Cosserat continuum\")");
  o.choice("blade-rotation", c.blade_rotation, {"held", "free", "coupled"},
           "the Cosserat rotation at the blade: held (w = 0 at the nodes straddling its face, "
           "the paper's), free, or coupled (wall friction on the grains' slip v_t - r w, its "
           "moment turning them; docs/theory/mpm.md)");
  o.real("grain-radius", c.grain_radius, {0.0, 1.0, Bounds::right_closed}, "m",
         "grain radius r = d50 / 2 of --blade-rotation coupled (the corn: d50 = 10 mm)");
  o.flag("blade-rotation-fixed", c.blade_rotation_fixed,
         "older spelling of --blade-rotation: true = held, false = free");
  o.group("Method and model (the compositions built into this program: see --help below)");
  o.choice("material", c.material,
           {"auto", "mohr-coulomb", "drucker-prager", "cosserat-drucker-prager"},
           "soil model; auto: mohr-coulomb, or cosserat-drucker-prager with --polar true");
  o.choice("cone", c.cone, {"default", "plane-strain", "plane-strain-per-angle", "outer", "inner"},
           "Drucker-Prager cone fitted to --phi and --psi; default: plane-strain for "
           "drucker-prager, plane-strain-per-angle (our reading of Tejchman) for "
           "cosserat-drucker-prager");
  o.choice("shape", c.shape, {"linear", "gimp", "quadratic-bspline", "cubic-bspline"},
           "shape functions (linear: the paper's bilinear Q4)");
  o.choice("integrator", c.integrator, {"musl", "usl", "usf", "fused-musl"},
           "update scheme (the paper: usl, which blows up at the blade's corner; see "
           "docs/theory/mpm.md); fused-musl: musl with the next step's particle-to-grid map in "
           "its last particle pass (integrator/fused.hpp), equal to musl within rounding");
  o.choice("transfer", c.transfer, {"flip-blend", "apic"},
           "particle velocity transfer: flip-blend (PIC/FLIP by --flip) or apic (affine, not "
           "with --shape linear)");
  o.choice("antilocking", c.antilocking, {"none", "fbar"},
           "volumetric anti-locking of the nonpolar continuum: none or fbar (F-bar, the "
           "cell-averaged volumetric strain rate)");
  o.group("Rig and blade (Sect. 2 of the paper)");
  o.real("grid-length", c.grid_length, {0.0, 100.0, Bounds::right_closed}, "m",
         "length of the rig (the grid)");
  o.real("grid-height", c.grid_height, {0.0, 100.0, Bounds::right_closed}, "m",
         "height of the rig (the grid)");
  o.real("depth", c.soil_depth, positive, "m",
         "soil depth h, at most --grid-height and --blade-height (the paper: 0.15, 0.25, 0.35)");
  o.real("blade-height", c.blade_height, positive, "m", "blade height, at most --grid-height");
  o.real("blade-thickness", c.blade_thickness, positive, "m", "blade thickness");
  o.real("blade-start", c.blade_start, non_negative, "m", "x of the blade's back face at rest");
  o.real("speed", c.blade_speed, positive, "m/s", "blade speed");
  o.real("travel", c.travel, positive, "m",
         "blade travel simulated; --average-from, --average-to and --profile-at lie within it");
  o.real("rig-width", c.rig_width, positive, "m",
         "width between the glass panels, for forces in N");
  o.real("gravity", c.gravity, {0.0, 1000.0, Bounds::right_closed}, "m/s^2", "gravity g");
  o.choice("floor", c.floor, {"fixed", "friction"},
           "rig floor under the soil: fixed (the paper's: no velocity at the floor nodes) or "
           "friction (a Coulomb wall at --floor-friction, on which the blade scrapes it clean)");
  o.real("floor-friction", c.floor_friction_deg, {0.0, 90.0, Bounds::left_closed}, "deg",
         "friction angle of the floor with --floor friction (steel: the blade's 14)");
  o.real("rig-angle", c.rig_angle_deg, {-45.0, 45.0, Bounds::closed}, "deg",
         "the whole rig (floor, walls, blade, its motion and gravity) turned by this angle "
         "against the grid, counter-clockwise; the floor and side walls are then rigid bodies "
         "(the paper's mesh-orientation study: 35)");
  o.group("Numerics");
  o.flag("start-of-step-contact", c.start_of_step_contact,
         "contact also corrects the start-of-step velocity (Nairn, Hammerquist and Smith 2020)");
  o.flag("gap-check", c.gap_check,
         "contact only where the material would reach the blade within the step");
  o.custom(
      "mesh", "NXxNY", "cells along x and y, e.g. 120x70 (sets --cells-x and --cells-y)",
      "whole numbers in [4, 100000]",
      [&c](std::string_view value, const std::string& where) {
        const auto x = value.find('x');
        std::int64_t nx = 0;
        std::int64_t ny = 0;
        using cosmpm::io::detail::IntegerParse;
        using cosmpm::io::detail::parse_integer;
        if (x == std::string_view::npos ||
            parse_integer(value.substr(0, x), nx) != IntegerParse::ok ||
            parse_integer(value.substr(x + 1), ny) != IntegerParse::ok) {
          throw cosmpm::Error(where + " = '" + cosmpm::io::detail::printable(value) +
                              "' is not NXxNY with whole numbers, e.g. 120x70");
        }
        if (nx < 4 || nx > 100000 || ny < 4 || ny > 100000) {
          throw cosmpm::Error(where + " = " + std::string(value) +
                              ": each count must be in [4, 100000]");
        }
        c.cells_x = static_cast<long>(nx);
        c.cells_y = static_cast<long>(ny);
      },
      [&c] { return std::to_string(c.cells_x) + "x" + std::to_string(c.cells_y); },
      Role::shorthand);
  o.integer("cells-x", c.cells_x, 4, 100000, "cells along x");
  o.integer("cells-y", c.cells_y, 4, 100000, "cells along y");
  o.integer("particles-per-cell", c.particles_per_cell, 1, 8, "particles per cell and axis");
  o.real("cfl", c.cfl, {0.0, 1.0, Bounds::right_closed}, "",
         "time step as a fraction of the stable one");
  o.real("flip", c.flip_fraction, {0.0, 1.0, Bounds::closed}, "",
         "FLIP share of the velocity update (1: FLIP, 0: PIC)");
  o.flag("separated-pic", c.separated_pic,
         "points whose grains have come apart (--separation) take the grid's velocity (PIC) "
         "instead of FLIP's: a lone point that falls onto the floor is stopped there instead of "
         "springing back faster than it came (docs/validation.md, \"Refinement\")");
  o.choice("stray-particles", c.stray_particles, {"stop", "freeze", "remove"},
           "a particle that leaves the rig (the grid): stop the run naming it, or take it out "
           "of the simulation, kept (freeze) or dropped (remove), counted in the summary");
  o.real("equilibrium-time", c.equilibrium_time, {0.0, 100.0, Bounds::closed}, "s",
         "damped settling under K0 before the blade moves");
  o.real("equilibrium-damping", c.equilibrium_damping, {0.0, 1.0, Bounds::left_closed}, "",
         "local damping while settling");
  o.real("damping", c.damping, {0.0, 1.0, Bounds::left_closed}, "", "local damping while cutting");
  o.group("Output");
  o.real("frame-interval", c.frame_interval, positive, "m", "blade travel between ParaView frames");
  o.real("average-from", c.average_from, non_negative, "m",
         "start of the draft average (the paper: 15-35 mm)");
  o.real("average-to", c.average_to, positive, "m", "end of the draft average");
  o.real("profile-at", c.profile_at, positive, "m",
         "travel of the blade stress profile (the paper's Fig. 9)");
  o.flag("frames", c.write_frames, "write ParaView frames");
  o.real("checkpoint-every", c.checkpoint_every, non_negative, "m",
         "blade travel between checkpoints (0: only when stopped by Ctrl-C or SIGTERM)");
  o.group("Run control");
  o.text("out", c.output_directory, "DIR",
         "output folder (default out/flat_blade/<tag of the case>)", Role::control);
  o.flag("replace", c.replace,
         "delete the results of an earlier run in the output folder before starting",
         Role::control);
  o.flag("restart", c.restart,
         "continue the stopped run in the output folder from its checkpoint (same settings)",
         Role::control);
  o.integer("threads", c.threads, 0, 4096, "OpenMP threads (0: all); results do not depend on it",
            Role::control);
  o.flag("check", c.check_only,
         "check the case and estimate the run (particles, steps, time), then stop; writes "
         "nothing",
         Role::control);
  o.flag("allow-large-run", c.allow_large_run,
         "start even when the run looks longer than a day or larger than the memory",
         Role::control);
}

// Checks that need more than one option; each message names the options to change. Sets
// `c.material` from auto and `c.polar`.
inline void validate(const Options& o, Case& c) {
  // --mesh and --cells-x/-y set the same counts: the command line may override a case file,
  // but one source may not give both.
  for (const char* cells : {"cells-x", "cells-y"}) {
    if (o.given("mesh") && o.origin(cells) == o.origin("mesh")) {
      o.fail("mesh", std::string("and --") + cells + " set the same count; give one of them");
    }
  }
  using Origin = Options::Origin;
  if (c.material == "auto") {
    c.material = c.polar ? "cosserat-drucker-prager" : "mohr-coulomb";
  } else if (c.polar != c.is_polar() && o.given("polar")) {
    // --polar on the command line overrides the model of a case file (case.used names both).
    if (o.origin("polar") == Origin::command_line && o.origin("material") == Origin::case_file) {
      c.material = c.polar ? "cosserat-drucker-prager" : "mohr-coulomb";
    } else {
      o.fail("polar", "contradicts " + o.describe("material") +
                          " (the polar model is cosserat-drucker-prager); give one of them");
    }
  }
  c.polar = c.is_polar();
  if (!c.polar) {
    for (const char* name : {"gc-over-g", "length-scale", "micro-inertia", "micro-inertia-scale",
                             "blade-rotation", "grain-radius", "blade-rotation-fixed"}) {
      if (o.changed(name)) {
        o.fail(name, "applies to polar soil only; add --polar true or leave it out");
      }
    }
  }
  if (o.given("blade-rotation-fixed")) {
    // The older flag; where both are given, the command line overrides a case file.
    // case.used writes both, consistently; a file or command line that sets both differently
    // is ambiguous.
    const bool consistent = c.blade_rotation_fixed == (c.blade_rotation == "held");
    if (o.given("blade-rotation") &&
        o.origin("blade-rotation") == o.origin("blade-rotation-fixed") && !consistent) {
      o.fail("blade-rotation-fixed",
             "and " + o.describe("blade-rotation") + " disagree; give --blade-rotation only");
    }
    if (!o.given("blade-rotation") ||
        (o.origin("blade-rotation-fixed") == Origin::command_line && !consistent)) {
      c.blade_rotation = c.blade_rotation_fixed ? "held" : "free";
    }
  }
  c.blade_rotation_fixed = c.blade_rotation == "held";  // case.used says the same
  if (c.blade_rotation != "coupled" && o.changed("grain-radius")) {
    o.fail("grain-radius", "applies to --blade-rotation coupled only; add it or leave this out");
  }
  if (c.material == "mohr-coulomb" && o.changed("cone")) {
    o.fail("cone", "applies to the Drucker-Prager models only (--material is mohr-coulomb)");
  }
  if (c.transfer == "apic" && c.flip_fraction != 1.0) {
    o.fail("flip",
           "blends FLIP into --transfer apic, which has no FLIP part; leave --flip at 1 "
           "or use --transfer flip-blend");
  }
  if (c.polar && c.antilocking != "none") {
    o.fail("antilocking", "applies to nonpolar soil only (--polar true); leave it at none");
  }
  const bool separable = c.material == "mohr-coulomb" && c.cohesion == 0.0;
  if (c.separated_pic && c.transfer == "apic") {
    o.fail("separated-pic",
           "has nothing to do with --transfer apic, whose velocity is PIC "
           "already; leave it false or use --transfer flip-blend");
  }
  if (c.separation_choice == "true" && !separable) {
    o.fail("separation", "is implemented for --material mohr-coulomb with --cohesion 0 only");
  }
  c.separation = c.separation_choice == "true" || (c.separation_choice == "auto" && separable);
  if (c.separated_pic && !c.separation) {
    o.fail("separated-pic",
           "needs points that can come apart: --separation (on for cohesionless "
           "--material mohr-coulomb)");
  }
  if (c.dilatancy_cutoff > 0.0 && c.material != "mohr-coulomb") {
    o.fail("dilatancy-cutoff", "is implemented for --material mohr-coulomb only; leave it at 0");
  }
  if (c.dilatancy_angle_deg > c.friction_angle_deg) {
    o.fail("psi", "exceeds " + o.describe("phi") + "; lower --psi or raise --phi");
  }
  if (c.wall_friction_deg > c.friction_angle_deg) {
    o.fail("delta",
           "exceeds " + o.describe("phi") + " (the Sokolovski reference needs delta <= phi)");
  }
  if (c.blade_height > c.grid_height) {
    o.fail("blade-height",
           "exceeds " + o.describe("grid-height") + "; lower one or raise the other");
  }
  if (c.soil_depth > c.blade_height) {
    o.fail("depth",
           "exceeds " + o.describe("blade-height") + ": the soil would flow over the blade");
  }
  const double room = c.grid_length - c.blade_start - c.blade_thickness;
  if (!(c.travel < room)) {
    o.fail("travel",
           "does not fit the rig: the blade's face starts at --blade-start + "
           "--blade-thickness = " +
               cosmpm::io::detail::format_number_exact(c.blade_start + c.blade_thickness) +
               " m and " + o.describe("grid-length") + "; shorten --travel or lengthen the rig");
  }
  const std::string window =
      "; the draft average --average-from .. --average-to must lie within "
      "the travel: lower them with it (e.g. --average-from 0 --average-to " +
      cosmpm::io::detail::format_number_exact(c.travel) + ") or raise --travel";
  if (c.average_to > c.travel) o.fail("average-to", "lies beyond " + o.describe("travel") + window);
  if (!(c.average_from < c.average_to)) {
    o.fail("average-from", "is not below " + o.describe("average-to") + window);
  }
  if (c.profile_at > c.travel) {
    o.fail("profile-at", "lies beyond " + o.describe("travel") +
                             "; lower --profile-at with --travel (e.g. to " +
                             cosmpm::io::detail::format_number_exact(c.travel) + ")");
  }
  if (c.floor != "friction" && o.changed("floor-friction")) {
    o.fail("floor-friction", "applies to --floor friction only; add it or leave this out");
  }
  if (c.replace && c.restart) o.fail("restart", "and --replace true exclude each other");
}

}  // namespace flat_blade
