#pragma once
// A pack of W doubles that arithmetic applies to lane by lane, for loops that process W
// particles at once. A particle's grid-to-particle update is one long chain of dependent
// operations (position, weights, node loads, sums, rates); the processor overlaps little of
// one particle with the next, so running two particles down the same chain in one register
// nearly halves the time, where fewer operations per particle did not help (measured on the
// bilinear gather; docs/architecture.md).
//
// GCC and Clang vector extensions give the pack: SSE2, part of every x86-64 target, holds two
// doubles; with AVX enabled (-mavx and up) a pack holds four. Other compilers use W = 1, a
// plain double, and the same code runs one particle at a time.
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "cosmpm/core/compiler.hpp"

namespace cosmpm {

// COSMPM_PACK_WIDTH (1, 2 or 4) overrides the choice, e.g. to compare widths.
#if defined(COSMPM_PACK_WIDTH)
inline constexpr int pack_width = COSMPM_PACK_WIDTH;
#elif defined(__GNUC__) || defined(__clang__)
#if defined(__AVX__)
inline constexpr int pack_width = 4;
#else
inline constexpr int pack_width = 2;
#endif
#else
inline constexpr int pack_width = 1;
#endif

namespace detail {
// W lanes of T (GCC/Clang vector extensions; a typedef, as GCC ignores the attribute on an
// alias of a dependent type); W = 1 is T itself.
template <class T, int W>
struct LaneType {
#if defined(__GNUC__) || defined(__clang__)
  typedef T type __attribute__((vector_size(W * sizeof(T))));
#endif
};
template <class T>
struct LaneType<T, 1> {
  using type = T;
};
}  // namespace detail

// W ints, for converting a Pack<W> lane by lane (__builtin_convertvector).
template <int W>
using IntPack = typename detail::LaneType<int, W>::type;

// Pack<1> is double, so code written for Pack<W> also serves the scalar remainder of a loop.
template <int W>
using Pack = typename detail::LaneType<double, W>::type;

// The helpers below take any lane type (a vector of doubles or of floats) or a plain number,
// its own single lane.

// The number of lanes of V.
template <class V>
constexpr int lane_count() {
  if constexpr (std::is_arithmetic_v<V>) {
    return 1;
  } else {
    return static_cast<int>(sizeof(V) / sizeof(std::declval<V&>()[0]));
  }
}

// Lane l of x.
template <class V>
inline auto lane_of(const V& x, int l) {
  if constexpr (std::is_arithmetic_v<V>) {
    (void)l;
    return x;
  } else {
    return x[l];
  }
}

// to's lane l = value(l), for values spread over memory (one particle's field each). Built in
// one initialisation: filling lanes one at a time goes through memory.
template <class V, class F>
inline void gather_lanes(V& to, F&& value) {
  if constexpr (std::is_arithmetic_v<V>) {
    to = value(0);
  } else {
    [&]<int... L>(std::integer_sequence<int, L...>) {
      to = V{value(L)...};
    }
    (std::make_integer_sequence<int, lane_count<V>()>{});
  }
}

template <int W>
inline double lane(const Pack<W>& pack, int l) {
  return lane_of(pack, l);
}

// A pack from value(l) (see gather_lanes).
template <int W, class F>
inline Pack<W> make_pack(F&& value) {
  Pack<W> pack;
  gather_lanes(pack, value);
  return pack;
}

// Whether every lane of a comparison's result is true, with one branch for the whole pack
// (SSE2 and AVX: the lanes' sign bits gathered by movmskpd).
template <int W, class Mask>
COSMPM_ALWAYS_INLINE bool all_lanes(const Mask& mask) {
  if constexpr (W == 1) {
    return static_cast<bool>(mask);
#if defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
  } else if constexpr (W == 2) {
    return __builtin_ia32_movmskpd(__builtin_bit_cast(Pack<2>, mask)) == 0x3;
#endif
#if defined(__AVX__) && (defined(__GNUC__) || defined(__clang__))
  } else if constexpr (W == 4) {
    return __builtin_ia32_movmskpd256(__builtin_bit_cast(Pack<4>, mask)) == 0xf;
#endif
  } else {
    bool all = true;
    for (int l = 0; l < W; ++l) all = all && mask[l] != 0;
    return all;
  }
}

}  // namespace cosmpm
