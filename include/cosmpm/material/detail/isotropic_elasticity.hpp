#pragma once
// Isotropic linear elasticity as every model uses it: the validated constants, the elastic trial
// stress stress + D de and the elastic tangent D. The one place these formulas are written; the
// classical models take all of it, the Cosserat ones its normal components.
//
// Component layout: the first three components are the normal ones (xx, yy, zz), the others
// tensor shears (plane strain [xx, yy, zz, xy], 3D [xx, yy, zz, xy, xz, yz]), so
//   D = lambda 1 (x) 1 + 2 G I,   sigma_ij = lambda tr(eps) delta_ij + 2 G eps_ij.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>

#include "cosmpm/core/error.hpp"

namespace cosmpm::material::detail {

// stress + D de for the first N components, as N values of the type of stress[i] + de[i]: a T
// for an Eigen vector, a pack of T (core/pack.hpp) for arrays of packs. Every input is read
// before the caller stores anything: a store through the stress could alias the increment as
// far as the compiler knows and would force reloads. Components one by one, never as whole
// vectors: callers that just wrote single components of the stress (the engine's Jaumann
// rotation) would stall reading them back as one wide load.
template <std::size_t N, class Stress, class Increment, class T>
inline auto isotropic_trial(const Stress& stress, const Increment& de, T lambda, T two_shear) {
  static_assert(N >= 3, "isotropic_trial: the first three components are the normal ones");
  using V = std::remove_cvref_t<decltype(stress[0] + de[0])>;
  const V volumetric = lambda * (de[0] + de[1] + de[2]);
  std::array<V, N> trial;
  for (std::size_t i = 0; i < 3; ++i) trial[i] = stress[i] + (volumetric + two_shear * de[i]);
  for (std::size_t i = 3; i < N; ++i) trial[i] = stress[i] + two_shear * de[i];
  return trial;
}

// D in the same layout: tangent(i, j) = d stress[i] / d de[j].
template <int N, class T>
Eigen::Matrix<T, N, N> isotropic_tangent(T lambda, T shear) {
  static_assert(N >= 3, "isotropic_tangent: the first three components are the normal ones");
  Eigen::Matrix<T, N, N> d = Eigen::Matrix<T, N, N>::Zero();
  d.template topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) d(i, i) += 2 * shear;
  for (int i = 3; i < N; ++i) d(i, i) = 2 * shear;
  return d;
}

template <class T>
struct IsotropicElasticity {
  T shear{};   // G
  T lambda{};  // Lame's first parameter
  T bulk() const { return lambda + T(2) / 3 * shear; }
  T p_wave() const { return lambda + 2 * shear; }

  template <std::size_t N, class Stress, class Increment>
  auto trial(const Stress& stress, const Increment& de) const {
    return isotropic_trial<N>(stress, de, lambda, 2 * shear);
  }
  template <int N>
  Eigen::Matrix<T, N, N> tangent() const {
    return isotropic_tangent<N>(lambda, shear);
  }
};

// Checks E > 0 and -1 < nu < 0.5 (the range where the elastic energy is positive definite).
template <class T>
IsotropicElasticity<T> isotropic_elasticity(std::string_view where, T youngs_modulus,
                                            T poisson_ratio) {
  require_positive(where, "youngs_modulus", static_cast<double>(youngs_modulus));
  require_in_range(where, "poisson_ratio", static_cast<double>(poisson_ratio), -1.0, 0.5);
  IsotropicElasticity<T> elastic;
  elastic.shear = youngs_modulus / (2 * (1 + poisson_ratio));
  elastic.lambda = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  return elastic;
}

}  // namespace cosmpm::material::detail
