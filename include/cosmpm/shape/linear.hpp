#pragma once
// Linear hat functions: the paper's bilinear Q4 element shape functions in 2D (tensor
// product). N(r) = 1 - |r| for |r| < 1 with r the particle-node distance in cells.
#include <array>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/detail/lanes.hpp"

namespace cosmpm::shape {

struct Linear {
  static constexpr int support = 2;
  static constexpr bool continuous_gradient = false;  // shape/concept.hpp
  static const char* name() { return "Linear"; }

  // Nodes cell and cell + 1 of the cell holding xi; xi = node_count - 1 (the last node)
  // belongs to the last cell so the stencil stays inside the grid.
  template <class T>
  static Index evaluate(T xi, T /*half_width*/, Index node_count, std::array<T, 2>& weights,
                        std::array<T, 2>& gradients) {
    Index cell = static_cast<Index>(xi);  // xi >= 0: truncation is floor
    cell = cell < node_count - 2 ? cell : node_count - 2;
    const T t = xi - static_cast<T>(cell);
    weights = {T(1) - t, t};
    gradients = {T(-1), T(1)};
    return cell;
  }

  // The weights for the lanes of a pack P of W doubles (GCC/Clang vector extensions), each
  // lane its own particle; the cells come from evaluate. Cells fit in int.
  template <class P>
  static void evaluate_lanes(const P& xi, Index node_count, std::array<P, 2>& weights,
                             std::array<P, 2>& gradients) {
    const P t = xi - detail::cell_lanes(xi, node_count);
    weights = {1.0 - t, t};
    gradients = {P{} - 1.0, P{} + 1.0};
  }
};

static_assert(Kernel<Linear>);

}  // namespace cosmpm::shape
