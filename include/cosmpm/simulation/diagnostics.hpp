#pragma once
// How the engine reports a step that failed. Loops that may run in parallel never throw:
// each records the first failing particle (lowest index, so the message does not depend on
// the thread count) and the stage throws one of these after the loop, naming the particle,
// its real position and velocity, the step and the cause.
#include <algorithm>
#include <cstdint>
#include <sstream>

#include <Eigen/LU>  // determinant

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm {

// The particles that left the grid box under StrayParticles::freeze or ::remove.
struct StrayReport {
  Index count = 0;    // since the start of the run
  double mass = 0.0;  // kg (per m of width in 2D)
  Index count_last_step = 0;
  double mass_last_step = 0.0;
};

// Where a step stands, for messages.
struct StepClock {
  double time = 0.0;  // at the start of the step
  std::int64_t step_count = 0;
};

// Keeps the lowest index. `first` is the thread's own copy when the loop is parallel (the
// reduction combines the copies).
inline void record_first(Index& first, Index p) {
  first = std::min(first, p);
}

namespace detail {

template <int Dim, class Store>
void describe_particle(std::ostringstream& message, const Store& particles, Index p) {
  const auto& x = particles.template get<particles::field::Position<Dim>>();
  const auto& v = particles.template get<particles::field::Velocity<Dim>>();
  message << "particle " << p << " at (" << x[p].transpose() << ") with velocity ("
          << v[p].transpose() << ")";
}

}  // namespace detail

// A particle whose stress came out non-finite or whose volume ratio det(F) is not positive.
template <int Dim, class Model, class Store>
[[noreturn]] void throw_unstable_stress(const Store& particles, Index p, const StepClock& clock) {
  const auto& F = particles.template get<particles::field::DeformationGradient<Dim>>();
  const auto& stress = particles.template get<particles::field::Stress<Model>>();
  std::ostringstream message;
  message << "Simulation: the run went unstable at step " << clock.step_count
          << " (t = " << clock.time << " s): ";
  detail::describe_particle<Dim>(message, particles, p);
  message << " has volume ratio det(F) = " << F[p].determinant()
          << " (valid range (0, inf)) and stress (" << stress[p].transpose()
          << ") (must be finite); reduce the time step or check the set-up";
  throw Error(message.str());
}

// A particle that left the open grid box, or whose position or velocity is not finite.
template <int Dim, class Store>
[[noreturn]] void throw_outside(const Store& particles, const grid::Grid<Dim>& grid, Index p,
                                const StepClock& clock) {
  const auto& x = particles.template get<particles::field::Position<Dim>>();
  const auto& v = particles.template get<particles::field::Velocity<Dim>>();
  std::ostringstream message;
  message.precision(10);
  if (!x[p].allFinite() || !v[p].allFinite()) {
    message << "Simulation: the run went unstable at step " << clock.step_count
            << " (t = " << clock.time << " s): ";
    detail::describe_particle<Dim>(message, particles, p);
    message << " is not finite; reduce the time step or check the set-up";
  } else {
    message << "Simulation: ";
    detail::describe_particle<Dim>(message, particles, p);
    message << " left the grid box [" << grid.origin().transpose() << "] + ["
            << grid.extent().transpose() << "] during step " << clock.step_count
            << " (t = " << clock.time << " s); the valid region is the open grid box";
  }
  throw Error(message.str());
}

}  // namespace cosmpm
