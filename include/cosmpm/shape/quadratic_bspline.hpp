#pragma once
// Quadratic B-spline centred on the nodes (Steffen, Kirby & Berzins 2008), knots at the cell
// midpoints. With a = |r| the distance in cells:
//   N(a) = 3/4 - a^2            a < 1/2
//        = (3/2 - a)^2 / 2      1/2 <= a < 3/2
//        = 0                    otherwise
// C1 across cells. Next to a grid edge the ghost node is folded onto the grid
// (detail/ghost_fold.hpp), which makes the basis linear in the half cell at the edge.
#include <array>

#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/detail/ghost_fold.hpp"
#include "cosmpm/shape/detail/lanes.hpp"

namespace cosmpm::shape {

struct QuadraticBSpline {
  static constexpr int support = 3;
  static const char* name() { return "QuadraticBSpline"; }

  // Nodes c - 1, c, c + 1 around the nearest node c.
  template <class T>
  static Index evaluate(T xi, T /*half_width*/, Index node_count, std::array<T, 3>& weights,
                        std::array<T, 3>& gradients) {
    const Index first = static_cast<Index>(xi + T(0.5)) - 1;  // xi >= 0: rounds to nearest
    const T d = xi - static_cast<T>(first + 1);               // in [-1/2, 1/2]
    const T left = T(0.5) - d;   // 3/2 - a for the left node (a = 1 + d)
    const T right = T(0.5) + d;  // 3/2 - a for the right node (a = 1 - d)
    weights = {T(0.5) * left * left, T(0.75) - d * d, T(0.5) * right * right};
    gradients = {-left, T(-2) * d, right};
    return detail::fold_into_grid(first, node_count, weights, gradients);
  }

  // The weights for the lanes of a pack P of doubles (GCC/Clang vector extensions), each lane
  // evaluate's arithmetic in the same order, the ghost folded where a lane's stencil sticks
  // out of the grid; the first nodes come from evaluate. Cells fit in int.
  template <class P>
  static void evaluate_lanes(const P& xi, Index node_count, std::array<P, 3>& weights,
                             std::array<P, 3>& gradients) {
    const P nearest = detail::floor_lanes(xi + 0.5);  // the nearest node, first + 1
    const P d = xi - nearest;
    const P left = 0.5 - d;
    const P right = 0.5 + d;
    weights = {0.5 * left * left, 0.75 - d * d, 0.5 * right * right};
    gradients = {-left, -2.0 * d, right};
    const auto below = nearest < 1.0;                                  // first < 0
    const auto above = nearest > static_cast<double>(node_count - 2);  // first > count - 3
    detail::fold_lanes_into_grid(below, above, weights);
    detail::fold_lanes_into_grid(below, above, gradients);
  }
};

static_assert(Kernel<QuadraticBSpline>);

}  // namespace cosmpm::shape
