#pragma once
// The spectral split of a plane-strain trial stress for the isotropic principal-space returns
// (Mohr-Coulomb): sigma_zz is principal already, so only the in-plane 2x2 eigenproblem is
// solved, in closed form. The returned stress is rebuilt with the trial's in-plane directions
// (isotropic returns keep them). The 3D counterpart is principal_3d.hpp.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "cosmpm/material/detail/isotropic_elasticity.hpp"

namespace cosmpm::material::detail {

// Consistent tangent of an isotropic return in plane strain from the tangent of the principal
// map. `principal_tangent(i, j)` = d sigma_i / d eps_j in the natural order (a, b, z) and
// `shear_ratio` = (sigma_a - sigma_b) / (trial_a - trial_b), the factor by which the in-plane
// principal-frame shear stiffness 2G is scaled because the directions are kept from the trial.
template <class T>
Eigen::Matrix<T, 4, 4> spectral_tangent(const Eigen::Matrix<T, 3, 3>& principal_tangent,
                                        T shear_modulus, T shear_ratio, T cos_2theta,
                                        T sin_2theta) {
  const T cc = (1 + cos_2theta) / 2;  // cos^2 theta
  const T ss = (1 - cos_2theta) / 2;  // sin^2 theta
  const T cs = sin_2theta / 2;        // cos theta sin theta
  // Stress-side projections (tensor components) and strain-side contractions (the xy entry
  // counts twice because the strain is stored with its tensor shear).
  const std::array<Eigen::Matrix<T, 4, 1>, 3> p_stress{Eigen::Matrix<T, 4, 1>(cc, ss, 0, cs),
                                                       Eigen::Matrix<T, 4, 1>(ss, cc, 0, -cs),
                                                       Eigen::Matrix<T, 4, 1>(0, 0, 1, 0)};
  const std::array<Eigen::Matrix<T, 4, 1>, 3> p_strain{Eigen::Matrix<T, 4, 1>(cc, ss, 0, 2 * cs),
                                                       Eigen::Matrix<T, 4, 1>(ss, cc, 0, -2 * cs),
                                                       Eigen::Matrix<T, 4, 1>(0, 0, 1, 0)};
  Eigen::Matrix<T, 4, 4> tangent = Eigen::Matrix<T, 4, 4>::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      tangent.noalias() += principal_tangent(i, j) * p_stress[i] * p_strain[j].transpose();
  const Eigen::Matrix<T, 4, 1> q_stress(-sin_2theta, sin_2theta, 0, cos_2theta);
  const Eigen::Matrix<T, 4, 1> q_strain(-cs, cs, 0, cos_2theta);
  tangent.noalias() += 2 * shear_modulus * shear_ratio * q_stress * q_strain.transpose();
  return tangent;
}

// The split of a trial [xx, yy, zz, xy]: the in-plane principal values a >= b, sigma_zz, and
// the three sorted s1 >= s2 >= s3.
template <class T>
class PlaneStrainSplit {
 public:
  using Mat3 = Eigen::Matrix<T, 3, 3>;

  explicit PlaneStrainSplit(const std::array<T, 4>& t)
      : xx_(t[0]), yy_(t[1]), zz_(t[2]), xy_(t[3]) {
    const T mean = (xx_ + yy_) / 2;
    half_ = (xx_ - yy_) / 2;
    radius_ = std::sqrt(half_ * half_ + xy_ * xy_);
    a_ = mean + radius_;
    b_ = mean - radius_;
    s1_ = std::max(a_, zz_);
    s2_ = std::min(std::max(zz_, b_), a_);
    s3_ = std::min(b_, zz_);
  }

  T s1() const { return s1_; }
  T s2() const { return s2_; }
  T s3() const { return s3_; }

  // The stress with sorted principal values r1 >= r2 >= r3 and the trial's directions.
  Eigen::Matrix<T, 4, 1> back(T r1, T r2, T r3) const {
    const Natural n = natural(r1, r2, r3);
    const T new_mean = (n.a + n.b) / 2;
    return {new_mean + half_ * n.ratio, new_mean - half_ * n.ratio, n.z, xy_ * n.ratio};
  }

  // The consistent tangent of the return (r1, r2, r3) with map d r / d s (sorted order).
  Eigen::Matrix<T, 4, 4> tangent(const Mat3& sorted_map, const IsotropicElasticity<T>& elastic,
                                 T r1, T r2, T r3) const {
    const Natural n = natural(r1, r2, r3);
    // sorted[i] = natural[order[i]], by the rank sigma_zz has among the three.
    static constexpr int orders[3][3] = {{2, 0, 1}, {0, 2, 1}, {0, 1, 2}};
    const int* order = orders[n.zz_rank];
    Mat3 natural_map;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) natural_map(order[i], order[j]) = sorted_map(i, j);
    Mat3 elastic_principal = Mat3::Constant(elastic.lambda);
    elastic_principal.diagonal().array() += 2 * elastic.shear;
    // Equal in-plane trial eigenvalues: the ratio's limit is the map's derivative along a - b.
    const T shear_ratio =
        2 * radius_ > T(1e-12) * std::max(std::abs(a_), T(1))
            ? n.ratio
            : (natural_map(0, 0) - natural_map(0, 1) - natural_map(1, 0) + natural_map(1, 1)) / 2;
    const T cos_2theta = radius_ > T(0) ? half_ / radius_ : T(1);
    const T sin_2theta = radius_ > T(0) ? xy_ / radius_ : T(0);
    return spectral_tangent<T>(natural_map * elastic_principal, elastic.shear, shear_ratio,
                               cos_2theta, sin_2theta);
  }

 private:
  // The returned values in the natural order (a, b, zz) and the factor of the in-plane
  // deviator, (a - b) / (trial a - trial b).
  struct Natural {
    T a, b, z, ratio;
    int zz_rank;
  };
  Natural natural(T r1, T r2, T r3) const {
    Natural n;
    if (zz_ >= a_) {
      n.z = r1, n.a = r2, n.b = r3, n.zz_rank = 0;
    } else if (zz_ >= b_) {
      n.a = r1, n.z = r2, n.b = r3, n.zz_rank = 1;
    } else {
      n.a = r1, n.b = r2, n.z = r3, n.zz_rank = 2;
    }
    n.ratio = radius_ > T(0) ? (n.a - n.b) / (2 * radius_) : T(0);
    return n;
  }

  T xx_, yy_, zz_, xy_;
  T half_, radius_, a_, b_;
  T s1_, s2_, s3_;
};

}  // namespace cosmpm::material::detail
