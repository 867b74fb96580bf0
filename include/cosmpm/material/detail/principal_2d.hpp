#pragma once
// Closed-form spectral split of a plane-strain stress: sigma_zz is principal already, so only the
// in-plane 2x2 eigenproblem is solved. The returned stress is rotated back with the trial
// eigenvectors (isotropic return mappings keep the principal directions).
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace cosmpm::material::detail {

// Principal values of [xx, yy, zz, xy] in the natural order (a, b, z) with a >= b in plane, the
// in-plane direction as (cos 2 theta, sin 2 theta) of the a-axis, and the permutation that sorts
// them descending: sorted[i] = natural[order[i]].
template <class T>
struct PlaneStrainSpectrum {
  Eigen::Matrix<T, 3, 1> natural;  // (sigma_a, sigma_b, sigma_zz)
  T cos_2theta{1};
  T sin_2theta{0};
  std::array<int, 3> order{0, 1, 2};

  Eigen::Matrix<T, 3, 1> sorted() const {
    return {natural[order[0]], natural[order[1]], natural[order[2]]};
  }
};

template <class T>
PlaneStrainSpectrum<T> plane_strain_spectrum(T xx, T yy, T zz, T xy) {
  PlaneStrainSpectrum<T> out;
  const T mean = (xx + yy) / 2;
  const T half = (xx - yy) / 2;
  const T radius = std::sqrt(half * half + xy * xy);
  out.natural = {mean + radius, mean - radius, zz};
  // radius == 0 means any in-plane direction is principal; keep the x-axis.
  if (radius > T(0)) {
    out.cos_2theta = half / radius;
    out.sin_2theta = xy / radius;
  }
  if (zz >= out.natural[0]) {
    out.order = {2, 0, 1};
  } else if (zz >= out.natural[1]) {
    out.order = {0, 2, 1};
  } else {
    out.order = {0, 1, 2};
  }
  return out;
}

// Rebuilds [xx, yy, zz, xy] from principal values in the natural order and the trial direction.
template <class T>
Eigen::Matrix<T, 4, 1> rotate_back(const Eigen::Matrix<T, 3, 1>& natural, T cos_2theta,
                                   T sin_2theta) {
  const T mean = (natural[0] + natural[1]) / 2;
  const T half = (natural[0] - natural[1]) / 2;
  return {mean + half * cos_2theta, mean - half * cos_2theta, natural[2], half * sin_2theta};
}

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

}  // namespace cosmpm::material::detail
