#pragma once
// Shared helpers of the material tests: finite-difference tangents, rotations, aimed increments.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::material::testing {

// Central finite-difference tangent d stress / d strain increment of any model, from the same
// old stress and state. The step is `relative_step` times the largest increment component.
template <class Model>
typename Model::tangent_type finite_difference_tangent(
    const Model& model, const typename Model::stress_type& old_stress,
    const typename Model::state_type& old_state, const typename Model::strain_type& de,
    double relative_step = 1e-6) {
  return conformance::detail::finite_difference_tangent(
      model, conformance::Step<Model>{old_stress, old_state, de}, relative_step);
}

// In-plane rotation by `angle` of [xx, yy, zz, xy] (stress or tensor-shear strain), or of a
// Cosserat stress or deformation (the non-symmetric 2x2 block as a tensor, the couple stress or
// curvature as a vector).
template <class Vector>
Vector rotate(const Vector& a, double angle) {
  return conformance::rotated(
      a, Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix());
}

// Relative difference of two matrices in the max norm, scaled by the larger one.
using conformance::detail::relative_difference;

// Runs `make`, expects a cosmpm::Error, and checks that the message names every fragment
// (the model, the parameter with its value, the valid range).
inline void expect_error(const std::function<void()>& make,
                         const std::vector<std::string>& fragments) {
  try {
    make();
    FAIL("expected cosmpm::Error");
  } catch (const cosmpm::Error& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments) {
      INFO("message: ", message, "  missing: ", fragment);
      CHECK(message.find(fragment) != std::string::npos);
    }
  }
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
