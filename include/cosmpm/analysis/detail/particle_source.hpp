#pragma once
// What the analysis functions read particles from: a particle store (particles::Store) or
// anything that holds one behind `particles()` (a Simulation). The functions only read.
#include <cmath>
#include <concepts>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis::detail {

template <class Source>
concept HoldsParticles = requires(const Source& source) {
  source.particles();
};

// The store itself, or the store a simulation holds.
template <class Source>
const auto& particles_of(const Source& source) {
  if constexpr (HoldsParticles<Source>) {
    return source.particles();
  } else {
    return source;
  }
}

template <class Source>
using store_of = std::remove_cvref_t<decltype(particles_of(std::declval<const Source&>()))>;

// The spatial dimension of a store, from its position field.
template <class Store>
consteval int store_dimension() {
  using particles::field::Position;
  if constexpr (Store::template has<Position<2>>) {
    return 2;
  } else if constexpr (Store::template has<Position<3>>) {
    return 3;
  } else {
    static_assert(
        Store::template has<Position<2>>,
        "analysis: the particle store has no position field (particles::field::Position)");
    return 0;
  }
}

template <class Source>
inline constexpr int dimension_of = store_dimension<store_of<Source>>();

// Two columns of one particle set must have one entry per particle.
inline void require_same_size(std::string_view where, std::string_view first, std::size_t a,
                              std::string_view second, std::size_t b) {
  if (a == b) return;
  throw Error(std::string(where) + ": " + std::string(first) + " has " + std::to_string(a) +
              " entries but " + std::string(second) + " has " + std::to_string(b) +
              " (one per particle is required)");
}

// The half size of a particle of volume (2D: area) V along any axis, sqrt(V) / 2 in 2D and
// cbrt(V) / 2 in 3D: the half side of the square (cube) of that volume. Exact for seeded,
// undeformed particles.
template <int Dim>
double half_size(double volume) {
  if constexpr (Dim == 2) {
    return 0.5 * std::sqrt(volume);
  } else {
    return 0.5 * std::cbrt(volume);
  }
}

}  // namespace cosmpm::analysis::detail
