#pragma once
// The run-time settings of a simulation and the stable time step.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace cosmpm {

// What happens to a particle that leaves the grid box (a stray): never silently dropped.
enum class StrayParticles {
  stop,    // the run stops with an error naming the particle, its position and velocity
  freeze,  // it leaves the simulation and is kept as it was (Simulation::frozen_particles())
  remove,  // it leaves the simulation and is dropped
};
// freeze and remove count the strays and their mass (Simulation::stray_particles()); a
// particle with a non-finite position or velocity always stops the run (it is unstable, not
// stray).

template <int Dim>
struct SimulationParameters {
  Vec<Dim> gravity = Vec<Dim>::Zero();
  // Fraction of FLIP in transfer::FlipBlend's particle velocity update: 1 = FLIP (the paper's
  // Eq. 18), 0 = PIC. Unset: default_flip_fraction. transfer::APIC takes none (it has no
  // FLIP part); setting anything but 1 with it is an error.
  std::optional<double> flip_fraction;
  // 0.99: pure FLIP keeps particle velocities next to fixed nodes and lets dilated particles
  // run ahead and blow up in flows to rest; 0.99 removed both in every smooth-kernel run of
  // docs/validation.md, "Granular flow to rest" (which also gives its cost: damping).
  static constexpr double default_flip_fraction = 0.99;
  double flip_fraction_or_default() const { return flip_fraction.value_or(default_flip_fraction); }
  // Points whose grains have come apart (a model with separation, state.separation > 0) take
  // the grid's velocity (PIC) instead of the FLIP update. Such a point carries no stress, and
  // under FLIP it keeps the velocity it brought onto a fixed node (whose acceleration is zero):
  // compressed until its gap closes, it springs back faster than it came (a point falling
  // behind the flat blade left the rig at 5 m/s, docs/validation.md, "Refinement"). PIC takes
  // its velocity relative to the grid away, as inelastic grain collisions do. Off: the
  // transfer's update for every point (APIC's is PIC already).
  bool pic_where_separated = false;
  // Cundall local non-viscous damping coefficient on the nodal unbalanced force, in [0, 1).
  double damping = 0.0;
  // Time step; 0 means cfl * stable_time_step().
  double time_step = 0.0;
  double cfl = 0.5;
  // A requested time step above the stable one is an error unless this is set.
  bool allow_unstable_time_step = false;
  // OpenMP threads; 0 means OpenMP's default. Results do not depend on it.
  int threads = 0;
  // Nodes lighter than this fraction of a typical particle mass are treated as empty.
  double empty_node_mass_fraction = 1e-12;
  StrayParticles stray_particles = StrayParticles::stop;
  // Declares a free-surface flow that runs far and comes to rest (a column collapse, a slope
  // failure): the Simulation's constructor then rejects, naming why, the compositions that
  // failed such flows in docs/validation.md, "Granular flow to rest"
  // (simulation/free_surface_checks.hpp), unless allow_fragile_composition is also set.
  bool free_surface_flow = false;
  bool allow_fragile_composition = false;
};

template <int Dim>
void validate(const SimulationParameters<Dim>& parameters) {
  if (parameters.flip_fraction) {
    require_in_range("SimulationParameters", "flip_fraction", *parameters.flip_fraction, 0.0, 1.0,
                     Bounds::closed);
  }
  require_in_range("SimulationParameters", "damping", parameters.damping, 0.0, 1.0,
                   Bounds::left_closed);
  require_in_range("SimulationParameters", "cfl", parameters.cfl, 0.0, 1.0, Bounds::right_closed);
  require_non_negative("SimulationParameters", "time_step", parameters.time_step);
  require_in_range("SimulationParameters", "threads", parameters.threads, 0, 4096, Bounds::closed);
  require_in_range("SimulationParameters", "empty_node_mass_fraction",
                   parameters.empty_node_mass_fraction, 0.0, 1.0, Bounds::left_closed);
  for (int d = 0; d < Dim; ++d) {
    require(std::isfinite(parameters.gravity[d]),
            "SimulationParameters: gravity has a non-finite component");
  }
}

// Largest stable step of a composition: the p-wave crosses the smallest cell at most once,
// and the continuum's own bound (its rotational degrees of freedom) holds.
template <int Dim, class Continuum>
double stable_time_step(const Continuum& continuum, const grid::Grid<Dim>& grid,
                        double max_density) {
  require(max_density > 0.0, "Simulation::stable_time_step: no particles have been added");
  const double wave_speed = std::sqrt(continuum.model().p_wave_modulus() / max_density);
  const double stable = grid.min_cell_size() / wave_speed;
  return std::min(stable, continuum.stable_time_step(grid, max_density));
}

// The step a run uses: the requested one, checked against the stable one.
template <int Dim>
double choose_time_step(const SimulationParameters<Dim>& parameters, double stable) {
  if (parameters.time_step == 0.0) return parameters.cfl * stable;
  if (parameters.time_step > stable && !parameters.allow_unstable_time_step) {
    throw Error("SimulationParameters: time_step = " + detail::format_number(parameters.time_step) +
                " s is above the stable time step " + detail::format_number(stable) +
                " s (valid range (0, " + detail::format_number(stable) +
                "]; set allow_unstable_time_step to override)");
  }
  return parameters.time_step;
}

}  // namespace cosmpm
