#pragma once
// The stencil of one particle kept as its per-axis factors. Every kernel of this library is a
// tensor product, N_n(x) = prod_d N(xi_d), so a sum over the S^Dim stencil nodes can be contracted
// one axis at a time: first along x over each row of S nodes, then across the rows. For the
// bilinear kernel that halves the arithmetic of a gather and the products of a full stencil are
// never formed; for the cubic spline it is a quarter. The nodes of a row are adjacent in memory, so
// the innermost loops run over contiguous node data.
//
// The transfers that contract these factors with node data are in shape/transfer.hpp.
#include <array>
#include <cstddef>
#include <string>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/stencil_grid.hpp"

namespace cosmpm::shape {

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
    constexpr bool by_lanes = W > 1 && requires(const P& x, std::array<P, support>& f) {
      K::evaluate_lanes(x, Index{}, f, f);
    };
    [[maybe_unused]] std::array<P, Dim> xi_lanes;
    if constexpr (by_lanes)
      xi_lanes = load_by_component<W, Dim>([&](int l) { return xi(l).data(); });
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      if constexpr (by_lanes) {
        K::evaluate_lanes(xi_lanes[d], grid.nodes[d], w[d], dw[d]);
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

  // Lane l as one particle's stencil (its factors and first node; cell and position_in_cells
  // are left zero): for a scatter at the stencil of this gather.
  COSMPM_ALWAYS_INLINE SeparableStencil<Dim, K> lane(int l) const {
    SeparableStencil<Dim, K> one{};
    one.first_node = first_node[l];
    one.stride = stride;
    COSMPM_UNROLL
    for (int d = 0; d < Dim; ++d) {
      COSMPM_UNROLL
      for (int i = 0; i < support; ++i) {
        one.w[d][i] = cosmpm::lane<W>(w[d][i], l);
        one.dw[d][i] = cosmpm::lane<W>(dw[d][i], l);
      }
    }
    return one;
  }
};

}  // namespace cosmpm::shape
