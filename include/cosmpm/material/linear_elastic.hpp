#pragma once
// Isotropic linear elasticity in plane strain with sigma_zz carried.
#include <Eigen/Core>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"

namespace cosmpm::material {

template <class T = double>
class LinearElastic {
 public:
  using scalar_type = T;
  using stress_type = SymTensor2D<T>;
  using strain_type = SymTensor2D<T>;  // [dxx, dyy, dzz, dxy], tensor shear
  using state_type = NoState;
  using tangent_type = Eigen::Matrix<T, 4, 4>;
  static constexpr bool is_cosserat = false;

  LinearElastic(T youngs_modulus, T poisson_ratio) {
    require_positive("LinearElastic", "youngs_modulus", youngs_modulus);
    require_in_range("LinearElastic", "poisson_ratio", poisson_ratio, -1.0, 0.5);
    shear_ = youngs_modulus / (2 * (1 + poisson_ratio));
    lambda_ = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }

  T shear_modulus() const { return shear_; }
  T lame_lambda() const { return lambda_; }
  T bulk_modulus() const { return lambda_ + T(2) / 3 * shear_; }
  T p_wave_modulus() const { return lambda_ + 2 * shear_; }

  void update(stress_type& stress, state_type& /*state*/, const strain_type& de) const {
    update_values(stress, de);
  }

  // stress += D de, component by component, on an Eigen vector or on an array of packs that
  // hold one component of several points each (the engine updates W particles at once so).
  // Component by component also because callers that just wrote single components of the
  // stress (the engine's Jaumann rotation) would stall reading them back as whole vectors.
  template <class Stress, class Increment>
  void update_values(Stress& stress, const Increment& de) const {
    const auto volumetric = lambda_ * (de[0] + de[1] + de[2]);
    const T two_shear = 2 * shear_;
    stress[0] += volumetric + two_shear * de[0];
    stress[1] += volumetric + two_shear * de[1];
    stress[2] += volumetric + two_shear * de[2];
    stress[3] += two_shear * de[3];
  }

  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update(stress, state, de);
    tangent = elastic_tangent();
  }

  tangent_type elastic_tangent() const {
    tangent_type d = tangent_type::Zero();
    d.template topLeftCorner<3, 3>().setConstant(lambda_);
    for (int i = 0; i < 3; ++i) d(i, i) += 2 * shear_;
    d(3, 3) = 2 * shear_;
    return d;
  }

 private:
  T shear_{};
  T lambda_{};
};

static_assert(ConstitutiveModel<LinearElastic<double>>);
static_assert(HasConsistentTangent<LinearElastic<double>>);

}  // namespace cosmpm::material
