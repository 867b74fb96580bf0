#pragma once
// Shared helpers of the material tests: finite-difference tangents, rotations, random states.
#include <Eigen/Core>
#include <cmath>
#include <random>

#include "cosmpm/core/types.hpp"

namespace cosmpm::material::testing {

// Central finite-difference tangent d stress / d strain increment of any model, from the same
// old stress and state. The step is `relative_step` times the largest increment component.
template <class Model>
Eigen::Matrix<double, Model::stress_type::RowsAtCompileTime, Model::stress_type::RowsAtCompileTime>
finite_difference_tangent(const Model& model, const typename Model::stress_type& old_stress,
                          const typename Model::state_type& old_state,
                          const typename Model::strain_type& de, double relative_step = 1e-6) {
  constexpr int n = Model::stress_type::RowsAtCompileTime;
  Eigen::Matrix<double, n, n> tangent;
  const double h = relative_step * std::max(de.cwiseAbs().maxCoeff(), 1e-12);
  for (int j = 0; j < n; ++j) {
    typename Model::strain_type plus = de, minus = de;
    plus[j] += h;
    minus[j] -= h;
    typename Model::stress_type s_plus = old_stress, s_minus = old_stress;
    typename Model::state_type st_plus = old_state, st_minus = old_state;
    model.update(s_plus, st_plus, plus);
    model.update(s_minus, st_minus, minus);
    tangent.col(j) = (s_plus - s_minus) / (2 * h);
  }
  return tangent;
}

// In-plane rotation by `angle` of [xx, yy, zz, xy] (stress or tensor-shear strain).
inline SymTensor2D<double> rotate(const SymTensor2D<double>& a, double angle) {
  Eigen::Matrix2d r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  Eigen::Matrix2d m;
  m << a[0], a[3], a[3], a[1];
  const Eigen::Matrix2d out = r * m * r.transpose();
  return {out(0, 0), out(1, 1), a[2], out(0, 1)};
}

// In-plane rotation of a Cosserat stress or deformation: the non-symmetric 2x2 block
// [[xx, xy], [yx, yy]] rotates as a tensor, the couple-stress / curvature pair as a vector.
inline CosseratTensor2D<double> rotate(const CosseratTensor2D<double>& a, double angle) {
  Eigen::Matrix2d r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  Eigen::Matrix2d m;
  m << a[0], a[3], a[4], a[1];
  const Eigen::Matrix2d out = r * m * r.transpose();
  const Eigen::Vector2d v = r * Eigen::Vector2d(a[5], a[6]);
  CosseratTensor2D<double> b;
  b << out(0, 0), out(1, 1), a[2], out(0, 1), out(1, 0), v[0], v[1];
  return b;
}

// Relative difference of two matrices in the max norm, scaled by the larger one.
template <class A, class B>
double relative_difference(const A& a, const B& b) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return (a - b).cwiseAbs().maxCoeff() / std::max(scale, 1e-300);
}

}  // namespace cosmpm::material::testing

namespace cosmpm::material::testing {

// The strain increment that takes `old_stress` elastically to `trial` (isotropic compliance,
// tensor shear), so a test can aim at a chosen trial stress.
inline SymTensor2D<double> increment_to(double shear, double lambda,
                                        const SymTensor2D<double>& old_stress,
                                        const SymTensor2D<double>& trial) {
  const SymTensor2D<double> d = trial - old_stress;
  const double bulk = lambda + 2.0 / 3.0 * shear;
  const double mean = (d[0] + d[1] + d[2]) / 3;
  const double volumetric = mean / (3 * bulk);  // strain of each normal component from p
  return {volumetric + (d[0] - mean) / (2 * shear), volumetric + (d[1] - mean) / (2 * shear),
          volumetric + (d[2] - mean) / (2 * shear), d[3] / (2 * shear)};
}

// Drained plane-strain biaxial compression: sigma_xx held at -confining by a Newton iteration on
// the x strain with the model's consistent tangent, y shortened in `steps` equal steps of
// `dyy`, zz and shear fixed. Returns the final stress. Works for the classical and (with
// symmetric, curvature-free increments) the Cosserat models.
template <class Model>
typename Model::stress_type biaxial_compression(const Model& model, double confining, double dyy,
                                                int steps) {
  using Stress = typename Model::stress_type;
  Stress stress = Stress::Zero();
  stress.template head<3>().setConstant(-confining);
  typename Model::state_type state{};
  for (int step = 0; step < steps; ++step) {
    typename Model::strain_type de = Model::strain_type::Zero();
    de[1] = dyy;
    for (int iteration = 0; iteration < 30; ++iteration) {
      Stress trial = stress;
      typename Model::state_type trial_state = state;
      typename Model::tangent_type tangent;
      model.update(trial, trial_state, de, tangent);
      const double residual = trial[0] + confining;
      if (std::abs(residual) <= 1e-12 * confining) break;
      de[0] -= residual / tangent(0, 0);
    }
    model.update(stress, state, de);
  }
  return stress;
}

}  // namespace cosmpm::material::testing
