#pragma once
// Prandtl's strip footing on a weightless Tresca layer, the set-up shared by example 05 and the
// anti-locking verification test (tests/continuum/antilocking_strip_footing.test.cpp).
//
// Half the problem by symmetry: the soil fills [0, half_domain] x [0, depth] (x = 0 the footing's
// axis, a roller; the far side a roller; the base fixed), with a layer of empty cells above the
// surface for the heave. A rigid footing of half-width b = B / 2, a contact::RigidContact box
// whose bottom starts on the surface y = depth, moves down at a constant slow velocity; smooth
// (frictionless Coulomb contact) or rough (no slip). No gravity: the collapse pressure of a
// weightless Tresca layer is q_u = (2 + pi) c for a smooth and a rough footing alike (Prandtl
// 1920; the rough footing's wedge moves with it, the same mechanism). The pressure is
// -F_y / b, F the force the footing applies to the material (the half domain carries half of
// it), averaged over each settlement interval to smooth the explicit step-to-step noise.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/continuum/antilocking.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace strip_footing {

inline constexpr double prandtl_factor = 2.0 + 3.14159265358979323846;  // q_u / c = 5.1416

struct Case {
  double width = 1.0;            // B (m), the full footing width
  int cells_per_half_width = 4;  // b / h
  double half_domain = 2.5;      // soil half-width / B (the mechanism reaches 1.5 B)
  double depth = 1.5;            // soil depth / B (the mechanism reaches 0.71 B)
  double cohesion = 10e3;        // c = undrained strength (Pa)
  double stiffness_ratio = 300;  // E / c
  double poisson_ratio = 0.49;   // nearly incompressible (undrained)
  double density = 1000;         // kg/m^3; only the time scale depends on it
  double velocity = 0.01;        // footing speed (m/s)
  double settlement = 0.08;      // final settlement / B
  double sample_every = 0.0025;  // settlement / B between samples of the averaged pressure
  // Cundall local damping: none by default. It acts on the contact nodes' unbalanced force
  // too, so the force RigidContact records there is (1 + damping) times the soil's resistance
  // (docs/verification/strip_footing.md); slow loading and the PIC part of the velocity blend
  // keep the run quasi-static instead.
  double damping = 0.0;
  bool rough = false;                 // false: smooth footing (frictionless contact)
  bool gap_check = true;              // contact only where the material reaches the footing
  bool start_of_step_contact = true;  // Nairn, Hammerquist and Smith (2020)
  double flip_fraction = 0.9;         // PIC/FLIP blend: 10 % PIC damps the ringing
  int particles_per_cell = 2;         // per direction
  int threads = 1;

  double half_width() const { return width / 2; }
  double cell() const { return half_width() / cells_per_half_width; }
};

// Checks a case; every message names the value and its valid range.
inline void validate(const Case& c) {
  using cosmpm::Bounds;
  using cosmpm::require_in_range;
  using cosmpm::require_positive;
  const char* where = "strip_footing::Case";
  require_positive(where, "width", c.width);
  require_in_range(where, "cells_per_half_width", c.cells_per_half_width, 1, 256, Bounds::closed);
  require_in_range(where, "half_domain (in B)", c.half_domain, 1.5, 100.0, Bounds::closed);
  require_in_range(where, "depth (in B)", c.depth, 0.75, 100.0, Bounds::closed);
  require_positive(where, "cohesion", c.cohesion);
  require_positive(where, "stiffness_ratio", c.stiffness_ratio);
  require_positive(where, "density", c.density);
  require_positive(where, "velocity", c.velocity);
  require_in_range(where, "settlement (in B)", c.settlement, 0.0, 0.5, Bounds::right_closed);
  require_in_range(where, "sample_every (in B)", c.sample_every, 0.0, c.settlement,
                   Bounds::right_closed);
  require_in_range(where, "damping", c.damping, 0.0, 1.0, Bounds::left_closed);
  require_in_range(where, "particles_per_cell", c.particles_per_cell, 1, 8, Bounds::closed);
  // poisson_ratio is checked by the model.
}

// One point of the load-settlement curve: the mean over the settlement interval ending there.
struct Sample {
  double settlement = 0.0;  // / B
  double pressure = 0.0;    // / c, from the contact force
  // / c, from the particle stresses: in static equilibrium without body forces,
  // int sigma_yy dV = int y t_y dA over the boundary, and only the footing (at y_f, force F
  // on the material) contributes (the base at y = 0, the rollers and the free surface carry no
  // y t_y), so F = -sum_p sigma_yy V_p / y_f: an independent check of the contact force.
  double stress_pressure = 0.0;
};

// A particle at the end of the run (the mechanism).
struct ParticleState {
  cosmpm::Vec<2> position;
  cosmpm::Vec<2> displacement;
  double plastic_shear_strain = 0.0;
  double volume_ratio = 1.0;  // det F
  double mean_stress = 0.0;   // / c, (sxx + syy + szz) / 3, tension positive
};

struct Result {
  std::vector<Sample> curve;
  std::vector<ParticleState> final_particles;
  std::int64_t steps = 0;
  cosmpm::Index particles = 0;
  double time_step = 0.0;
};

using Soil = cosmpm::material::MohrCoulomb<double, 2>;

inline Soil tresca_soil(const Case& c) {
  return Soil({.youngs_modulus = c.stiffness_ratio * c.cohesion,
               .poisson_ratio = c.poisson_ratio,
               .friction_angle_deg = 0,
               .dilatancy_angle_deg = 0,
               .cohesion = c.cohesion});
}

// The mean footing pressure / c over the samples with settlement / B in [from, to]: the limit
// pressure where the curve has levelled off.
inline double mean_pressure(const std::vector<Sample>& curve, double from, double to) {
  double sum = 0.0;
  int count = 0;
  for (const auto& s : curve) {
    if (s.settlement >= from - 1e-12 && s.settlement <= to + 1e-12) {
      sum += s.pressure;
      ++count;
    }
  }
  if (count == 0) {
    throw cosmpm::Error("strip_footing::mean_pressure: no sample with settlement / B in [" +
                        cosmpm::detail::format_number(from) + ", " +
                        cosmpm::detail::format_number(to) + "]");
  }
  return sum / count;
}

// The grid's cells along x, in the soil along y, and above the soil (room for the heave).
struct Cells {
  cosmpm::Index x = 0, soil = 0, air = 0;
};
inline Cells cells_of(const Case& c) {
  const double h = c.cell();
  // Whole cells: the surface on a grid line, the footing's edge on a node.
  const auto cells = [&](double length) {
    return static_cast<cosmpm::Index>(std::lround(length / h));
  };
  return {cells(c.half_domain * c.width), cells(c.depth * c.width),
          std::max<cosmpm::Index>(2, cells(0.25 * c.width))};
}
inline cosmpm::Index particle_count(const Case& c) {
  const Cells n = cells_of(c);
  return n.x * n.soil * c.particles_per_cell * c.particles_per_cell;
}

// What a caller follows while a case runs (each may be empty).
struct Watch {
  std::function<void(double time, double end_time, std::int64_t step)> progress;  // every step
  std::function<void(const Sample&)> sample;  // every sample, as it is taken
};

// Runs the case with the continuum's anti-locking policy (antilocking::None or FBar) and the
// shape functions Kernel (the paper's linear by default).
template <class AntiLocking, class Kernel = cosmpm::shape::Linear>
Result run(const Case& c, const Watch& watch = {}) {
  using namespace cosmpm;
  validate(c);
  using Continuum = continuum::Classical<Soil, AntiLocking>;
  using Sim = Simulation<2, Kernel, Continuum, contact::RigidContact<2>, integrator::MUSL>;
  const double h = c.cell(), b = c.half_width();
  const Cells n = cells_of(c);
  const Index nx = n.x, ny_soil = n.soil, ny_air = n.air;
  const double soil_top = static_cast<double>(ny_soil) * h;
  const grid::Grid<2> grid(
      Vec<2>(0.0, 0.0),
      Vec<2>(static_cast<double>(nx) * h, static_cast<double>(ny_soil + ny_air) * h),
      {nx, ny_soil + ny_air});

  contact::RigidContact<2> footing_contact;
  // The footing spans the axis (x from -b to b); the part outside the grid is never touched.
  const int footing = footing_contact.add_body(
      contact::RigidBody<2>::box(Vec<2>(-b, soil_top), Vec<2>(b, soil_top + 0.5 * c.width))
          .set_velocity(Vec<2>(0.0, -c.velocity)),
      c.rough ? contact::Interface::no_slip() : contact::Interface::frictionless());
  // Contact only where the material reaches the footing within the step: without it the row
  // of nodes a cell below the footing follows it too (a footing a cell thicker, embedded).
  footing_contact.set_gap_check(c.gap_check);
  footing_contact.set_start_of_step_correction(c.start_of_step_contact);

  SimulationParameters<2> parameters;
  parameters.damping = c.damping;
  parameters.threads = c.threads;
  parameters.flip_fraction = c.flip_fraction;
  Sim sim(grid, tresca_soil(c), parameters, std::move(footing_contact));
  using BC = grid::BoundaryConditions<2>;
  sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::roller);  // the axis
  sim.boundary_conditions().set(BC::face(0, true), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::fixed);

  const auto soil = particles::seed_box(
      grid, Vec<2>(0.0, 0.0), Vec<2>(static_cast<double>(nx) * h, soil_top), c.particles_per_cell);
  sim.add_particles(soil.positions, soil.volume, c.density, soil.half_width);

  Result result;
  result.particles = sim.particles().size();
  result.time_step = sim.time_step();
  const double dt = result.time_step;
  const double end_time = c.settlement * c.width / c.velocity;
  const double sample_time = c.sample_every * c.width / c.velocity;
  const double footing_start = sim.contact().body(footing).lower_bound()[1];
  const auto& stress = sim.particles().template get<particles::field::Stress<Soil>>();
  const auto& volume = sim.particles().template get<particles::field::Volume>();
  double force_sum = 0.0, stress_force_sum = 0.0, next_sample = sample_time;
  std::int64_t steps_in_sample = 0;
  while (sim.time() < end_time - 0.5 * dt) {
    sim.step(dt);
    force_sum += -sim.contact().force_on_material(footing)[1];
    double stress_integral = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) stress_integral += stress[p][1] * volume[p];
    stress_force_sum += -stress_integral / sim.contact().body(footing).lower_bound()[1];
    ++steps_in_sample;
    if (sim.time() >= next_sample - 0.5 * dt) {
      const double settlement = footing_start - sim.contact().body(footing).lower_bound()[1];
      const double scale = static_cast<double>(steps_in_sample) * b * c.cohesion;
      result.curve.push_back({settlement / c.width, force_sum / scale, stress_force_sum / scale});
      if (watch.sample) watch.sample(result.curve.back());
      force_sum = stress_force_sum = 0.0;
      steps_in_sample = 0;
      next_sample += sample_time;
    }
    if (watch.progress) watch.progress(sim.time(), end_time, sim.step_count());
  }
  result.steps = sim.step_count();
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  const auto& x0 = sim.particles().template get<particles::field::InitialPosition<2>>();
  const auto& F = sim.particles().template get<particles::field::DeformationGradient<2>>();
  const auto& state = sim.particles().template get<particles::field::MaterialState<Soil>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    result.final_particles.push_back({x[p], x[p] - x0[p], state[p].plastic_shear_strain,
                                      F[p].determinant(),
                                      stress[p].template head<3>().mean() / c.cohesion});
  }
  return result;
}

}  // namespace strip_footing
