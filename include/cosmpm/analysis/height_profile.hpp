#pragma once
// The height profile of a deposit (2D): in bins of equal width along the horizontal axis, the
// height of the material's top above a base level and the thickness of material the bin holds.
//
//   surface[i]   = max over the particles whose centre lies in bin i of (y_p + h_p) - base,
//                  h_p = sqrt(V_p) / 2 the half size of the particle (detail::half_size);
//                  0 where the bin holds no particle;
//   thickness[i] = sum over those particles of V0_p / bin_width, the thickness the material
//                  would have at its initial density (V0 the initial volume): a dilute tail of
//                  stretched particles has a high top but almost no thickness.
//
// Particles whose centre lies outside [from, from + bins * bin_width) are not counted; pass
// a range that covers the deposit.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

struct HeightProfile {
  double from = 0.0;              // left end of the first bin
  double bin_width = 0.0;         // m
  double base = 0.0;              // level the heights are measured from
  std::vector<double> x;          // bin centres
  std::vector<double> surface;    // top of the material above base, 0 in empty bins
  std::vector<double> thickness;  // sum of initial volumes per bin width
  std::vector<Index> count;       // particles per bin

  std::size_t size() const { return x.size(); }
  double bin_end(std::size_t i) const { return from + static_cast<double>(i + 1) * bin_width; }
};

struct HeightProfileOptions {
  double from = 0.0;  // left end of the range, m
  double to = 1.0;    // right end of the range (the last bin may end beyond it), m
  double bin_width = 0.01;
  double base = 0.0;  // the floor level, m
};

// The profile of the particles of a store or a simulation (2D: x horizontal, y up).
template <class Source>
HeightProfile height_profile(const Source& source, const HeightProfileOptions& options) {
  constexpr int Dim = detail::dimension_of<Source>;
  static_assert(Dim == 2, "analysis::height_profile: defined for 2D (x horizontal, y up)");
  const char* where = "analysis::height_profile";
  require_positive(where, "bin_width", options.bin_width);
  require(std::isfinite(options.from) && std::isfinite(options.base),
          "analysis::height_profile: from and base must be finite");
  if (!(options.to > options.from) || !std::isfinite(options.to)) {
    throw Error("analysis::height_profile: to = " + cosmpm::detail::format_number(options.to) +
                " must be finite and exceed from = " + cosmpm::detail::format_number(options.from));
  }
  const double span = (options.to - options.from) / options.bin_width;
  require_in_range(where, "(to - from) / bin_width", span, 0.0, 1e8, Bounds::right_closed);
  const auto bins = static_cast<std::size_t>(std::ceil(span - 1e-9));

  HeightProfile profile;
  profile.from = options.from;
  profile.bin_width = options.bin_width;
  profile.base = options.base;
  profile.x.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) {
    profile.x[i] = options.from + (static_cast<double>(i) + 0.5) * options.bin_width;
  }
  profile.surface.assign(bins, 0.0);
  profile.thickness.assign(bins, 0.0);
  profile.count.assign(bins, 0);

  const auto& store = detail::particles_of(source);
  const auto& x = store.template get<particles::field::Position<2>>();
  const auto& volume = store.template get<particles::field::Volume>();
  const auto& initial_volume = store.template get<particles::field::InitialVolume>();
  std::vector<double> top(bins, -HUGE_VAL);
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double cell = std::floor((x[p][0] - options.from) / options.bin_width);
    if (!(cell >= 0.0 && cell < static_cast<double>(bins))) continue;
    const auto i = static_cast<std::size_t>(cell);
    top[i] = std::max(top[i], x[p][1] + detail::half_size<2>(volume[p]));
    profile.thickness[i] += initial_volume[p] / options.bin_width;
    ++profile.count[i];
  }
  for (std::size_t i = 0; i < bins; ++i) {
    if (profile.count[i] > 0) profile.surface[i] = top[i] - options.base;
  }
  return profile;
}

}  // namespace cosmpm::analysis
