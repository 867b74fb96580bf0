#pragma once
// Isotropic Cosserat (micropolar) elasticity in 2D plane strain after de Borst (1991).
//
// Component layout (CosseratTensor2D, tension positive):
//   stress  [s_xx, s_yy, s_zz, s_xy, s_yx, m_31, m_32]
//   strain  [e_xx, e_yy, e_zz, e_xy, e_yx, kappa_31, kappa_32]   (increments)
// s_ij is the force per unit area in direction j on the face with normal x_i (first index = face
// normal), so translational equilibrium reads d s_ij / d x_i + b_j = 0 and rotational equilibrium
// d m_3i / d x_i + s_xy - s_yx = 0. The work-conjugate deformations are
//   e_xx = du_x/dx, e_yy = du_y/dy, e_xy = du_y/dx - omega_3, e_yx = du_x/dy + omega_3,
//   kappa_31 = d omega_3 / dx, kappa_32 = d omega_3 / dy,
// with omega_3 the micro-rotation (counter-clockwise positive). When omega_3 equals the
// continuum rotation (du_y/dx - du_x/dy) / 2, e_xy = e_yx = the tensor shear of SymTensor2D.
// Elastic law:
//   s_ij = lambda e_kk delta_ij + (G + Gc) e_ij + (G - Gc) e_ji,   m_3i = 2 G l^2 kappa_3i.
// The power s_ij e_ij + m_3i kappa_3i is the plain dot product of the two 7-vectors.
#include <Eigen/Core>
#include <cstddef>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/cosserat_elasticity.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"

namespace cosmpm::material {

// Parameters by name, e.g. CosseratElastic({.youngs_modulus = 2.76e6, .poisson_ratio = 0.2,
// .cosserat_shear_modulus = 2.3e6, .characteristic_length = 0.01}).
struct CosseratElasticParameters {
  double youngs_modulus = detail::unset;          // E (Pa), > 0
  double poisson_ratio = detail::unset;           // nu, -1 < nu < 0.5
  double cosserat_shear_modulus = detail::unset;  // Gc (Pa), >= 0
  double characteristic_length = detail::unset;   // l (m), > 0
};

template <class T = double>
class CosseratElastic {
 public:
  using scalar_type = T;
  using stress_type = CosseratTensor2D<T>;
  using strain_type = CosseratTensor2D<T>;
  using state_type = NoState;
  using tangent_type = Eigen::Matrix<T, 7, 7>;
  using parameters_type = CosseratElasticParameters;
  static constexpr bool is_cosserat = true;
  static constexpr int dimension = 2;  // plane strain only (issue 18 leaves 3D Cosserat out)

  explicit CosseratElastic(const CosseratElasticParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_("CosseratElastic", T(parameters.youngs_modulus), T(parameters.poisson_ratio),
                 T(parameters.cosserat_shear_modulus), T(parameters.characteristic_length)) {}
  // E > 0 (Pa), -1 < nu < 0.5, Gc >= 0 (Pa), l > 0 (m).
  CosseratElastic(T youngs_modulus, T poisson_ratio, T cosserat_shear_modulus,
                  T characteristic_length)
      : CosseratElastic(CosseratElasticParameters{static_cast<double>(youngs_modulus),
                                                  static_cast<double>(poisson_ratio),
                                                  static_cast<double>(cosserat_shear_modulus),
                                                  static_cast<double>(characteristic_length)}) {}

  const CosseratElasticParameters& parameters() const { return parameters_; }

  T shear_modulus() const { return elastic_.iso.shear; }
  T cosserat_shear_modulus() const { return elastic_.cosserat_shear; }
  T characteristic_length() const { return elastic_.length; }
  T lame_lambda() const { return elastic_.iso.lambda; }
  T bulk_modulus() const { return elastic_.iso.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave_modulus(); }
  T bending_modulus() const { return elastic_.bending_modulus(); }

  void update(stress_type& stress, state_type& /*state*/, const strain_type& de) const {
    const auto trial = detail::cosserat_trial(stress, de, elastic_.moduli());
    for (std::size_t i = 0; i < trial.size(); ++i) stress[i] = trial[i];
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update(stress, state, de);
    tangent = elastic_.tangent();
  }
  tangent_type elastic_tangent() const { return elastic_.tangent(); }

 private:
  static const CosseratElasticParameters& checked(const CosseratElasticParameters& p) {
    detail::require_set("CosseratElastic", "CosseratElasticParameters",
                        {{"youngs_modulus", p.youngs_modulus},
                         {"poisson_ratio", p.poisson_ratio},
                         {"cosserat_shear_modulus", p.cosserat_shear_modulus},
                         {"characteristic_length", p.characteristic_length}});
    return p;
  }

  CosseratElasticParameters parameters_;
  detail::CosseratElasticity<T> elastic_;
};

static_assert(ConstitutiveModel<CosseratElastic<double>>);
static_assert(HasConsistentTangent<CosseratElastic<double>>);

}  // namespace cosmpm::material
