#pragma once
// The integrator concept. An explicit update scheme is a type that composes the engine's
// public stages (Simulation::map_to_grid, update_grid, map_to_particles, ...) into one step:
//
//   struct MyScheme {
//     static constexpr const char* name() { return "my scheme"; }
//     template <class Sim> static void step(Sim& sim, double dt) { ... stages ... }
//   };
//
// The simulation runs the bookkeeping around it (contact law advance, clock). A scheme is one
// file of its own; the engine needs no change (see integrator/usl.hpp for the smallest one).
#include <concepts>

namespace cosmpm::integrator {

template <class I>
concept Integrator = requires {
  { I::name() } -> std::convertible_to<const char*>;
};

// Whether scheme I can advance simulation Sim by one step.
template <class I, class Sim>
concept IntegratorFor = Integrator<I> && requires(Sim& sim, double dt) {
  I::step(sim, dt);
};

}  // namespace cosmpm::integrator
