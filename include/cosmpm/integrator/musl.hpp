#pragma once
// Modified USL (Sulsky et al. 1994): after the particles are updated, their new momenta are
// mapped back to the grid (with the start-of-step stencils, as the grid mass was) and the
// strain rate is taken from that smoothed velocity field.
#include "cosmpm/integrator/concept.hpp"

namespace cosmpm::integrator {

struct MUSL {
  static constexpr const char* name() { return "MUSL"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_and_update_grid(dt);  // map_to_grid(true), update_grid(dt)
    sim.map_to_particles(dt);
    sim.remap_momentum(dt);
    sim.update_stress_from_grid(dt, sim.nodes().velocity, sim.nodes().spin);
  }
};

}  // namespace cosmpm::integrator
