#pragma once
// Yield-point maps (Coetzee 2014, Fig. 12): which particles have a stress state on the yield
// surface. Two readings:
//  - yield_points: from the stress, f(sigma) >= -tolerance |sigma| with f the model's yield
//    function (in stress units, <= 0 inside) and |sigma| the Euclidean norm of the stress
//    components. The map of a stress field, whenever it was reached (a cohesionless point at
//    zero stress sits on the apex, so it counts).
//  - plastic_points: the state flag `plastic` the model set at its last update (1 when that
//    update returned to the surface): the points that yielded in the last step.
// At rest the two differ: a point that stopped on the surface has f = 0 but its last update,
// with a vanishing increment, may be elastic.
#include <concepts>
#include <cstdint>
#include <span>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

template <class Model>
concept HasYieldFunction = requires(const Model& model, const typename Model::stress_type& s) {
  { model.yield_function(s) } -> std::convertible_to<double>;
};

// 1 where the stress is on (or, within the tolerance, at) the yield surface.
template <HasYieldFunction Model>
std::vector<std::uint8_t> yield_points(const Model& model,
                                       std::span<const typename Model::stress_type> stress,
                                       double relative_tolerance = 1e-6) {
  require_in_range("analysis::yield_points", "relative_tolerance", relative_tolerance, 0.0, 1.0,
                   Bounds::left_closed);
  std::vector<std::uint8_t> on_surface(stress.size());
  for (std::size_t p = 0; p < stress.size(); ++p) {
    const double f = static_cast<double>(model.yield_function(stress[p]));
    on_surface[p] = f >= -relative_tolerance * static_cast<double>(stress[p].norm()) ? 1 : 0;
  }
  return on_surface;
}

template <class Sim>
requires HasYieldFunction<typename Sim::model_type> std::vector<std::uint8_t> yield_points(
    const Sim& sim, double relative_tolerance = 1e-6) {
  using Model = typename Sim::model_type;
  const auto& stress = sim.particles().template get<particles::field::Stress<Model>>();
  return yield_points(sim.model(), std::span<const typename Model::stress_type>(stress),
                      relative_tolerance);
}

// 1 where the model's last update was plastic (state.plastic, material::PlasticState).
template <class State>
requires requires(const State& state) {
  state.plastic;
}
std::vector<std::uint8_t> plastic_points(std::span<const State> states) {
  std::vector<std::uint8_t> plastic(states.size());
  for (std::size_t p = 0; p < states.size(); ++p) plastic[p] = states[p].plastic > 0.5 ? 1 : 0;
  return plastic;
}

template <class Sim>
requires requires {
  typename Sim::model_type::state_type;
}
std::vector<std::uint8_t> plastic_points(const Sim& sim) {
  using Model = typename Sim::model_type;
  const auto& state = sim.particles().template get<particles::field::MaterialState<Model>>();
  return plastic_points(std::span<const typename Model::state_type>(state));
}

}  // namespace cosmpm::analysis
