#pragma once
// USL and MUSL with fewer particle passes per step: the pass that ends a step also maps the
// particles to the grid for the next one (stages/fused_pass.hpp), and the next step takes the
// node fields from those records; MUSL's grid-to-particle map also remaps the momenta in the
// same pass, and its stress update gathers the velocity gradient in its own pass. Opt-in: the nodal
// sums take the unfused schemes' terms in another order, so results differ from USL's and MUSL's by
// rounding; they are the same on one thread and on two, and the fused pass itself runs on at most
// two. The unfused schemes and their stages stay as they are.
//
// Between steps, take the particles for writing through Simulation::particles() (or
// continuum(), engine()) each time: that call drops the records the last pass scattered. A
// reference kept from an earlier call and written through after a step is not seen.
#include "cosmpm/integrator/concept.hpp"

namespace cosmpm::integrator {

struct FusedUSL {
  static constexpr const char* name() { return "fused USL"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_or_reuse_and_update_grid(dt);  // map_to_grid_or_reuse(), update_grid(dt)
    sim.map_to_particles_and_grid(dt);
  }
};

struct FusedMUSL {
  static constexpr const char* name() { return "fused MUSL"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_or_reuse_and_update_grid(dt);  // map_to_grid_or_reuse(), update_grid(dt)
    sim.map_to_particles_and_remap(dt);
    sim.update_stress_and_map_to_grid(dt, sim.nodes().velocity, sim.nodes().spin);
  }
};

}  // namespace cosmpm::integrator
