#pragma once
// Uniform GIMP (uGIMP, Bardenhagen & Kober 2004): the hat function averaged over the
// particle's domain [xi - lp, xi + lp], lp the particle half-width in cell units, which stays
// constant (e.g. lp = 0.25 for 2 x 2 particles per cell). With a = |r| the distance in cells:
//   S(a) = 1 - (a^2 + lp^2) / (2 lp)     a < lp
//        = 1 - a                         lp <= a < 1 - lp
//        = (1 + lp - a)^2 / (4 lp)       1 - lp <= a < 1 + lp
//        = 0                             otherwise
// Valid for 0 < lp <= 1/2, where the support 1 + lp spans at most 3 nodes. Next to a grid edge
// the ghost node is folded onto the grid (detail/ghost_fold.hpp).
#include <array>

#include "cosmpm/core/types.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/detail/ghost_fold.hpp"

namespace cosmpm::shape {

struct GIMP {
  static constexpr int support = 3;
  // Open at 0 (a particle has a size; use Linear for points), closed at 1/2 (one particle
  // per cell).
  static constexpr double min_half_width = 0.0;
  static constexpr double max_half_width = 0.5;
  static const char* name() { return "GIMP"; }

  // Nodes c - 1, c, c + 1 around the nearest node c. Precondition: 0 < half_width <= 1/2.
  template <class T>
  static Index evaluate(T xi, T half_width, Index node_count, std::array<T, 3>& weights,
                        std::array<T, 3>& gradients) {
    const T lp = half_width;
    const T inv_lp = T(1) / lp;
    const Index first = static_cast<Index>(xi + T(0.5)) - 1;  // xi >= 0: rounds to nearest
    const T d = xi - static_cast<T>(first + 1);               // in [-1/2, 1/2]
    // Centre node: |d| <= 1/2 <= 1 - lp, so only the first two branches of S apply.
    const T ad = d < T(0) ? -d : d;
    const bool inside = ad < lp;
    weights[1] = inside ? T(1) - (d * d + lp * lp) * (T(0.5) * inv_lp) : T(1) - ad;
    gradients[1] = inside ? -d * inv_lp : (d > T(0) ? T(-1) : T(1));
    // Neighbours at distance a in [1/2, 3/2] >= lp: the last three branches of S.
    T s_left, ds_left, s_right, ds_right;
    neighbour(T(1) + d, lp, inv_lp, s_left, ds_left);
    neighbour(T(1) - d, lp, inv_lp, s_right, ds_right);
    weights[0] = s_left;
    gradients[0] = ds_left;  // the left node lies at r = +a
    weights[2] = s_right;
    gradients[2] = -ds_right;  // the right node lies at r = -a
    return detail::fold_into_grid(first, node_count, weights, gradients);
  }

 private:
  // S(a) and dS/da for a >= lp.
  template <class T>
  static void neighbour(T a, T lp, T inv_lp, T& s, T& ds) {
    const T q = T(1) + lp - a;  // > 0 inside the support
    const bool linear = a < T(1) - lp;
    const bool overlap = q > T(0);
    s = linear ? T(1) - a : (overlap ? q * q * (T(0.25) * inv_lp) : T(0));
    ds = linear ? T(-1) : (overlap ? -q * (T(0.5) * inv_lp) : T(0));
  }
};

static_assert(Kernel<GIMP>);
static_assert(UsesHalfWidth<GIMP>);

}  // namespace cosmpm::shape
