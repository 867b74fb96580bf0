#pragma once
// Update Stress Last, the paper's Appendix: stress updated at the end of the step from the new
// grid velocity. The grid-to-particle map runs the velocity gradient and the stress update in
// the same pass (one sweep over the particles instead of three, at the same start-of-step
// stencil).
#include "cosmpm/integrator/concept.hpp"

namespace cosmpm::integrator {

struct USL {
  static constexpr const char* name() { return "USL"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_and_update_grid(dt);  // map_to_grid(true), update_grid(dt)
    sim.map_to_particles(dt, /*with_stress_update=*/true);
  }
};

}  // namespace cosmpm::integrator
