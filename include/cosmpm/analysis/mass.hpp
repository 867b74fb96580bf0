#pragma once
// The mass of a set of particles: all of them, those a flag marks (frozen, stray, in a
// region: whatever the caller flags), or those removed since an earlier count. In 2D plane
// strain the mass is per unit thickness (kg/m).
//
// The engine keeps no flag of its own yet; a policy that freezes or removes stray particles
// reports what it did, and these functions count what the caller hands them.
#include <cstddef>
#include <cstdint>
#include <ranges>

#include "cosmpm/analysis/detail/particle_source.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

struct MassCount {
  Index count = 0;
  double mass = 0.0;
};

// Every particle of a store or a simulation.
template <class Source>
MassCount mass_of(const Source& source) {
  const auto& mass = detail::particles_of(source).template get<particles::field::Mass>();
  MassCount total;
  for (double m : mass) {
    ++total.count;
    total.mass += m;
  }
  return total;
}

// The particles whose flag converts to true; one flag per particle (any sized range of
// values convertible to bool: std::vector<std::uint8_t>, std::vector<bool>, ...).
template <class Source, std::ranges::sized_range Flags>
MassCount mass_of(const Source& source, const Flags& flags) {
  const auto& mass = detail::particles_of(source).template get<particles::field::Mass>();
  detail::require_same_size("analysis::mass_of", "the particle store", mass.size(), "flags",
                            static_cast<std::size_t>(std::ranges::size(flags)));
  MassCount flagged;
  std::size_t p = 0;
  for (const auto& flag : flags) {
    if (static_cast<bool>(flag)) {
      ++flagged.count;
      flagged.mass += mass[p];
    }
    ++p;
  }
  return flagged;
}

// What left a store between an earlier count `before` and now: the difference of counts and
// masses (a removal policy takes particles out of the store).
template <class Source>
MassCount removed_since(const MassCount& before, const Source& source) {
  const MassCount now = mass_of(source);
  return {before.count - now.count, before.mass - now.mass};
}

}  // namespace cosmpm::analysis
