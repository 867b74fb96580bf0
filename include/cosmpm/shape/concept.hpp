#pragma once
// The shape-function concept. A shape function is a stateless 1D kernel; the Dim-dimensional
// weights are its tensor product (shape/stencil.hpp).
//
// Kernel::evaluate(xi, half_width, node_count, weights, gradients) -> first node index
//   xi          position in cell units along the axis (node k sits at xi = k),
//               0 <= xi <= node_count - 1 (the kernels of this library accept the closed range)
//   half_width  particle half-size in cell units (GIMP uses it, others ignore it)
//   node_count  nodes along the axis (boundary-modified splines need it), >= support
//   weights[k], gradients[k]: N and dN/dxi of node first + k, k < Kernel::support.
// Contract: 0 <= first <= node_count - support; nodes outside the grid never receive weight.
// evaluate() does not check its inputs (it is the innermost loop); shape::Stencil does.
#include <array>
#include <concepts>

#include "cosmpm/core/types.hpp"

namespace cosmpm::shape {

template <class K>
concept Kernel = requires(double xi, double half_width, Index node_count,
                          std::array<double, K::support>& weights,
                          std::array<double, K::support>& gradients) {
  { K::support } -> std::convertible_to<int>;
  { K::evaluate(xi, half_width, node_count, weights, gradients) } -> std::same_as<Index>;
  { K::name() } -> std::convertible_to<const char*>;
};

// Whether a kernel's gradient is continuous across cells (and vanishes where its weight does).
// The hat (Linear) declares `static constexpr bool continuous_gradient = false`: its gradient
// jumps at cell faces and stays finite at nodes of vanishing mass, which transfers that use
// the gradient of the grid velocity (APIC's affine matrix) cannot survive.
template <class K>
inline constexpr bool has_continuous_gradient = [] {
  if constexpr (requires { K::continuous_gradient; }) {
    return static_cast<bool>(K::continuous_gradient);
  } else {
    return true;
  }
}();

// Kernels that read the particle half-width declare the valid range of it in cell units,
// (min_half_width, max_half_width]; shape::Stencil checks it.
template <class K>
concept UsesHalfWidth = Kernel<K> && requires {
  { K::min_half_width } -> std::convertible_to<double>;
  { K::max_half_width } -> std::convertible_to<double>;
};

}  // namespace cosmpm::shape
