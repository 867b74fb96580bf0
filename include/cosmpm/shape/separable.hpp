#pragma once
// The stencil of one particle kept as its per-axis factors, and the particle-grid transfers
// that use them. Every kernel of this library is a tensor product, N_n(x) = prod_d N(xi_d),
// so a sum over the S^Dim stencil nodes can be contracted one axis at a time: first along x
// over each row of S nodes, then across the rows. For the bilinear kernel that halves the
// arithmetic of a gather and the products of a full stencil are never formed; for the cubic
// spline it is a quarter. The nodes of a row are adjacent in memory, so the innermost loops
// run over contiguous node data.
#include <array>
#include <cstddef>
#include <string>
#include <type_traits>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"

namespace cosmpm::shape {

namespace detail {

constexpr int int_pow(int base, int exponent) {
  int result = 1;
  for (int i = 0; i < exponent; ++i) result *= base;
  return result;
}

// Relative slack on the far face for the round-off of (x - origin) / h.
inline constexpr double position_round_off = 1e-12;

// Reports why an axis of a stencil could not be evaluated. Kept out of line and cold so the
// checks in the hot path cost one well-predicted branch per axis.
template <class K>
[[gnu::cold, gnu::noinline]] inline void throw_bad_stencil_input(int axis, double position,
                                                                 double xi, double half_width,
                                                                 Index node_count) {
  const std::string where = std::string("shape::Stencil<") + K::name() + ">";
  const std::string along = " along axis " + std::to_string(axis);
  require_in_range(where, "grid node count" + along, static_cast<double>(node_count),
                   static_cast<double>(K::support), 1e8, Bounds::closed);
  const double last = static_cast<double>(node_count - 1);
  if (!(xi >= 0.0 && xi <= last * (1.0 + position_round_off))) {
    require_in_range(where,
                     "particle position" + along + " in cell units from the grid origin (x = " +
                         cosmpm::detail::format_number(position) + ")",
                     xi, 0.0, last, Bounds::closed);
  }
  if constexpr (UsesHalfWidth<K>) {
    require_in_range(where, "particle half-width in cell units" + along, half_width,
                     K::min_half_width, K::max_half_width, Bounds::right_closed);
  }
  throw Error(where + ": invalid input" + along);  // unreachable unless the checks disagree
}

}  // namespace detail

// The grid constants a stencil needs, copied out of grid::Grid: the transfers store doubles to
// node arrays, which the compiler must assume could alias the grid's own doubles, so a loop
// that reads them from the grid reloads them for every particle. Built once per pass.
template <int Dim>
struct StencilGrid {
  std::array<double, Dim> origin;
  std::array<double, Dim> inverse_cell_size;
  std::array<double, Dim> last;   // index of the last node
  std::array<double, Dim> upper;  // last, with slack for round-off on the far face
  std::array<Index, Dim> nodes;
  std::array<Index, Dim> stride;  // node index strides, stride[0] = 1
  // upper, or -1 (no position valid) along an axis with fewer nodes than a kernel of that
  // support needs: a kernel's whole check is then two comparisons per axis.
  static constexpr int tabled_support = 4;
  std::array<std::array<double, Dim>, tabled_support + 1> upper_for_support;

  explicit StencilGrid(const grid::Grid<Dim>& grid) {
    Index next_stride = 1;
    for (int d = 0; d < Dim; ++d) {
      origin[d] = grid.origin()[d];
      inverse_cell_size[d] = grid.inverse_cell_size()[d];
      nodes[d] = grid.nodes(d);
      last[d] = static_cast<double>(nodes[d] - 1);
      upper[d] = last[d] * (1.0 + detail::position_round_off);
      stride[d] = next_stride;
      next_stride *= nodes[d];
      for (int support = 0; support <= tabled_support; ++support)
        upper_for_support[support][d] = nodes[d] >= support ? upper[d] : -1.0;
    }
  }

  // Whether position xi (cell units, axis d) is one a stencil can be built at: inside the
  // closed grid box up to round-off, the grid wide enough for the kernel, and (GIMP) the
  // half-width in its range. NaN is never valid.
  template <Kernel K>
  bool valid(int d, double xi, double half_width) const {
    bool ok;
    if constexpr (K::support <= tabled_support) {
      ok = xi >= 0.0 && xi <= upper_for_support[K::support][d];
    } else {
      ok = xi >= 0.0 && xi <= upper[d] && nodes[d] >= K::support;
    }
    if constexpr (UsesHalfWidth<K>) {
      ok = ok && half_width > K::min_half_width && half_width <= K::max_half_width;
    }
    return ok;
  }

  // The cell holding position xi (cell units, axis d, 0 <= xi <= last node), in
  // [0, cells - 1]: a position on the far face belongs to the last cell. Stencils and
  // particle blocks both take the cell from here, so they always agree.
  Index cell_of(int d, double xi) const {
    const Index containing = static_cast<Index>(xi);  // xi >= 0: truncation is floor
    return containing < nodes[d] - 2 ? containing : nodes[d] - 2;
  }

  // Whether position xi (cell units, axis d) lies strictly inside the grid box.
  bool inside(int d, double xi) const { return xi > 0.0 && xi < last[d]; }
};

// The per-axis factors of a stencil, with Value = double for one particle or a Pack of
// several (lane l for particle l).
template <int Dim, Kernel K, class Value>
struct StencilFactors {
  static constexpr int dim = Dim;
  static constexpr int support = K::support;
  // Rows: the S^(Dim-1) lines of S nodes along x that make up the stencil.
  static constexpr int rows = detail::int_pow(K::support, Dim - 1);
  using kernel_type = K;
  using value_type = Value;

  // w[d][i], dw[d][i]: N and dN/dx (physical units) of node first + i along axis d.
  std::array<std::array<Value, support>, Dim> w;
  std::array<std::array<Value, support>, Dim> dw;
  // Node index strides of the grid (stride[0] = 1).
  std::array<Index, Dim> stride;

  // Offset of row r's first node from the first node; r's base-S digits index axes 1..Dim-1.
  COSMPM_ALWAYS_INLINE Index row_offset(int r) const {
    Index offset = 0;
    COSMPM_UNROLL
    for (int d = 1; d < Dim; ++d) {
      offset += (r % support) * stride[d];
      r /= support;
    }
    return offset;
  }

  // The cross-row factors of row r: weight = prod_{d>=1} N_d, and gradient[d] (d >= 1) the
  // same product with dN_d in place of N_d. gradient[0] is unused (the x-derivative is taken
  // along the row).
  COSMPM_ALWAYS_INLINE void row_factors(int r, Value& weight,
                                        std::array<Value, Dim>& gradient) const {
    std::array<int, Dim> digit{};
    COSMPM_UNROLL
    for (int d = 1; d < Dim; ++d) {
      digit[d] = r % support;
      r /= support;
    }
    weight = Value{} + 1.0;  // a scalar broadcasts to every lane of a pack
    COSMPM_UNROLL
    for (int d = 1; d < Dim; ++d) weight *= w[d][digit[d]];
    gradient[0] = Value{};
    COSMPM_UNROLL
    for (int d = 1; d < Dim; ++d) {
      Value g = dw[d][digit[d]];
      COSMPM_UNROLL
      for (int e = 1; e < Dim; ++e) {
        if (e != d) g *= w[e][digit[e]];
      }
      gradient[d] = g;
    }
  }
};

template <int Dim, Kernel K>
struct SeparableStencil : StencilFactors<Dim, K, double> {
  using StencilFactors<Dim, K, double>::support;
  using StencilFactors<Dim, K, double>::w;
  using StencilFactors<Dim, K, double>::dw;
  using StencilFactors<Dim, K, double>::stride;
  // The linear index of the stencil's first node.
  Index first_node = 0;
  // Set by compute(): the grid cell holding the particle along each axis, in [0, cells - 1],
  // and its position in cell units from the grid origin, in [0, last node].
  std::array<Index, Dim> cell;
  Vec<Dim> position_in_cells;

  // x: particle position; half_width: particle half-size in cell units per axis (GIMP only).
  // Throws cosmpm::Error if x lies outside the closed grid box, the grid has fewer nodes than
  // the kernel's support along an axis, or GIMP's half-width is out of range.
  COSMPM_ALWAYS_INLINE void compute(const StencilGrid<Dim>& grid, const Vec<Dim>& x,
                                    const Vec<Dim>& half_width) {
    if (!try_compute(grid, x, half_width)) [[unlikely]] {
      report_invalid(grid, x, half_width);
    }
  }

  // As compute(), but returns false instead of throwing (and leaves the stencil unusable):
  // for loops inside OpenMP regions, which an exception must not leave.
  COSMPM_ALWAYS_INLINE bool try_compute(const StencilGrid<Dim>& grid, const Vec<Dim>& x,
                                        const Vec<Dim>& half_width) {
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      const double xi = (x[d] - grid.origin[d]) * grid.inverse_cell_size[d];
      // A particle on the far face (e.g. at Grid::node_position of the last node) can land a
      // few ulps past it after the scaling; that is round-off, not a particle outside.
      if (!grid.template valid<K>(d, xi, half_width[d])) [[unlikely]] {
        return false;
      }
      position_in_cells[d] = xi < grid.last[d] ? xi : grid.last[d];
      cell[d] = grid.cell_of(d, position_in_cells[d]);
    }
    compute_from_cell_units(grid, position_in_cells, half_width);
    return true;
  }

  // Names the first axis whose input is out of range (cold: runs only before an error).
  [[gnu::cold, gnu::noinline]] static void report_invalid(const StencilGrid<Dim>& grid,
                                                          const Vec<Dim>& x,
                                                          const Vec<Dim>& half_width) {
    for (int d = 0; d < Dim; ++d) {
      const double xi = (x[d] - grid.origin[d]) * grid.inverse_cell_size[d];
      if (!grid.template valid<K>(d, xi, half_width[d])) {
        detail::throw_bad_stencil_input<K>(d, x[d], xi, half_width[d], grid.nodes[d]);
      }
    }
    throw Error(std::string("shape::Stencil<") + K::name() + ">: invalid input");
  }

  // From a position already in cell units and checked by compute() (0 <= xi <= last node):
  // the maps after the first of a step reuse it instead of checking the particle again.
  COSMPM_ALWAYS_INLINE void compute_from_cell_units(const StencilGrid<Dim>& grid,
                                                    const Vec<Dim>& xi,
                                                    const Vec<Dim>& half_width) {
    first_node = 0;
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      const Index first = K::evaluate(xi[d], half_width[d], grid.nodes[d], w[d], dw[d]);
      COSMPM_UNROLL
      for (int i = 0; i < support; ++i) dw[d][i] *= grid.inverse_cell_size[d];
      stride[d] = grid.stride[d];
      first_node += first * grid.stride[d];
    }
  }

  void compute(const grid::Grid<Dim>& grid, const Vec<Dim>& x, const Vec<Dim>& half_width) {
    compute(StencilGrid<Dim>(grid), x, half_width);
  }

  // Kernels that ignore the particle size (all but GIMP) can be called without it.
  void compute(const grid::Grid<Dim>& grid, const Vec<Dim>& x) requires(!UsesHalfWidth<K>) {
    compute(grid, x, Vec<Dim>::Zero());
  }

  // Node records (C doubles per node) of the stencil's node i along x on row r.
  template <int C>
  COSMPM_ALWAYS_INLINE const double* row_records(const double* records, int r) const {
    return records + (first_node + this->row_offset(r)) * C;
  }
};

// The stencils of W particles side by side, for grid-to-particle maps that run W particles at
// once: lane l of every factor belongs to particle l.
template <int Dim, Kernel K, int W>
struct PackedStencil : StencilFactors<Dim, K, Pack<W>> {
  using StencilFactors<Dim, K, Pack<W>>::support;
  using StencilFactors<Dim, K, Pack<W>>::w;
  using StencilFactors<Dim, K, Pack<W>>::dw;
  using StencilFactors<Dim, K, Pack<W>>::stride;
  std::array<Index, W> first_node;

  // Lane l from particle position in cell units xi(l) (checked, as for
  // SeparableStencil::compute_from_cell_units) and half-width half_width(l).
  template <class Position, class HalfWidth>
  COSMPM_ALWAYS_INLINE void compute_from_cell_units(const StencilGrid<Dim>& grid, Position&& xi,
                                                    HalfWidth&& half_width) {
    using P = Pack<W>;
    // The first nodes lane by lane in integers; the weights from the same scalar stencils, or
    // (kernels that evaluate whole packs, Linear) from the pack, the scalar weights then
    // dropped as unused. The node addresses, which the gather waits for, so never wait for
    // the conversions of the pack.
    std::array<SeparableStencil<Dim, K>, W> one;
    COSMPM_UNROLL
    for (int l = 0; l < W; ++l) {
      one[l].compute_from_cell_units(grid, xi(l), half_width(l));
      first_node[l] = one[l].first_node;
    }
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      if constexpr (W > 1 && requires(const P& x, std::array<P, support>& f) {
                      K::evaluate_lanes(x, Index{}, f, f);
                    }) {
        K::evaluate_lanes(make_pack<W>([&](int l) { return xi(l)[d]; }), grid.nodes[d], w[d],
                          dw[d]);
        COSMPM_UNROLL
        for (int i = 0; i < support; ++i) dw[d][i] *= grid.inverse_cell_size[d];
      } else {
        COSMPM_UNROLL
        for (int i = 0; i < support; ++i) {
          w[d][i] = make_pack<W>([&](int l) { return one[l].w[d][i]; });
          dw[d][i] = make_pack<W>([&](int l) { return one[l].dw[d][i]; });
        }
      }
    }
    stride = grid.stride;
  }
};

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
  return detail::gather_rows<C, G>(s, [&](int r, int i, int c) {
    const Index offset = s.row_offset(r);
    return make_pack<W>([&](int l) { return records[(s.first_node[l] + offset) * C + i * C + c]; });
  });
}

// Particle-to-grid: adds to the C components of `records`
//   N_n weighted[c]                                          c < W
//   N_n weighted[c] + sum_d dN_n/dx_d by_gradient[c - W][d]   W <= c < C
// (mass and momentum are weighted only; forces also take the stress divergence).
template <int W, int Dim, Kernel K, std::size_t C>
COSMPM_ALWAYS_INLINE void scatter(
    const SeparableStencil<Dim, K>& s, double* records, const std::array<double, C>& weighted,
    const std::type_identity_t<std::array<std::array<double, Dim>, C - W>>& by_gradient) {
  static_assert(W <= static_cast<int>(C), "shape::scatter: more weighted-only than components");
  constexpr int S = K::support;
  constexpr int F = static_cast<int>(C) - W;
  constexpr int R = static_cast<int>(C);
  // Per node i along x: what the row factors multiply.
  std::array<std::array<double, C>, S> along;                    // N_x(i) a + dN_x(i) b_x
  std::array<std::array<std::array<double, Dim>, F>, S> across;  // N_x(i) b_d, d >= 1
  COSMPM_UNROLL
  for (int i = 0; i < S; ++i) {
    COSMPM_UNROLL
    for (int c = 0; c < R; ++c) along[i][c] = s.w[0][i] * weighted[c];
    COSMPM_UNROLL
    for (int f = 0; f < F; ++f) {
      along[i][W + f] += s.dw[0][i] * by_gradient[f][0];
      COSMPM_UNROLL
      for (int d = 1; d < Dim; ++d) across[i][f][d] = s.w[0][i] * by_gradient[f][d];
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
      for (int c = 0; c < W; ++c) row[i * R + c] += weight * along[i][c];
      COSMPM_UNROLL
      for (int f = 0; f < F; ++f) {
        double add = weight * along[i][W + f];
        COSMPM_UNROLL
        for (int d = 1; d < Dim; ++d) add += gradient[d] * across[i][f][d];
        row[i * R + W + f] += add;
      }
    }
  }
}

}  // namespace cosmpm::shape
