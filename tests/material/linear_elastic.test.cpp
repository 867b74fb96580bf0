#include <doctest/doctest.h>

#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/linear_elastic.hpp"

using cosmpm::SymTensor2D;
using cosmpm::material::LinearElastic;
namespace conformance = cosmpm::material::conformance;

namespace {
constexpr double kE = 2.76e6;  // corn, the paper's Table 1
constexpr double kNu = 0.2;
}  // namespace

TEST_CASE("LinearElastic: Hooke's law in plane strain, written out by hand") {
  const LinearElastic<double> model({.youngs_modulus = kE, .poisson_ratio = kNu});
  // G = E / (2 (1 + nu)) = 1.15 MPa, lambda = E nu / ((1 + nu)(1 - 2 nu)) = 0.76667 MPa.
  const double g = 1.15e6, lambda = 2.76e6 * 0.2 / (1.2 * 0.6);
  CHECK(model.shear_modulus() == doctest::Approx(g).epsilon(1e-15));
  CHECK(model.lame_lambda() == doctest::Approx(lambda).epsilon(1e-15));
  CHECK(model.p_wave_modulus() == doctest::Approx(lambda + 2 * g).epsilon(1e-15));
  SymTensor2D<double> stress(-1e3, -2e3, -1.5e3, 100);
  cosmpm::material::NoState none;
  model.update(stress, none, SymTensor2D<double>(1e-4, -3e-4, 0.0, 5e-5));
  const double volumetric = lambda * (1e-4 - 3e-4);
  CHECK(stress[0] == doctest::Approx(-1e3 + volumetric + 2 * g * 1e-4).epsilon(1e-14));
  CHECK(stress[1] == doctest::Approx(-2e3 + volumetric - 2 * g * 3e-4).epsilon(1e-14));
  CHECK(stress[2] == doctest::Approx(-1.5e3 + volumetric).epsilon(1e-14));
  CHECK(stress[3] == doctest::Approx(100 + 2 * g * 5e-5).epsilon(1e-14));
}

TEST_CASE("LinearElastic: the conformance kit") {
  const LinearElastic<double> model(kE, kNu);
  const auto steps = conformance::random_steps(model, 1000, 1, 5e3, 1e-3);
  const std::vector<conformance::Step<LinearElastic<double>>> tangent_steps{
      {SymTensor2D<double>(-1e3, -2e3, -1e3, 300), {}, SymTensor2D<double>(1e-4, 2e-4, 0, -1e-4)}};
  const auto report = conformance::check_constitutive_model(model, model, steps, tangent_steps);
  CHECK_MESSAGE(report.passed(), report.summary());
  CHECK(report.elastic == 1000);
  // The packed hook runs on packs of 1 and 2 (and 4 with AVX) over all 1000 steps.
  CHECK(report.packed_lanes >= 2000);
  CHECK(report.tangents == 1);
}
