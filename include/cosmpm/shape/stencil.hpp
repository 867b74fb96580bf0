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
    // Every index below is a compile-time constant (axes and slots are expanded over index
    // sequences), so the per-axis factors stay in registers instead of a stack array.
    Factors f;
    [&]<int... D>(std::integer_sequence<int, D...>) {
      (evaluate_axis<D>(grid, x, half_width, f), ...);
    }
    (std::make_integer_sequence<int, Dim>{});
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
  // The 1D weights and physical derivatives per axis, and where the stencil starts.
  struct Factors {
    std::array<std::array<double, support>, Dim> w;
    std::array<std::array<double, support>, Dim> dw;
    std::array<Index, Dim> stride;
    Index first_node = 0;
    Index next_stride = 1;
  };

  template <int D>
  static void evaluate_axis(const grid::Grid<Dim>& grid, const Vec<Dim>& x,
                            const Vec<Dim>& half_width, Factors& f) {
    const Index n = grid.nodes(D);
    const double inv_h = grid.inverse_cell_size()[D];
    const double last = static_cast<double>(n - 1);
    double xi = (x[D] - grid.origin()[D]) * inv_h;
    // A particle on the far face (e.g. at Grid::node_position of the last node) can land a
    // few ulps past it after the scaling; that is round-off, not a particle outside.
    bool valid = xi >= 0.0 && xi <= last * (1.0 + detail::position_round_off) && n >= support;
    if constexpr (UsesHalfWidth<K>) {
      valid = valid && half_width[D] > K::min_half_width && half_width[D] <= K::max_half_width;
    }
    if (!valid) [[unlikely]] {
      detail::throw_bad_stencil_input<K>(D, x[D], xi, half_width[D], n);
    }
    xi = xi < last ? xi : last;
    const Index first = K::evaluate(xi, half_width[D], n, f.w[D], f.dw[D]);
    [&]<int... I>(std::integer_sequence<int, I...>) {
      ((f.dw[D][I] *= inv_h), ...);
    }
    (std::make_integer_sequence<int, support>{});
    f.stride[D] = f.next_stride;
    f.first_node += first * f.next_stride;
    f.next_stride *= n;
  }

  // Slot k has the base-`support` digits (i_0, ..., i_{Dim-1}), i_0 fastest.
  template <int Slot>
  static constexpr int digit(int axis) {
    int rest = Slot;
    for (int d = 0; d < axis; ++d) rest /= support;
    return rest % support;
  }

  // The product of the weights of every axis but `Skip` (Skip = -1: all axes).
  template <int Slot, int Skip, int... D>
  static double weight_product(const Factors& f, std::integer_sequence<int, D...>) {
    return ((D == Skip ? 1.0 : f.w[D][digit<Slot>(D)]) * ...);
  }

  template <int Slot, int... D>
  void fill_slot(const Factors& f, std::integer_sequence<int, D...> axes) {
    node[Slot] = f.first_node + ((digit<Slot>(D) * f.stride[D]) + ...);
    weight[Slot] = weight_product<Slot, -1>(f, axes);
    ((gradient[Slot][D] = f.dw[D][digit<Slot>(D)] * weight_product<Slot, D>(f, axes)), ...);
  }
};

}  // namespace cosmpm::shape
