#pragma once
// The particle-grid transfers over a stencil kept as per-axis factors (shape/separable.hpp):
// gather (grid to particle: values and gradients of node data at a particle) and scatter
// (particle to grid: weighted values and stress-divergence terms added to nodes), contracted
// one axis at a time.
#include <array>
#include <cstddef>
#include <type_traits>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/separable.hpp"

namespace cosmpm::shape {

// Node data for the transfers is kept as records: C doubles per node, node n's component c
// at n * C + c. A stencil row is then one run of S * C doubles, reached from one address.

// Grid-to-particle sums over the stencil of the C components of `records`:
//   value[c] = sum_n N_n f_c(n)                     c < C
//   gradient[c][d] = sum_n dN_n/dx_d f_c(n)          c < G (the first G components)
template <int Dim, int C, int G, class Value = double>
struct Gathered {
  std::array<Value, C> value;
  std::array<std::array<Value, Dim>, G> gradient;
};

namespace detail {
// The contraction of gather, for one particle or a pack; node(r, i, c) loads component c of
// node i along x on row r.
template <int C, int G, class Factors, class Node>
COSMPM_ALWAYS_INLINE auto gather_rows(const Factors& s, Node&& node) {
  static_assert(G <= C, "shape::gather: more gradient components than components");
  using Value = typename Factors::value_type;
  constexpr int Dim = Factors::dim;
  constexpr int S = Factors::support;
  // Sums start from their first term, not from zero: 0.0 + x is not x for x = -0.0, so the
  // compiler has to keep every such addition.
  Gathered<Dim, C, G, Value> out;
  COSMPM_UNROLL
  for (int r = 0; r < Factors::rows; ++r) {
    std::array<Value, C> along;                   // sum_i N_x(i) f
    std::array<Value, (G > 0 ? G : 1)> along_dx;  // sum_i dN_x(i) f, c < G
    COSMPM_UNROLL
    for (int c = 0; c < C; ++c) {
      const Value f = node(r, 0, c);
      along[c] = s.w[0][0] * f;
      if (c < G) along_dx[c] = s.dw[0][0] * f;
    }
    COSMPM_UNROLL
    for (int i = 1; i < S; ++i) {
      COSMPM_UNROLL
      for (int c = 0; c < C; ++c) {
        const Value f = node(r, i, c);
        along[c] += s.w[0][i] * f;
        if (c < G) along_dx[c] += s.dw[0][i] * f;
      }
    }
    Value weight;
    std::array<Value, Dim> gradient;
    s.row_factors(r, weight, gradient);
    COSMPM_UNROLL
    for (int c = 0; c < C; ++c) {
      out.value[c] = r == 0 ? weight * along[c] : out.value[c] + weight * along[c];
    }
    COSMPM_UNROLL
    for (int c = 0; c < G; ++c) {
      out.gradient[c][0] =
          r == 0 ? weight * along_dx[c] : out.gradient[c][0] + weight * along_dx[c];
      COSMPM_UNROLL
      for (int d = 1; d < Dim; ++d) {
        out.gradient[c][d] =
            r == 0 ? gradient[d] * along[c] : out.gradient[c][d] + gradient[d] * along[c];
      }
    }
  }
  return out;
}
}  // namespace detail

template <int C, int G, int Dim, Kernel K>
COSMPM_ALWAYS_INLINE Gathered<Dim, C, G> gather(const SeparableStencil<Dim, K>& s,
                                                const double* records) {
  return detail::gather_rows<C, G>(
      s, [&](int r, int i, int c) { return s.template row_records<C>(records, r)[i * C + c]; });
}

template <int C, int G, int Dim, Kernel K, int W>
COSMPM_ALWAYS_INLINE Gathered<Dim, C, G, Pack<W>> gather(const PackedStencil<Dim, K, W>& s,
                                                         const double* records) {
  if constexpr (W == 4 && C >= 2 && cosmpm::detail::transposes_records) {
    // Each lane's whole node record at once, transposed in registers (core/pack_records.hpp).
    std::array<std::array<Pack<W>, C>, PackedStencil<Dim, K, W>::rows * K::support> by_node;
    // Each lane's first record once; a node's records are then one offset from it for all
    // lanes (from the node index, the multiplication by C was redone per lane and load).
    std::array<const double*, W> first_record;
    for (int l = 0; l < W; ++l) first_record[l] = records + s.first_node[l] * C;
    for (int r = 0; r < PackedStencil<Dim, K, W>::rows; ++r) {
      const Index offset = s.row_offset(r);
      for (int i = 0; i < K::support; ++i) {
        const Index node_offset = (offset + i) * C;
        by_node[r * K::support + i] =
            load_by_component<W, C>([&](int l) { return first_record[l] + node_offset; });
      }
    }
    return detail::gather_rows<C, G>(
        s, [&](int r, int i, int c) { return by_node[r * K::support + i][c]; });
  } else {
    return detail::gather_rows<C, G>(s, [&](int r, int i, int c) {
      const Index offset = s.row_offset(r);
      return make_pack<W>(
          [&](int l) { return records[(s.first_node[l] + offset) * C + i * C + c]; });
    });
  }
}

namespace detail {
// at[l] += add[l] for the lanes of V, stored as doubles: a memcpy's store may alias anything,
// after which every array address of the particle loop around it is loaded again.
template <class V>
COSMPM_ALWAYS_INLINE void add_to_records(double* at, const V& add) {
  constexpr int lanes = lane_count<V>();
  cosmpm::detail::store_pack<lanes>(at, cosmpm::detail::load_pack<lanes>(at) + add);
}

// row[k + l] += weight along[k + l] + sum_{d >= 1} gradient[d] across[d - 1][k + l] for the
// lanes l of V, in that order of operations whatever V is.
template <class V, std::size_t Dim, std::size_t N, std::size_t A>
COSMPM_ALWAYS_INLINE void add_to_row(double* row, int k, double weight,
                                     const std::array<double, Dim>& gradient,
                                     const std::array<double, N>& along,
                                     const std::array<std::array<double, N>, A>& across) {
  // The factors go into registers lane by lane: vector loads of values just stored one by
  // one would stall on store forwarding.
  V a;
  gather_lanes(a, [&](int l) { return along[k + l]; });
  V add = weight * a;
  COSMPM_UNROLL
  for (std::size_t d = 0; d < A; ++d) {
    V b;
    gather_lanes(b, [&](int l) { return across[d][k + l]; });
    add += gradient[d + 1] * b;
  }
  add_to_records(row + k, add);
}

// scatter (below) for records of whole packs, C a multiple of the register width P: a node's
// record is C / P packs, whose terms are formed in registers from packs of the particle's
// weighted values and gradient factors. The row arrays' lane-by-lane loads were the largest
// part of the Cosserat scatter (8 doubles per node; docs/performance.md, "The scatter by node
// packs"). Per lane the operations of the row arrays, in their order; a weighted-only lane of
// a pack that also holds forces adds products with a zero factor, which move no sum (a record
// starts at +0, and +0 + -0 is +0).
template <int W, int Dim, Kernel K, std::size_t C>
COSMPM_ALWAYS_INLINE void scatter_node_packs(
    const SeparableStencil<Dim, K>& s, double* records, const std::array<double, C>& weighted,
    const std::type_identity_t<std::array<std::array<double, Dim>, C - W>>& by_gradient) {
  constexpr int P = pack_width;
  constexpr int R = static_cast<int>(C);
  constexpr int J = R / P;  // packs per node
  constexpr int S = K::support;
  using V = Pack<P>;
  // Pack j (components j P, ..., j P + P - 1) takes gradient terms if one of them does.
  constexpr auto forced = [](int j) { return (j + 1) * P > W; };
  std::array<V, J> weighted_packs;
  std::array<std::array<V, Dim>, J> factor_packs{};  // by_gradient, 0 for c < W
  COSMPM_UNROLL
  for (int j = 0; j < J; ++j) {
    gather_lanes(weighted_packs[j], [&](int l) { return weighted[j * P + l]; });
    if (!forced(j)) continue;
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      gather_lanes(factor_packs[j][d], [&](int l) {
        const int c = j * P + l;
        return c < W ? 0.0 : by_gradient[c < W ? 0 : c - W][d];
      });
    }
  }
  // Node i along x: N_x(i) a + dN_x(i) b_x, and N_x(i) b_d for the row's derivatives d >= 1.
  std::array<std::array<V, J>, S> along;
  std::array<std::array<std::array<V, Dim>, J>, S> across;
  COSMPM_UNROLL
  for (int i = 0; i < S; ++i) {
    COSMPM_UNROLL
    for (int j = 0; j < J; ++j) {
      along[i][j] = s.w[0][i] * weighted_packs[j];
      if (!forced(j)) continue;
      along[i][j] += s.dw[0][i] * factor_packs[j][0];
      COSMPM_UNROLL
      for (int d = 1; d < Dim; ++d) across[i][j][d] = s.w[0][i] * factor_packs[j][d];
    }
  }
  COSMPM_UNROLL
  for (int r = 0; r < SeparableStencil<Dim, K>::rows; ++r) {
    double* const row = records + (s.first_node + s.row_offset(r)) * R;
    double weight;
    std::array<double, Dim> gradient;
    s.row_factors(r, weight, gradient);
    COSMPM_UNROLL
    for (int i = 0; i < S; ++i) {
      COSMPM_UNROLL
      for (int j = 0; j < J; ++j) {
        V add = weight * along[i][j];
        if constexpr (W < R) {  // as the row arrays: zero factors where a record has forces
          COSMPM_UNROLL
          for (int d = 1; d < Dim; ++d) add += gradient[d] * (forced(j) ? across[i][j][d] : V{});
        }
        add_to_records(row + i * R + j * P, add);
      }
    }
  }
}

// scatter for any C: the terms of a stencil row laid out as the row's doubles, added in packs.
template <int W, int Dim, Kernel K, std::size_t C>
COSMPM_ALWAYS_INLINE void scatter_rows(
    const SeparableStencil<Dim, K>& s, double* records, const std::array<double, C>& weighted,
    const std::type_identity_t<std::array<std::array<double, Dim>, C - W>>& by_gradient) {
  constexpr int S = K::support;
  constexpr int F = static_cast<int>(C) - W;
  constexpr int R = static_cast<int>(C);
  constexpr int N = S * R;  // one row's doubles
  // Element i * R + c of a row: what the row weight multiplies, N_x(i) a + dN_x(i) b_x, and
  // what the row's derivative along d >= 1 multiplies, N_x(i) b_d.
  std::array<double, N> along;
  std::array<std::array<double, N>, (F > 0 ? Dim - 1 : 0)> across;
  COSMPM_UNROLL
  for (int i = 0; i < S; ++i) {
    COSMPM_UNROLL
    for (int c = 0; c < R; ++c) along[i * R + c] = s.w[0][i] * weighted[c];
    if constexpr (F > 0) {
      COSMPM_UNROLL
      for (int d = 1; d < Dim; ++d) {
        COSMPM_UNROLL
        for (int c = 0; c < W; ++c) across[d - 1][i * R + c] = 0.0;
      }
      COSMPM_UNROLL
      for (int f = 0; f < F; ++f) {
        along[i * R + W + f] += s.dw[0][i] * by_gradient[f][0];
        COSMPM_UNROLL
        for (int d = 1; d < Dim; ++d) across[d - 1][i * R + W + f] = s.w[0][i] * by_gradient[f][d];
      }
    }
  }
  COSMPM_UNROLL
  for (int r = 0; r < SeparableStencil<Dim, K>::rows; ++r) {
    double* const row = records + (s.first_node + s.row_offset(r)) * R;
    double weight;
    std::array<double, Dim> gradient;
    s.row_factors(r, weight, gradient);
    constexpr int P = pack_width;
    if constexpr (R > 1 && R < P && P % R == 0) {
      // A node's record in one smaller pack (2D MUSL's remap: two momenta): a pack across two
      // nodes meets half of the next particle's store to the node it shares and waits for it
      // to reach the cache; node by node the store is met whole and forwarded (fused MUSL
      // Mohr-Coulomb step -2.4 %). Records of 3 or 5 doubles node by node took 2-3 % longer:
      // more operations (docs/performance.md, "The remap node by node").
      COSMPM_UNROLL
      for (int i = 0; i < S; ++i)
        detail::add_to_row<Pack<R>>(row, i * R, weight, gradient, along, across);
    } else {
      // Packs of the register width, then a pair, then single doubles.
      constexpr int packed = N / P * P;
      constexpr int paired = P > 2 ? packed + (N - packed) / 2 * 2 : packed;
      COSMPM_UNROLL
      for (int k = 0; k < packed; k += P)
        detail::add_to_row<Pack<P>>(row, k, weight, gradient, along, across);
      COSMPM_UNROLL
      for (int k = packed; k < paired; k += 2)
        detail::add_to_row<Pack<2>>(row, k, weight, gradient, along, across);
      COSMPM_UNROLL
      for (int k = paired; k < N; ++k)
        detail::add_to_row<double>(row, k, weight, gradient, along, across);
    }
  }
}
}  // namespace detail

// Particle-to-grid: adds to the C components of `records`
//   N_n weighted[c]                                          c < W
//   N_n weighted[c] + sum_d dN_n/dx_d by_gradient[c - W][d]   W <= c < C
// (mass and momentum are weighted only; forces also take the stress divergence).
//
// A row of the stencil is S * C consecutive doubles, so it is updated in packs of the
// register width (core/pack.hpp; GCC left the per-component loops scalar). The per-node
// factors are laid out as that row first, with zero stress-divergence factors for the
// weighted-only components: adding their product, +-0, changes no nonzero sum. Records of
// whole packs with forces skip that layout: their terms are formed in registers, node by node,
// with the same sums bit for bit (detail::scatter_node_packs). Weighted-only records of whole
// packs (MUSL's remap, padded: stages/remap.hpp) keep the rows, which then also add node by
// node: in the fused MUSL pass the compiler contracted the node packs' products otherwise than
// the unpadded record's, which changed the last bits of its results.
template <int W, int Dim, Kernel K, std::size_t C>
COSMPM_ALWAYS_INLINE void scatter(
    const SeparableStencil<Dim, K>& s, double* records, const std::array<double, C>& weighted,
    const std::type_identity_t<std::array<std::array<double, Dim>, C - W>>& by_gradient) {
  static_assert(W <= static_cast<int>(C), "shape::scatter: more weighted-only than components");
  if constexpr (pack_width > 1 && C % pack_width == 0 && W < static_cast<int>(C)) {
    detail::scatter_node_packs<W>(s, records, weighted, by_gradient);
  } else {
    detail::scatter_rows<W>(s, records, weighted, by_gradient);
  }
}

// scatter for W particles side by side (lane l for particle l): the terms of each node formed
// in packs across the particles, then added to the node records particle after particle (all of
// a lane's nodes before the next lane's), so every record takes its terms in lane order. Per lane
// the operations of scatter, in its order (a product with a zero factor, which moves no sum, left
// out). Where one particle's terms took scalar products and lane-by-lane packs along the rows, the
// pack's take one product per node and component (docs/performance.md, "The scatter across
// particles").
template <int Wt, int Dim, Kernel K, int W, std::size_t C>
COSMPM_ALWAYS_INLINE void scatter_lanes(
    const PackedStencil<Dim, K, W>& s, double* records, const std::array<Pack<W>, C>& weighted,
    const std::type_identity_t<std::array<std::array<Pack<W>, Dim>, C - Wt>>& by_gradient) {
  static_assert(Wt <= static_cast<int>(C), "shape::scatter: more weighted-only than components");
  using V = Pack<W>;
  constexpr int S = K::support;
  constexpr int R = static_cast<int>(C);
  constexpr int F = R - Wt;
  // Node i along x: N_x(i) a + dN_x(i) b_x, and N_x(i) b_d for the row's derivatives d >= 1.
  std::array<std::array<V, R>, S> along;
  std::array<std::array<std::array<V, Dim>, (F > 0 ? F : 1)>, S> across;
  COSMPM_UNROLL
  for (int i = 0; i < S; ++i) {
    COSMPM_UNROLL
    for (int c = 0; c < R; ++c) along[i][c] = s.w[0][i] * weighted[c];
    COSMPM_UNROLL
    for (int f = 0; f < F; ++f) {
      along[i][Wt + f] += s.dw[0][i] * by_gradient[f][0];
      COSMPM_UNROLL
      for (int d = 1; d < Dim; ++d) across[i][f][d] = s.w[0][i] * by_gradient[f][d];
    }
  }
  constexpr int rows = PackedStencil<Dim, K, W>::rows;
  std::array<std::array<V, R>, rows * S> terms;  // node r S + i: row r, node i along x
  std::array<Index, rows * S> node_offsets;
  COSMPM_UNROLL
  for (int r = 0; r < rows; ++r) {
    V weight;
    std::array<V, Dim> gradient;
    s.row_factors(r, weight, gradient);
    COSMPM_UNROLL
    for (int i = 0; i < S; ++i) {
      auto& term = terms[r * S + i];
      COSMPM_UNROLL
      for (int c = 0; c < R; ++c) term[c] = weight * along[i][c];
      COSMPM_UNROLL
      for (int f = 0; f < F; ++f) {
        COSMPM_UNROLL
        for (int d = 1; d < Dim; ++d) term[Wt + f] += gradient[d] * across[i][f][d];
      }
      node_offsets[r * S + i] = (s.row_offset(r) + i) * R;
    }
  }
  add_by_component<W, R>(
      [&](int l, int n) { return records + s.first_node[l] * R + node_offsets[n]; }, terms);
}

}  // namespace cosmpm::shape
