#pragma once
// Compositions that do not hold for a free-surface flow to rest. A dry column released under
// gravity (docs/validation.md, "Granular flow to rest", 96 runs) stopped before rest with
//   - shape::Linear: 16 of 24 runs (4 of 12 even with a FLIP fraction of 0.99): the gradient
//     jumps where a particle crosses a cell edge, which compresses dilated particles into
//     det F <= 0;
//   - pure FLIP (transfer::FlipBlend with flip_fraction = 1): 25 of 48 runs, every USL run
//     among them, and the rest left a dilated tail running ahead of the deposit;
// minutes into the run. With SimulationParameters::free_surface_flow set, the Simulation's
// constructor says so up front; allow_fragile_composition runs them anyway (to reproduce a
// paper made with them, or to study the failure).
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/simulation/parameters.hpp"

namespace cosmpm {

// Why a composition is not expected to hold for a free-surface flow to rest; empty if none is
// known. Independent of SimulationParameters::free_surface_flow, so a caller can ask.
template <class Kernel, class Transfer, int Dim>
std::vector<std::string> free_surface_flow_concerns(const SimulationParameters<Dim>& parameters) {
  std::vector<std::string> concerns;
  if constexpr (!shape::has_continuous_gradient<Kernel>) {
    concerns.push_back(
        "the kernel's gradient jumps where a particle crosses a cell edge (shape::Linear): 16 "
        "of 24 such flows stopped with det F <= 0, 4 of 12 at a FLIP fraction of 0.99; use "
        "shape::GIMP, QuadraticBSpline or CubicBSpline");
  }
  if (!Transfer::affine && parameters.flip_fraction_or_default() == 1.0) {
    concerns.push_back(
        "pure FLIP (flip_fraction = 1) keeps particle velocities the grid no longer has: 25 "
        "of 48 such flows stopped, every USL one, and the others left a dilated tail ahead of "
        "the deposit; leave flip_fraction unset (0.99) or use transfer::APIC");
  }
  return concerns;
}

// Throws if parameters.free_surface_flow is set, a concern is known and
// allow_fragile_composition is not set.
template <class Kernel, class Transfer, int Dim>
void check_free_surface_flow(const SimulationParameters<Dim>& parameters) {
  if (!parameters.free_surface_flow || parameters.allow_fragile_composition) return;
  const auto concerns = free_surface_flow_concerns<Kernel, Transfer>(parameters);
  if (concerns.empty()) return;
  std::string message =
      "Simulation: this composition is not expected to hold for a free-surface flow to rest "
      "(SimulationParameters::free_surface_flow; docs/validation.md, \"Granular flow to "
      "rest\"):";
  for (const auto& concern : concerns) message += "\n  - " + concern;
  message += "\n(set allow_fragile_composition to run it anyway)";
  throw Error(message);
}

}  // namespace cosmpm
