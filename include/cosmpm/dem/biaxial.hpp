#pragma once
// A servo-controlled biaxial test (PFC's classic): grains placed on a lattice in a box of four
// frictionless plane walls, compacted isotropically to the confining stress by servo-controlled
// walls, then sheared by moving the top and bottom platens together at a constant strain rate
// while the side walls keep the confining stress. It reports the mobilised friction angle
// sin(phi) = (s1 - s3) / (s1 + s3) against the axial strain: its peak, and its mean over the
// last part of the test (the critical state, where the volume has stopped changing).
//
// Servo (PFC): a wall moves along its normal with v = G (s_target - s_wall), with
// G = alpha L / (k N_c dt) (L: the wall's length, N_c: its contacts, k: the wall contact's
// k_n + k_s), at most 2 % of the smallest radius per step; while shearing, the side walls add
// the integral of their error (over 200 steps), so they do not lag behind the sample's dilation.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/damping.hpp"
#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace cosmpm::dem {

struct BiaxialSettings {
  Index particles = 2000;
  double aspect = 2.0;                 // initial height / width of the lattice
  double confining_stress = 5e3;       // Pa, s3
  double axial_strain = 0.2;           // at the end of shearing
  double strain_rate = 0.5;            // 1/s, platens' approach over the sample height
  double critical_from = 0.75;         // critical state: mean over strains >= this x axial_strain
  double local_damping = 0.7;          // PFC's default
  double servo_gain = 0.5;             // alpha
  double time_step_fraction = 0.8;     // of the critical time step
  double compaction_tolerance = 0.01;  // relative stress error that ends the compaction
  double max_compaction_time = 3.0;    // s
  int record_every = 50;               // steps
  int threads = 0;
  std::uint64_t seed = 7;
};

struct BiaxialPoint {
  double axial_strain = 0.0;       // shortening / initial height
  double volumetric_strain = 0.0;  // (A - A0) / A0: dilation positive
  double sigma1 = 0.0;             // Pa, compression positive (platens)
  double sigma3 = 0.0;             // Pa (side walls)
  double friction_angle_deg = 0.0;
};

struct BiaxialResult {
  std::vector<BiaxialPoint> curve;
  double peak_angle_deg = 0.0;
  double peak_strain = 0.0;
  double critical_angle_deg = 0.0;
  double critical_dilatancy = 0.0;  // d(volumetric) / d(axial) over the critical window
  double porosity = 0.0;            // after compaction
  double compaction_time = 0.0;     // simulated, s
  bool compacted = false;
  std::int64_t steps = 0;
  Index particles = 0;
};

// `compaction_law`, if given, acts during the isotropic compaction (PFC's practice: compact
// with low friction for a denser sample), and `law` during the shearing.
template <class Law>
BiaxialResult biaxial_test(const Law& law, const Grains& grains, const BiaxialSettings& s,
                           const std::function<void(double)>& progress = {},
                           const std::optional<Law>& compaction_law = std::nullopt) {
  const char* where = "dem::biaxial_test";
  grains.validate(where);
  require_in_range(where, "particles", static_cast<double>(s.particles), 16.0, 1e8, Bounds::closed);
  require_positive(where, "aspect", s.aspect);
  require_positive(where, "confining stress [Pa]", s.confining_stress);
  require_in_range(where, "axial strain", s.axial_strain, 0.0, 0.5, Bounds::right_closed);
  require_positive(where, "strain rate [1/s]", s.strain_rate);
  require_in_range(where, "critical_from", s.critical_from, 0.0, 1.0);
  require_in_range(where, "time step fraction", s.time_step_fraction, 0.0, 1.0,
                   Bounds::right_closed);
  require_in_range(where, "record_every", s.record_every, 1, 1e9, Bounds::closed);

  // The sample: a lattice filling the box.
  const double spacing = 1.02 * 2.0 * grains.shape.bounding_radius() * grains.max_size;
  const auto columns = std::max<Index>(
      4, static_cast<Index>(std::lround(std::sqrt(static_cast<double>(s.particles) / s.aspect))));
  const Index rows = (s.particles + columns - 1) / columns;
  const double width = static_cast<double>(columns) * spacing;
  const double height = static_cast<double>(rows) * spacing;
  Assembly assembly;
  rain(assembly, grains, s.particles, {0.0, width * (1.0 + 1e-12), 0.0, height * (1.0 + 1e-12)},
       s.seed);

  Parameters parameters;
  parameters.gravity = Vec<2>::Zero();
  parameters.threads = s.threads;
  Simulation<Law, LocalDamping> sim(std::move(assembly), law, LocalDamping(s.local_damping),
                                    parameters);
  auto smooth = law.particle_material();
  smooth.friction = 0.0;
  const Index bottom = sim.add_plane_wall("bottom", Vec<2>(0, 0), Vec<2>(0, 1), smooth);
  const Index top = sim.add_plane_wall("top", Vec<2>(0, height), Vec<2>(0, -1), smooth);
  const Index left = sim.add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), smooth);
  const Index right = sim.add_plane_wall("right", Vec<2>(width, 0), Vec<2>(-1, 0), smooth);
  const double dt = s.time_step_fraction * sim.critical_time_step();
  if (compaction_law) sim.set_law(*compaction_law);
  const double r_min = sim.assembly().min_radius();
  const double wall_stiffness = Law::time_step_stiffness(law.wall_constants(smooth), r_min);

  auto span = [&](Index a, Index b) {
    return std::abs((sim.walls()[b].point - sim.walls()[a].point).dot(sim.walls()[a].normal));
  };
  // Compressive stress on wall w: the particles' force against its normal over its length.
  auto stress = [&](Index w) {
    const double length = (w == left || w == right) ? span(bottom, top) : span(left, right);
    return -sim.wall_force(w).dot(sim.walls()[w].normal) / length;
  };
  // While shearing, the side walls also integrate their error (over 200 steps): a purely
  // proportional servo lags by v / G, 5 % of s3 at 0.5/s.
  std::vector<double> integral(4, 0.0);
  bool integrate = false;
  auto servo = [&](Index w, double target) {
    const double length = (w == left || w == right) ? span(bottom, top) : span(left, right);
    const double contacts = std::max(1, sim.walls()[w].contacts);
    const double gain = s.servo_gain * length / (wall_stiffness * contacts * dt);
    const double cap = 0.02 * r_min / dt;
    const double error = target - stress(w);
    if (integrate) integral[static_cast<std::size_t>(w)] += error / 200.0;
    const double speed =
        std::clamp(gain * (error + integral[static_cast<std::size_t>(w)]), -cap, cap);
    sim.walls().set_velocity(w, speed * sim.walls()[w].normal);
  };

  BiaxialResult result;
  result.particles = s.particles;
  const double target = s.confining_stress;
  // Isotropic compaction.
  while (sim.time() < s.max_compaction_time) {
    for (const Index w : {bottom, top, left, right}) servo(w, target);
    sim.step(dt);
    if (sim.step_count() % 50 == 0) {
      bool close = sim.unbalanced_force_ratio() < 0.01;
      for (const Index w : {bottom, top, left, right}) {
        close = close && std::abs(stress(w) - target) < s.compaction_tolerance * target;
      }
      if (progress) progress(0.5 * sim.time() / s.max_compaction_time);
      if (close) {
        result.compacted = true;
        break;
      }
    }
  }
  result.compaction_time = sim.time();
  const double inset = 2.0 * sim.assembly().max_radius();
  result.porosity = porosity(
      sim.assembly(),
      Vec<2>(sim.walls()[left].point[0] + inset, sim.walls()[bottom].point[1] + inset),
      Vec<2>(sim.walls()[right].point[0] - inset, sim.walls()[top].point[1] - inset), 0.2 * r_min);

  // Shearing at constant platen speed, sides servo-controlled.
  if (compaction_law) sim.set_law(law);
  const double h0 = span(bottom, top);
  const double area0 = h0 * span(left, right);
  const double platen_speed = 0.5 * s.strain_rate * h0;
  sim.walls().set_velocity(bottom, Vec<2>(0.0, platen_speed));
  sim.walls().set_velocity(top, Vec<2>(0.0, -platen_speed));
  integrate = true;
  for (;;) {
    servo(left, target);
    servo(right, target);
    sim.step(dt);
    const double strain = (h0 - span(bottom, top)) / h0;
    if (sim.step_count() % s.record_every == 0 || strain >= s.axial_strain) {
      BiaxialPoint p;
      p.axial_strain = strain;
      p.volumetric_strain = span(bottom, top) * span(left, right) / area0 - 1.0;
      p.sigma1 = 0.5 * (stress(bottom) + stress(top));
      p.sigma3 = 0.5 * (stress(left) + stress(right));
      p.friction_angle_deg = radians_to_degrees(
          std::asin(std::clamp((p.sigma1 - p.sigma3) / (p.sigma1 + p.sigma3), -1.0, 1.0)));
      result.curve.push_back(p);
      if (progress) progress(0.5 + 0.5 * strain / s.axial_strain);
    }
    if (strain >= s.axial_strain) break;
  }
  result.steps = sim.step_count();

  double sum = 0.0, n = 0.0, se = 0.0, sv = 0.0, see = 0.0, sev = 0.0;
  for (const BiaxialPoint& p : result.curve) {
    if (p.friction_angle_deg > result.peak_angle_deg) {
      result.peak_angle_deg = p.friction_angle_deg;
      result.peak_strain = p.axial_strain;
    }
    if (p.axial_strain >= s.critical_from * s.axial_strain) {
      sum += p.friction_angle_deg;
      n += 1.0;
      se += p.axial_strain;
      sv += p.volumetric_strain;
      see += p.axial_strain * p.axial_strain;
      sev += p.axial_strain * p.volumetric_strain;
    }
  }
  if (n > 0) result.critical_angle_deg = sum / n;
  if (n > 1) result.critical_dilatancy = (n * sev - se * sv) / (n * see - se * se);
  return result;
}

}  // namespace cosmpm::dem
