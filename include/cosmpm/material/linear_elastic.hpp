#pragma once
// Isotropic linear elasticity, in plane strain with sigma_zz carried (Dim = 2) or in 3D
// (Dim = 3); component order in stress_space.hpp.
#include <Eigen/Core>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace cosmpm::material {

// Parameters by name: LinearElastic({.youngs_modulus = 2.76e6, .poisson_ratio = 0.2}).
struct LinearElasticParameters {
  double youngs_modulus = detail::unset;  // E (Pa), > 0
  double poisson_ratio = detail::unset;   // nu, -1 < nu < 0.5
};

template <class T = double, int Dim = 2>
class LinearElastic {
  static constexpr int n = symmetric_components<Dim>;

 public:
  using scalar_type = T;
  using stress_type = SymmetricTensor<Dim, T>;  // [xx, yy, zz, xy(, xz, yz)]
  using strain_type = SymmetricTensor<Dim, T>;  // tensor shear
  using state_type = NoState;
  using tangent_type = Eigen::Matrix<T, n, n>;
  using parameters_type = LinearElasticParameters;
  static constexpr bool is_cosserat = false;
  static constexpr int dimension = Dim;

  explicit LinearElastic(const LinearElasticParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_(detail::isotropic_elasticity<T>("LinearElastic", T(parameters.youngs_modulus),
                                                 T(parameters.poisson_ratio))) {}
  LinearElastic(T youngs_modulus, T poisson_ratio)
      : LinearElastic(LinearElasticParameters{static_cast<double>(youngs_modulus),
                                              static_cast<double>(poisson_ratio)}) {}

  const LinearElasticParameters& parameters() const { return parameters_; }
  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }

  void update(stress_type& stress, state_type& /*state*/, const strain_type& de) const {
    update_values(stress, de);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update(stress, state, de);
    tangent = elastic_tangent();
  }

  // The packed hook (HasPackedUpdate), and update()'s one path: stress += D de on an Eigen
  // vector or on arrays of packs that hold one component of several points each.
  template <class Stress, class Increment>
  void update_values(Stress& stress, const Increment& de) const {
    const auto trial = elastic_.template trial<n>(stress, de);
    for (int i = 0; i < n; ++i) stress[i] = trial[i];
  }

  tangent_type elastic_tangent() const { return elastic_.template tangent<n>(); }

 private:
  static const LinearElasticParameters& checked(const LinearElasticParameters& p) {
    detail::require_set("LinearElastic", "LinearElasticParameters",
                        {{"youngs_modulus", p.youngs_modulus}, {"poisson_ratio", p.poisson_ratio}});
    return p;
  }

  LinearElasticParameters parameters_;
  detail::IsotropicElasticity<T> elastic_;
};

static_assert(ConstitutiveModel<LinearElastic<double>>);
static_assert(HasConsistentTangent<LinearElastic<double>>);
static_assert(HasPackedUpdate<LinearElastic<double>, double>);
static_assert(ConstitutiveModel<LinearElastic<double, 3>>);
static_assert(HasPackedUpdate<LinearElastic<double, 3>, double>);

}  // namespace cosmpm::material
