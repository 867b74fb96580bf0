#pragma once
// Update Stress First: the stress is updated from the grid velocity at the start of the step,
// then the forces of the new stress drive the momentum update.
#include "cosmpm/integrator/concept.hpp"

namespace cosmpm::integrator {

struct USF {
  static constexpr const char* name() { return "USF"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/false);
    sim.grid_velocity_from_momentum(dt);
    // nodes().momentum now holds the start velocity, spin_momentum the start spin.
    sim.update_stress_from_grid(dt, sim.nodes().momentum, sim.nodes().spin_momentum);
    sim.map_forces_to_grid();
    sim.update_grid(dt);
    sim.map_to_particles(dt);
  }
};

}  // namespace cosmpm::integrator
