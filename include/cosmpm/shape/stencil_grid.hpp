#pragma once
// The grid constants a particle's stencil is built from, and the checks that decide whether a
// position can carry a stencil (and which cell holds it): one place for stencils and the
// engine's particle blocks alike.
#include <array>
#include <string>

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

}  // namespace cosmpm::shape
