#pragma once
// The elastic part shared by the Cosserat models (layout and law in cosserat_elastic.hpp): the
// validated constants, the trial stress stress + D de and the tangent D. The normal components
// are those of isotropic elasticity (isotropic_elasticity.hpp), written there once.
#include <Eigen/Core>
#include <array>
#include <string_view>
#include <type_traits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"

namespace cosmpm::material::detail {

// The moduli of the Cosserat elastic law as the trial stress uses them.
template <class T>
struct CosseratModuli {
  T lambda;   // Lame's lambda
  T shear2;   // 2 G
  T plus;     // G + Gc
  T minus;    // G - Gc
  T bending;  // 2 G l^2
};

// stress + D de as seven values, each a T (Eigen vectors) or lanes of T (arrays of lanes, the
// batched return). Every input is read before the caller writes anything (see
// isotropic_trial).
template <class Stress, class Increment, class T>
inline auto cosserat_trial(const Stress& s, const Increment& d, const CosseratModuli<T>& m) {
  using V = std::remove_cvref_t<decltype(s[0] + d[0])>;
  const std::array<V, 3> normal = isotropic_trial<3>(s, d, m.lambda, m.shear2);
  return std::array<V, 7>{normal[0],
                          normal[1],
                          normal[2],
                          s[3] + (m.plus * d[3] + m.minus * d[4]),
                          s[4] + (m.plus * d[4] + m.minus * d[3]),
                          s[5] + m.bending * d[5],
                          s[6] + m.bending * d[6]};
}

template <class T>
struct CosseratElasticity {
  IsotropicElasticity<T> iso;
  T cosserat_shear{};  // Gc
  T length{};          // l

  CosseratElasticity(std::string_view where, T youngs_modulus, T poisson_ratio,
                     T cosserat_shear_modulus, T characteristic_length)
      : iso(isotropic_elasticity<T>(where, youngs_modulus, poisson_ratio)),
        cosserat_shear(cosserat_shear_modulus),
        length(characteristic_length) {
    require_non_negative(where, "cosserat_shear_modulus",
                         static_cast<double>(cosserat_shear_modulus));
    require_positive(where, "characteristic_length", static_cast<double>(characteristic_length));
  }

  T bending_modulus() const { return 2 * iso.shear * length * length; }  // m = this * kappa

  // The stiffest wave modulus: lambda + 2G, or G + Gc for the short shear waves that the
  // micro-rotation cannot follow (larger than lambda + 2G for the paper's Gc = 2G, nu = 0.2).
  T p_wave_modulus() const {
    const T shear_wave = iso.shear + cosserat_shear;
    return iso.p_wave() > shear_wave ? iso.p_wave() : shear_wave;
  }

  CosseratModuli<T> moduli() const {
    return {iso.lambda, 2 * iso.shear, iso.shear + cosserat_shear, iso.shear - cosserat_shear,
            bending_modulus()};
  }

  Eigen::Matrix<T, 7, 7> tangent() const {
    Eigen::Matrix<T, 7, 7> d = iso.template tangent<7>();
    d(3, 3) = d(4, 4) = iso.shear + cosserat_shear;
    d(3, 4) = d(4, 3) = iso.shear - cosserat_shear;
    d(5, 5) = d(6, 6) = bending_modulus();
    return d;
  }
};

}  // namespace cosmpm::material::detail
