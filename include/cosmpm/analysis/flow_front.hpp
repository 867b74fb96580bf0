#pragma once
// Where a flow ends, in two senses:
//  - extreme_front: the furthest material along an axis, over all particles: the particle
//    centre plus its half size (detail::half_size). One stray particle sets it.
//  - deposit_front: the far end of the deposit, from a height profile: starting at the first
//    bin that holds at least `min_thickness` of material (at initial density), the end of the
//    last bin of the unbroken run of such bins. A dilute tail of stretched particles, or a
//    blob ahead of a gap, does not count; an experiment's runout is read the same way, where
//    the deposit ends.
// mass_beyond counts what lies ahead of a position (the tail ahead of the deposit front).
#include <algorithm>
#include <cmath>
#include <string>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/analysis/height_profile.hpp"
#include "cosmpm/analysis/mass.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

struct FlowFront {
  double position = 0.0;  // along the axis
  Index particle = -1;    // the particle that sets it
};

namespace detail {
inline void check_axis_direction(const char* where, int axis, int dim, int direction) {
  require_in_range(where, "axis", axis, 0, dim - 1, Bounds::closed);
  if (direction != 1 && direction != -1) {
    throw Error(std::string(where) + ": direction = " + std::to_string(direction) +
                " must be +1 (towards larger coordinates) or -1");
  }
}
}  // namespace detail

// The furthest material along `axis` in `direction` (+1: the largest coordinate).
template <class Source>
FlowFront extreme_front(const Source& source, int axis = 0, int direction = 1) {
  constexpr int Dim = detail::dimension_of<Source>;
  detail::check_axis_direction("analysis::extreme_front", axis, Dim, direction);
  const auto& store = detail::particles_of(source);
  const auto& x = store.template get<particles::field::Position<Dim>>();
  const auto& volume = store.template get<particles::field::Volume>();
  require(!x.empty(), "analysis::extreme_front: the particle store is empty");
  FlowFront front{-HUGE_VAL, -1};
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double reach = direction * x[p][axis] + detail::half_size<Dim>(volume[p]);
    if (reach > front.position) front = {reach, static_cast<Index>(p)};
  }
  front.position *= direction;
  return front;
}

// The far end (largest x) of the deposit in `profile`: see the header comment.
inline double deposit_front(const HeightProfile& profile, double min_thickness) {
  require_positive("analysis::deposit_front", "min_thickness", min_thickness);
  std::size_t i = 0;
  while (i < profile.size() && profile.thickness[i] < min_thickness) ++i;
  if (i == profile.size()) {
    double thickest = 0.0;
    for (double t : profile.thickness) thickest = std::max(thickest, t);
    throw Error("analysis::deposit_front: no bin holds min_thickness = " +
                cosmpm::detail::format_number(min_thickness) +
                " m of material (the thickest holds " + cosmpm::detail::format_number(thickest) +
                " m)");
  }
  while (i + 1 < profile.size() && profile.thickness[i + 1] >= min_thickness) ++i;
  return profile.bin_end(i);
}

// The particles whose centre lies beyond `position` along `axis` in `direction`.
template <class Source>
MassCount mass_beyond(const Source& source, double position, int axis = 0, int direction = 1) {
  constexpr int Dim = detail::dimension_of<Source>;
  detail::check_axis_direction("analysis::mass_beyond", axis, Dim, direction);
  const auto& store = detail::particles_of(source);
  const auto& x = store.template get<particles::field::Position<Dim>>();
  const auto& mass = store.template get<particles::field::Mass>();
  MassCount beyond;
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (direction * (x[p][axis] - position) > 0.0) {
      ++beyond.count;
      beyond.mass += mass[p];
    }
  }
  return beyond;
}

}  // namespace cosmpm::analysis
