#pragma once
// Cubic B-spline centred on the nodes, knots at the nodes. With a = |r| the distance in cells:
//   N(a) = 2/3 - a^2 + a^3 / 2   a < 1
//        = (2 - a)^3 / 6         1 <= a < 2
//        = 0                     otherwise
// C2 across cells. Next to a grid edge the ghost node is folded onto the grid
// (detail/ghost_fold.hpp); the folded basis spans the cubic splines with zero second
// derivative at the edge (a natural spline).
#include <array>

#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/detail/ghost_fold.hpp"
#include "cosmpm/shape/detail/lanes.hpp"

namespace cosmpm::shape {

struct CubicBSpline {
  static constexpr int support = 4;
  static const char* name() { return "CubicBSpline"; }

  // Nodes cell - 1 .. cell + 2 around the cell holding xi (the last node belongs to the last
  // cell).
  template <class T>
  static Index evaluate(T xi, T /*half_width*/, Index node_count, std::array<T, 4>& weights,
                        std::array<T, 4>& gradients) {
    Index cell = static_cast<Index>(xi);  // xi >= 0: truncation is floor
    cell = cell < node_count - 2 ? cell : node_count - 2;
    const T t = xi - static_cast<T>(cell);  // in [0, 1]
    const T s = T(1) - t;
    const T t2 = t * t;
    const T s2 = s * s;
    constexpr T sixth = T(1) / T(6);
    weights = {sixth * s2 * s, T(2) / T(3) - t2 + T(0.5) * t2 * t,
               T(2) / T(3) - s2 + T(0.5) * s2 * s, sixth * t2 * t};
    gradients = {T(-0.5) * s2, T(-2) * t + T(1.5) * t2, T(2) * s - T(1.5) * s2, T(0.5) * t2};
    const Index first = cell - 1;
    return detail::fold_into_grid(first, node_count, weights, gradients);
  }

  // The weights for the lanes of a pack P of doubles (GCC/Clang vector extensions), each lane
  // evaluate's arithmetic in the same order, the ghost folded where a lane's stencil sticks
  // out of the grid; the first nodes come from evaluate. Cells fit in int.
  template <class P>
  static void evaluate_lanes(const P& xi, Index node_count, std::array<P, 4>& weights,
                             std::array<P, 4>& gradients) {
    const P cell = detail::cell_lanes(xi, node_count);
    const P t = xi - cell;
    const P s = 1.0 - t;
    const P t2 = t * t;
    const P s2 = s * s;
    constexpr double sixth = 1.0 / 6.0;
    weights = {sixth * s2 * s, 2.0 / 3.0 - t2 + 0.5 * t2 * t, 2.0 / 3.0 - s2 + 0.5 * s2 * s,
               sixth * t2 * t};
    gradients = {-0.5 * s2, -2.0 * t + 1.5 * t2, 2.0 * s - 1.5 * s2, 0.5 * t2};
    const auto below = cell < 1.0;                                  // first < 0
    const auto above = cell > static_cast<double>(node_count - 3);  // first > count - 4
    detail::fold_lanes_into_grid(below, above, weights);
    detail::fold_lanes_into_grid(below, above, gradients);
  }
};

static_assert(Kernel<CubicBSpline>);

}  // namespace cosmpm::shape
