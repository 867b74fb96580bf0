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
#include <array>
#include <string_view>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/elastic_parameters.hpp"

namespace cosmpm::material {

namespace detail {

// The moduli of the Cosserat elastic law as the trial stress uses them.
template <class T>
struct CosseratModuli {
  T lambda;   // Lame's lambda
  T shear2;   // 2 G
  T plus;     // G + Gc
  T minus;    // G - Gc
  T bending;  // 2 G l^2
};

// stress + D de as seven scalars. Every input is read before the caller writes anything: a
// store through the stress may alias the moduli and the increment as far as the compiler
// knows and would force reloads; and scalar loads, since a 16-byte load across two earlier
// stores of the stress would stall.
template <class T, class V>
std::array<T, 7> trial_stress(const V& stress, const Eigen::Matrix<T, 7, 1>& de,
                              const CosseratModuli<T>& m) {
  const T d0 = de[0], d1 = de[1], d2 = de[2], d3 = de[3], d4 = de[4], d5 = de[5], d6 = de[6];
  const T volumetric = m.lambda * (d0 + d1 + d2);
  return {stress[0] + (volumetric + m.shear2 * d0),
          stress[1] + (volumetric + m.shear2 * d1),
          stress[2] + (volumetric + m.shear2 * d2),
          stress[3] + (m.plus * d3 + m.minus * d4),
          stress[4] + (m.plus * d4 + m.minus * d3),
          stress[5] + m.bending * d5,
          stress[6] + m.bending * d6};
}

// The same for stress and increment given as seven values, each a T or (update_batch) lanes of
// T. (Written out twice: the version above through this one costs the per-point update about 30
// instructions of copies.)
template <class V, class T>
std::array<V, 7> trial_stress(const std::array<V, 7>& s, const std::array<V, 7>& d,
                              const CosseratModuli<T>& m) {
  const V volumetric = m.lambda * (d[0] + d[1] + d[2]);
  return {s[0] + (volumetric + m.shear2 * d[0]),
          s[1] + (volumetric + m.shear2 * d[1]),
          s[2] + (volumetric + m.shear2 * d[2]),
          s[3] + (m.plus * d[3] + m.minus * d[4]),
          s[4] + (m.plus * d[4] + m.minus * d[3]),
          s[5] + m.bending * d[5],
          s[6] + m.bending * d[6]};
}

// The elastic part shared by the Cosserat models.
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

  // stress += D de (see trial_stress).
  template <class V>
  void add_elastic(V& stress, const Eigen::Matrix<T, 7, 1>& de) const {
    const std::array<T, 7> trial = trial_stress(stress, de, moduli());
    for (int i = 0; i < 7; ++i) stress[i] = trial[i];
  }

  Eigen::Matrix<T, 7, 7> tangent() const {
    Eigen::Matrix<T, 7, 7> d = Eigen::Matrix<T, 7, 7>::Zero();
    d.template topLeftCorner<3, 3>().setConstant(iso.lambda);
    for (int i = 0; i < 3; ++i) d(i, i) += 2 * iso.shear;
    d(3, 3) = d(4, 4) = iso.shear + cosserat_shear;
    d(3, 4) = d(4, 3) = iso.shear - cosserat_shear;
    d(5, 5) = d(6, 6) = bending_modulus();
    return d;
  }
};

}  // namespace detail

template <class T = double>
class CosseratElastic {
 public:
  using scalar_type = T;
  using stress_type = CosseratTensor2D<T>;
  using strain_type = CosseratTensor2D<T>;
  using state_type = NoState;
  using tangent_type = Eigen::Matrix<T, 7, 7>;
  static constexpr bool is_cosserat = true;

  // E > 0 (Pa), -1 < nu < 0.5, Gc >= 0 (Pa), l > 0 (m).
  CosseratElastic(T youngs_modulus, T poisson_ratio, T cosserat_shear_modulus,
                  T characteristic_length)
      : elastic_("CosseratElastic", youngs_modulus, poisson_ratio, cosserat_shear_modulus,
                 characteristic_length) {}

  T shear_modulus() const { return elastic_.iso.shear; }
  T cosserat_shear_modulus() const { return elastic_.cosserat_shear; }
  T characteristic_length() const { return elastic_.length; }
  T lame_lambda() const { return elastic_.iso.lambda; }
  T bulk_modulus() const { return elastic_.iso.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave_modulus(); }
  T bending_modulus() const { return elastic_.bending_modulus(); }

  void update(stress_type& stress, state_type& /*state*/, const strain_type& de) const {
    elastic_.add_elastic(stress, de);
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    update(stress, state, de);
    tangent = elastic_.tangent();
  }
  tangent_type elastic_tangent() const { return elastic_.tangent(); }

 private:
  detail::CosseratElasticity<T> elastic_;
};

static_assert(ConstitutiveModel<CosseratElastic<double>>);
static_assert(HasConsistentTangent<CosseratElastic<double>>);

}  // namespace cosmpm::material
