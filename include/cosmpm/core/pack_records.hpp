#pragma once
// Packs by component from records by lane and back: lane l's record of C doubles starts at
// address(l) (a particle's stress, deformation gradient or position, a node's gather record),
// and component c of the W lanes becomes one pack. Lane by lane (make_pack) that is W scalar
// loads and W - 1 inserts per pack; with AVX (W = 4) whole records are loaded and transposed
// in registers instead: 4 loads and 8 shuffles for four 4-double records, where lane by lane
// took 16 loads and 12 inserts (docs/performance.md, "Records transposed in registers").
// Only data moves: every lane's values and arithmetic are those of the lane-by-lane path.
#include <array>
#include <cstddef>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"

namespace cosmpm {

namespace detail {
// A pack at an address of doubles, aligned only as a double: accessed as doubles for the
// compiler's aliasing rules (memcpy would be a store that may alias anything, after which every
// array pointer in the loop is reloaded).
template <int W>
struct UnalignedPack {
  typedef double type __attribute__((vector_size(W * sizeof(double)), aligned(sizeof(double))));
};
// W = 1 is a double (Pack<1>), so callers written for any width need no case of their own.
template <int W>
COSMPM_ALWAYS_INLINE Pack<W> load_pack(const double* from) {
  if constexpr (W == 1) {
    return *from;
  } else {
    return *reinterpret_cast<const typename UnalignedPack<W>::type*>(from);
  }
}
template <int W>
COSMPM_ALWAYS_INLINE void store_pack(double* to, const Pack<W>& p) {
  if constexpr (W == 1) {
    *to = p;
  } else {
    *reinterpret_cast<typename UnalignedPack<W>::type*>(to) = p;
  }
}

#if defined(__AVX__) && (defined(__GNUC__) || defined(__clang__))
inline constexpr bool transposes_records = true;

// The 4 x 4 transpose: rows in, columns out (its own inverse).
COSMPM_ALWAYS_INLINE std::array<Pack<4>, 4> transpose4(const Pack<4>& r0, const Pack<4>& r1,
                                                       const Pack<4>& r2, const Pack<4>& r3) {
  const Pack<4> t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
  const Pack<4> t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const Pack<4> t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
  const Pack<4> t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  return {__builtin_shufflevector(t0, t2, 0, 1, 4, 5), __builtin_shufflevector(t1, t3, 0, 1, 4, 5),
          __builtin_shufflevector(t0, t2, 2, 3, 6, 7), __builtin_shufflevector(t1, t3, 2, 3, 6, 7)};
}

// Two lanes' 2-double records as one pack [lane a, lane b].
COSMPM_ALWAYS_INLINE Pack<4> join_pairs(const double* a, const double* b) {
  return __builtin_shufflevector(load_pack<2>(a), load_pack<2>(b), 0, 1, 2, 3);
}
#else
inline constexpr bool transposes_records = false;
#endif
}  // namespace detail

// Component c < C of lane l's record at address(l), as pack c. With AVX and W = 4 the record
// goes in chunks of 4 components (transposed), then 2, then 1 (lane by lane).
template <int W, int C, class Address>
COSMPM_ALWAYS_INLINE std::array<Pack<W>, C> load_by_component(Address&& address) {
  std::array<Pack<W>, C> out;
#if defined(__AVX__) && (defined(__GNUC__) || defined(__clang__))
  if constexpr (W == 4) {
    constexpr int quads = C / 4 * 4;
    for (int k = 0; k < quads; k += 4) {
      const auto columns = detail::transpose4(
          detail::load_pack<4>(address(0) + k), detail::load_pack<4>(address(1) + k),
          detail::load_pack<4>(address(2) + k), detail::load_pack<4>(address(3) + k));
      for (int c = 0; c < 4; ++c) out[k + c] = columns[c];
    }
    if constexpr (C - quads >= 2) {
      constexpr int k = quads;
      const Pack<4> lanes02 = detail::join_pairs(address(0) + k, address(2) + k);  // [a0 b0 a2 b2]
      const Pack<4> lanes13 = detail::join_pairs(address(1) + k, address(3) + k);  // [a1 b1 a3 b3]
      out[k] = __builtin_shufflevector(lanes02, lanes13, 0, 4, 2, 6);
      out[k + 1] = __builtin_shufflevector(lanes02, lanes13, 1, 5, 3, 7);
    }
    if constexpr (C % 2 == 1) {
      out[C - 1] = make_pack<W>([&](int l) { return address(l)[C - 1]; });
    }
    return out;
  }
#endif
  for (int c = 0; c < C; ++c) out[c] = make_pack<W>([&](int l) { return address(l)[c]; });
  return out;
}

// The inverse: component c of lane l's record at address(l) = lane l of pack c.
template <int W, int C, class Address>
COSMPM_ALWAYS_INLINE void store_by_component(Address&& address,
                                             const std::array<Pack<W>, C>& packs) {
#if defined(__AVX__) && (defined(__GNUC__) || defined(__clang__))
  if constexpr (W == 4) {
    constexpr int quads = C / 4 * 4;
    for (int k = 0; k < quads; k += 4) {
      const auto rows = detail::transpose4(packs[k], packs[k + 1], packs[k + 2], packs[k + 3]);
      for (int l = 0; l < 4; ++l) detail::store_pack<4>(address(l) + k, rows[l]);
    }
    if constexpr (C - quads >= 2) {
      constexpr int k = quads;
      const Pack<4> lanes02 = __builtin_shufflevector(packs[k], packs[k + 1], 0, 4, 2, 6);
      const Pack<4> lanes13 = __builtin_shufflevector(packs[k], packs[k + 1], 1, 5, 3, 7);
      detail::store_pack<2>(address(0) + k, __builtin_shufflevector(lanes02, lanes02, 0, 1));
      detail::store_pack<2>(address(1) + k, __builtin_shufflevector(lanes13, lanes13, 0, 1));
      detail::store_pack<2>(address(2) + k, __builtin_shufflevector(lanes02, lanes02, 2, 3));
      detail::store_pack<2>(address(3) + k, __builtin_shufflevector(lanes13, lanes13, 2, 3));
    }
    if constexpr (C % 2 == 1) {
      for (int l = 0; l < W; ++l) address(l)[C - 1] = packs[C - 1][l];
    }
    return;
  }
#endif
  for (int l = 0; l < W; ++l) {
    double* const record = address(l);
    for (int c = 0; c < C; ++c) record[c] = lane_of(packs[c], l);
  }
}

// Lane l's records at address(l, n) += lane l of packs[n][c] for n < N, lane after lane: the
// lanes of one particle each, so a node record that several lanes reach takes their terms in
// lane order, as W particles scattered one after the other would add them. With AVX and W = 4
// the packs are transposed as store_by_component's, each lane's chunk of a record added whole.
template <int W, int C, std::size_t N, class Address>
COSMPM_ALWAYS_INLINE void add_by_component(Address&& address,
                                           const std::array<std::array<Pack<W>, C>, N>& packs) {
#if defined(__AVX__) && (defined(__GNUC__) || defined(__clang__))
  if constexpr (W == 4) {
    constexpr int quads = C / 4 * 4;
    std::array<std::array<std::array<Pack<4>, 4>, (quads > 0 ? quads / 4 : 1)>, N> rows;
    [[maybe_unused]] std::array<std::array<Pack<4>, 2>, N> pairs;  // lanes 0 and 2, 1 and 3
    for (std::size_t n = 0; n < N; ++n) {
      const auto& p = packs[n];
      for (int k = 0; k < quads; k += 4) {
        rows[n][k / 4] = detail::transpose4(p[k], p[k + 1], p[k + 2], p[k + 3]);
      }
      if constexpr (C - quads >= 2) {
        pairs[n][0] = __builtin_shufflevector(p[quads], p[quads + 1], 0, 4, 2, 6);
        pairs[n][1] = __builtin_shufflevector(p[quads], p[quads + 1], 1, 5, 3, 7);
      }
    }
    for (int l = 0; l < 4; ++l) {
      for (std::size_t n = 0; n < N; ++n) {
        double* const record = address(l, static_cast<int>(n));
        for (int k = 0; k < quads; k += 4) {
          detail::store_pack<4>(record + k, detail::load_pack<4>(record + k) + rows[n][k / 4][l]);
        }
        if constexpr (C - quads >= 2) {
          const Pack<4>& both = pairs[n][l % 2];
          const Pack<2> pair = l < 2 ? __builtin_shufflevector(both, both, 0, 1)
                                     : __builtin_shufflevector(both, both, 2, 3);
          detail::store_pack<2>(record + quads, detail::load_pack<2>(record + quads) + pair);
        }
        if constexpr (C % 2 == 1) record[C - 1] += packs[n][C - 1][l];
      }
    }
    return;
  }
#endif
  for (int l = 0; l < W; ++l) {
    for (std::size_t n = 0; n < N; ++n) {
      double* const record = address(l, static_cast<int>(n));
      for (int c = 0; c < C; ++c) record[c] += lane_of(packs[n][c], l);
    }
  }
}

}  // namespace cosmpm
