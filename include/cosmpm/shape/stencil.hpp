#pragma once
// The Dim-dimensional stencil of one particle: the tensor product of a 1D kernel along each
// axis. It runs once per particle per transfer, so everything has compile-time trip counts
// and lives on the stack.
#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/separable.hpp"

namespace cosmpm::shape {

template <int Dim, Kernel K>
struct Stencil {
  static constexpr int dim = Dim;
  static constexpr int support = K::support;
  static constexpr int size = detail::int_pow(K::support, Dim);
  using kernel_type = K;

  // node[k]: linear grid node index (Grid::node_index numbering); weight[k]: N_k(x);
  // gradient[k]: dN_k/dx in physical units. Slot k walks the stencil x fastest.
  std::array<Index, size> node;
  std::array<double, size> weight;
  std::array<Vec<Dim>, size> gradient;

  // x: particle position; half_width: particle half-size in cell units per axis (used by
  // GIMP only). Throws cosmpm::Error if x lies outside the closed grid box, the grid has
  // fewer nodes than the kernel's support along an axis, or GIMP's half-width is out of range.
  void compute(const grid::Grid<Dim>& grid, const Vec<Dim>& x, const Vec<Dim>& half_width) {
    SeparableStencil<Dim, K> f;
    f.compute(grid, x, half_width);
    // Every index below is a compile-time constant (slots are expanded over an index sequence),
    // so the per-axis factors stay in registers instead of a stack array.
    [&]<int... Slot>(std::integer_sequence<int, Slot...>) {
      (fill_slot<Slot>(f, std::make_integer_sequence<int, Dim>{}), ...);
    }
    (std::make_integer_sequence<int, size>{});
  }

  // Kernels that ignore the particle size (all but GIMP) can be called without it.
  void compute(const grid::Grid<Dim>& grid, const Vec<Dim>& x) requires(!UsesHalfWidth<K>) {
    compute(grid, x, Vec<Dim>::Zero());
  }

 private:
  // Slot k has the base-`support` digits (i_0, ..., i_{Dim-1}), i_0 fastest.
  template <int Slot>
  static constexpr int digit(int axis) {
    int rest = Slot;
    for (int d = 0; d < axis; ++d) rest /= support;
    return rest % support;
  }

  // The product of the weights of every axis but `Skip` (Skip = -1: all axes).
  template <int Slot, int Skip, int... D>
  static double weight_product(const SeparableStencil<Dim, K>& f,
                               std::integer_sequence<int, D...>) {
    return ((D == Skip ? 1.0 : f.w[D][digit<Slot>(D)]) * ...);
  }

  template <int Slot, int... D>
  void fill_slot(const SeparableStencil<Dim, K>& f, std::integer_sequence<int, D...> axes) {
    node[Slot] = f.first_node + ((digit<Slot>(D) * f.stride[D]) + ...);
    weight[Slot] = weight_product<Slot, -1>(f, axes);
    ((gradient[Slot][D] = f.dw[D][digit<Slot>(D)] * weight_product<Slot, D>(f, axes)), ...);
  }
};

}  // namespace cosmpm::shape
