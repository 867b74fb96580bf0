#pragma once
// Linear hat functions: the paper's bilinear Q4 element shape functions in 2D (tensor
// product). N(r) = 1 - |r| for |r| < 1 with r the particle-node distance in cells.
#include <array>

#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"

namespace cosmpm::shape {

struct Linear {
  static constexpr int support = 2;
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
};

static_assert(Kernel<Linear>);

}  // namespace cosmpm::shape
