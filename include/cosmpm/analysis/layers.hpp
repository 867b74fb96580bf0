#pragma once
// Coloured layers for flow patterns (the paper's Figs. 1-2): horizontal layers of equal
// thickness counted upwards from a base level, by each particle's INITIAL position, so the
// colour sticks to the material however it flows:
//   layer_p = floor((y0_p - base) / thickness),   0 for the bottom layer.
// A particle that starts below the base is an error (its layer would be negative).
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <vector>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

struct LayerOptions {
  double thickness = 0.05;  // m
  double base = 0.0;        // level of the bottom of layer 0, m
  int axis = 1;             // the vertical axis
};

// Layer of each position in `initial_positions`.
template <int Dim>
std::vector<std::int32_t> layer_index(std::span<const Vec<Dim>> initial_positions,
                                      const LayerOptions& options) {
  const char* where = "analysis::layer_index";
  require_positive(where, "thickness", options.thickness);
  require_in_range(where, "axis", options.axis, 0, Dim - 1, Bounds::closed);
  std::vector<std::int32_t> layer(initial_positions.size());
  for (std::size_t p = 0; p < initial_positions.size(); ++p) {
    const double level = (initial_positions[p][options.axis] - options.base) / options.thickness;
    if (!(level >= 0.0 && level < 2e9)) {
      std::ostringstream message;
      message << where << ": particle " << p << " starts at coordinate "
              << initial_positions[p][options.axis] << " on axis " << options.axis
              << ", below the base " << options.base
              << " or too far above it (valid: base <= y0 < base + 2e9 thickness)";
      throw Error(message.str());
    }
    layer[p] = static_cast<std::int32_t>(std::floor(level));
  }
  return layer;
}

// Layer of each particle of a store or a simulation, from its initial position.
template <class Source>
std::vector<std::int32_t> layer_index(const Source& source, const LayerOptions& options) {
  constexpr int Dim = detail::dimension_of<Source>;
  const auto& x0 =
      detail::particles_of(source).template get<particles::field::InitialPosition<Dim>>();
  return layer_index<Dim>(std::span<const Vec<Dim>>(x0), options);
}

}  // namespace cosmpm::analysis
