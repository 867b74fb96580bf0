#pragma once
// Lanes: L values that arithmetic applies to lane by lane, for the batched returns of the
// material models (GCC and Clang vector extensions; other compilers get `has_lanes` false and
// the models fall back to their per-point update). The models use lanes of the register width
// (register_bytes: 2 doubles with SSE2, 4 with AVX). Wider lanes cost more than they give
// with GCC 12 and SSE2: GCC splits their arithmetic well, but turns a comparison or selection
// on them into scalar code lane by lane, and 16 xmm registers hold few of them (the measured
// Cosserat Drucker-Prager batch took 1.4 to 1.6 times as long with 4 or 8 lanes as with 2).
//
// The helpers also take a plain T, so a formula written once, as a template on the value type,
// serves the per-point update and the lanes. Comparisons of lanes give lane masks (-1 / 0),
// which `mask ? a : b` selects with, as a bool does for a plain T.
#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>

#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2__)
#include <emmintrin.h>
#endif
#if (defined(__GNUC__) || defined(__clang__)) && defined(__AVX__)
#include <immintrin.h>
#endif

#include "cosmpm/core/pack.hpp"

namespace cosmpm::material::detail {

#if defined(__GNUC__) || defined(__clang__)
inline constexpr bool has_lanes = true;

// L lanes of T (L a power of two, at least 2): the engine's packs (core/pack.hpp).
template <class T, int L>
using Lanes = typename cosmpm::detail::LaneType<T, L>::type;

// The width of the target's vector registers in bytes.
#if defined(__AVX__)
inline constexpr std::size_t register_bytes = 32;
#else
inline constexpr std::size_t register_bytes = 16;
#endif
#else
// No lanes: the models call their per-point update; these keep the batch code compiling.
inline constexpr bool has_lanes = false;
template <class T, int L>
using Lanes = T;
inline constexpr std::size_t register_bytes = sizeof(double);
#endif

// Lanes from memory and back (no alignment needed). Lanes go by reference: lanes wider than the
// target's registers passed by value have an ABI that depends on the flags (GCC's -Wpsabi).
template <class V, class T>
inline void load_lanes(V& to, const T* from) {
  std::memcpy(&to, from, sizeof(to));
}
template <class T, class V>
inline void store_lanes(T* to, const V& from) {
  std::memcpy(to, &from, sizeof(from));
}

// The lane helpers of the engine's packs, which take any lane type.
using cosmpm::gather_lanes;
using cosmpm::lane_count;
using cosmpm::lane_of;

// Every lane of a V (lanes or a plain T) set to x.
template <class V, class T>
inline V splat(T x) {
  V v;
  gather_lanes(v, [&](int) { return x; });
  return v;
}

// x = sqrt(x), lane by lane for lanes: the vector extensions have no square root, so lanes of
// a register's width take the target's instruction (sqrtpd), others std::sqrt lane by lane.
template <class V>
inline void sqrt_in_place(V& x) {
  if constexpr (std::is_floating_point_v<V>) {
    x = std::sqrt(x);
  } else {
#if (defined(__GNUC__) || defined(__clang__)) && defined(__AVX__)
    if constexpr (std::is_same_v<V, Lanes<double, 4>>) {
      x = _mm256_sqrt_pd(x);
      return;
    }
#endif
#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2__)
    if constexpr (std::is_same_v<V, Lanes<double, 2>>) {
      x = _mm_sqrt_pd(x);
      return;
    }
#endif
    for (int k = 0; k < lane_count<V>(); ++k) x[k] = std::sqrt(x[k]);
  }
}

}  // namespace cosmpm::material::detail
