#pragma once
// The particle displacement ratio of Coetzee (2014), Sect. 3.3: "the ratio of the magnitude
// of the particle displacement vector to the magnitude of the blade displacement vector",
//   PDR_p = |x_p - x_p^ref| / |u_tool|.
// The paper marks PDR >= 0.15 at 15 mm of blade travel to show the slip line (its Fig. 11).
// The reference positions are where the particles stood when the tool started to move (the
// flat-blade example settles the layer first, so these are not the seeded positions).
#include <cstdint>
#include <span>
#include <vector>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

template <int Dim>
std::vector<double> displacement_ratio(std::span<const Vec<Dim>> positions,
                                       std::span<const Vec<Dim>> reference_positions,
                                       const Vec<Dim>& tool_displacement) {
  const char* where = "analysis::displacement_ratio";
  detail::require_same_size(where, "positions", positions.size(), "reference_positions",
                            reference_positions.size());
  const double travel = tool_displacement.norm();
  require_positive(where, "|tool_displacement| (m)", travel);
  std::vector<double> ratio(positions.size());
  for (std::size_t p = 0; p < positions.size(); ++p) {
    ratio[p] = (positions[p] - reference_positions[p]).norm() / travel;
  }
  return ratio;
}

// The ratio for the particles of a store or a simulation, against given reference positions
// (one per particle).
template <class Source>
std::vector<double> displacement_ratio(
    const Source& source, std::span<const Vec<detail::dimension_of<Source>>> reference_positions,
    const Vec<detail::dimension_of<Source>>& tool_displacement) {
  constexpr int Dim = detail::dimension_of<Source>;
  const auto& x = detail::particles_of(source).template get<particles::field::Position<Dim>>();
  return displacement_ratio<Dim>(std::span<const Vec<Dim>>(x), reference_positions,
                                 tool_displacement);
}

// 1 where the ratio reaches `threshold` (the paper's darker particles), else 0.
inline std::vector<std::uint8_t> at_least(std::span<const double> values, double threshold) {
  std::vector<std::uint8_t> flags(values.size());
  for (std::size_t p = 0; p < values.size(); ++p) flags[p] = values[p] >= threshold ? 1 : 0;
  return flags;
}

}  // namespace cosmpm::analysis
