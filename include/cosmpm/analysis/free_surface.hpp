#pragma once
// The free surface of a 2D particle set as curves: the upper envelope of the material. The
// horizontal range the particles cover is cut into bins of equal width, the first centred on
// the leftmost particle (particles seeded at that spacing fall in bin middles); in each bin that
// holds a particle, the highest particle gives one point, (x_p, y_p + h_p) with h_p its half
// size (detail::half_size). Consecutive non-empty bins form one curve; an empty bin ends it,
// so two heaps give two curves. Points run from left to right.
//
// The envelope is single valued: an overhang shows only its top. The bin width sets the
// resolution; about one particle spacing resolves the surface without gaps inside the
// material.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

using SurfaceCurve = std::vector<Vec<2>>;

template <class Source>
std::vector<SurfaceCurve> free_surface(const Source& source, double bin_width) {
  static_assert(detail::dimension_of<Source> == 2,
                "analysis::free_surface: defined for 2D (x horizontal, y up)");
  require_positive("analysis::free_surface", "bin_width", bin_width);
  const auto& store = detail::particles_of(source);
  const auto& x = store.template get<particles::field::Position<2>>();
  const auto& volume = store.template get<particles::field::Volume>();
  std::vector<SurfaceCurve> curves;
  if (x.empty()) return curves;
  double left = HUGE_VAL, right = -HUGE_VAL;
  for (const auto& position : x) {
    left = std::min(left, position[0]);
    right = std::max(right, position[0]);
  }
  left -= 0.5 * bin_width;
  const double span = (right - left) / bin_width;
  require_in_range("analysis::free_surface", "(particle x range) / bin_width", span, 0.0, 1e8,
                   Bounds::closed);
  const auto bins = static_cast<std::size_t>(std::floor(span)) + 1;
  std::vector<Index> highest(bins, -1);
  std::vector<double> top(bins, -HUGE_VAL);
  for (std::size_t p = 0; p < x.size(); ++p) {
    const auto i = std::min(bins - 1, static_cast<std::size_t>((x[p][0] - left) / bin_width));
    const double reach = x[p][1] + detail::half_size<2>(volume[p]);
    if (reach > top[i]) {
      top[i] = reach;
      highest[i] = static_cast<Index>(p);
    }
  }
  SurfaceCurve curve;
  for (std::size_t i = 0; i < bins; ++i) {
    if (highest[i] < 0) {
      if (!curve.empty()) curves.push_back(std::move(curve));
      curve.clear();
      continue;
    }
    curve.emplace_back(x[static_cast<std::size_t>(highest[i])][0], top[i]);
  }
  if (!curve.empty()) curves.push_back(std::move(curve));
  return curves;
}

}  // namespace cosmpm::analysis
