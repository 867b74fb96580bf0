#include <doctest/doctest.h>

#include <functional>
#include <string>
#include <type_traits>

#include "cosmpm/material.hpp"
#include "test_helpers.hpp"

using namespace cosmpm::material;

namespace {

using cosmpm::material::testing::expect_error;

constexpr double kE = 2.76e6, kNu = 0.2, kG = kE / 2.4;

}  // namespace

TEST_CASE("Material parameters out of range give a cosmpm::Error naming value and range") {
  // Mohr-Coulomb: E, nu, phi, psi, c and the tension cut-off.
  expect_error([] { MohrCoulomb<double>(0.0, kNu, 26, 2); },
               {"MohrCoulomb", "youngs_modulus = 0", "(0, inf)"});
  expect_error([] { MohrCoulomb<double>(kE, 0.5, 26, 2); },
               {"MohrCoulomb", "poisson_ratio = 0.5", "(-1, 0.5)"});
  expect_error([] { MohrCoulomb<double>(kE, -1.0, 26, 2); }, {"poisson_ratio = -1", "(-1, 0.5)"});
  // phi = 0 is Tresca and needs cohesion (mohr_coulomb_tresca.test.cpp).
  expect_error([] { MohrCoulomb<double>(kE, kNu, 0, 0); },
               {"MohrCoulomb", "friction_angle_deg = 0", "cohesion = 0", "(0, inf)", "(0, 90)"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 90, 2); }, {"friction_angle_deg = 90", "[0, 90)"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 26, 30); },
               {"MohrCoulomb", "dilatancy_angle_deg = 30", "[0, 26]"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 26, -1); },
               {"dilatancy_angle_deg = -1", "[0, 26]"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 26, 2, -5.0); },
               {"MohrCoulomb", "cohesion = -5", "[0, inf)"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 26, 2, 0.0, 10.0); },
               {"MohrCoulomb", "tension_cutoff = 10", "[0, 0]"});
  expect_error([] { MohrCoulomb<double>(kE, kNu, 26, 2, 1e3, -1.0); },
               {"tension_cutoff = -1", "[0, 2050"});
  CHECK_NOTHROW(MohrCoulomb<double>(kE, kNu, 26, 26, 1e3, 0.0));
  CHECK_NOTHROW(MohrCoulomb<double>(kE, kNu, 26, 0));

  // Drucker-Prager.
  expect_error([] { DruckerPrager<double>(-1.0, kNu, 26, 2); },
               {"DruckerPrager", "youngs_modulus = -1"});
  expect_error([] { DruckerPrager<double>(kE, kNu, 100, 2); },
               {"DruckerPrager", "friction_angle_deg = 100", "(0, 90)"});
  expect_error([] { DruckerPrager<double>(kE, kNu, 26, 27); },
               {"DruckerPrager", "dilatancy_angle_deg = 27"});
  expect_error([] { DruckerPrager<double>(kE, kNu, 26, 2, -1.0); },
               {"DruckerPrager", "cohesion = -1"});

  // Cosserat elasticity and plasticity: l, Gc and the invariant coefficients.
  expect_error([] { CosseratElastic<double>(kE, kNu, 2 * kG, 0.0); },
               {"CosseratElastic", "characteristic_length = 0", "(0, inf)"});
  expect_error([] { CosseratElastic<double>(kE, kNu, -1.0, 0.01); },
               {"CosseratElastic", "cosserat_shear_modulus = -1", "[0, inf)"});
  expect_error([] { CosseratElastic<double>(kE, 0.7, 2 * kG, 0.01); },
               {"CosseratElastic", "poisson_ratio = 0.7"});
  expect_error([] { CosseratDruckerPrager<double>(kE, kNu, 2 * kG, -0.01, 26, 2); },
               {"CosseratDruckerPrager", "characteristic_length = -0.01"});
  expect_error([] { CosseratDruckerPrager<double>(kE, kNu, -2.0, 0.01, 26, 2); },
               {"CosseratDruckerPrager", "cosserat_shear_modulus = -2"});
  expect_error([] { CosseratDruckerPrager<double>(kE, kNu, 2 * kG, 0.01, 26, 40); },
               {"CosseratDruckerPrager", "dilatancy_angle_deg = 40"});
  expect_error(
      [] {
        CosseratDruckerPrager<double>(kE, kNu, 2 * kG, 0.01, 26, 2, 0, {0.1, 0.2, 1});
      },
      {"CosseratDruckerPrager", "a1 - a2 = -0.1", "[0, inf)"});
  expect_error(
      [] {
        CosseratDruckerPrager<double>(kE, kNu, 2 * kG, 0.01, 26, 2, 0, {0.375, 0.125, -1});
      },
      {"CosseratDruckerPrager", "a3 = -1"});
  CHECK_NOTHROW(CosseratElastic<double>(kE, kNu, 0.0, 0.01));  // Gc = 0 is allowed
}

TEST_CASE("Material parameters by name: the same model as the positional constructor") {
  // Corn (the paper's Table 1). The parameters are kept as given.
  const MohrCoulomb<double> by_name({.youngs_modulus = kE,
                                     .poisson_ratio = kNu,
                                     .friction_angle_deg = 26,
                                     .dilatancy_angle_deg = 2,
                                     .cohesion = 1e3});
  const MohrCoulomb<double> positional(kE, kNu, 26, 2, 1e3);
  CHECK(by_name.parameters().friction_angle_deg == 26);
  CHECK(by_name.parameters().dilatancy_angle_deg == 2);
  CHECK(by_name.friction_angle_deg() == 26);
  CHECK(by_name.apex_stress() == positional.apex_stress());
  // Class template argument deduction picks the double model.
  const MohrCoulomb deduced({.youngs_modulus = kE,
                             .poisson_ratio = kNu,
                             .friction_angle_deg = 26,
                             .dilatancy_angle_deg = 2});
  static_assert(std::is_same_v<decltype(deduced), const MohrCoulomb<double>>);
  // The same update, bit for bit, in the plastic and the elastic case.
  for (const double dyy : {-3e-3, -1e-6}) {
    cosmpm::SymTensor2D<double> a(-5e3, -5e3, -5e3, 0), b = a;
    PlasticState sa, sb;
    by_name.update(a, sa, {0, dyy, 0, 0});
    positional.update(b, sb, {0, dyy, 0, 0});
    CHECK(a == b);
    CHECK(sa.plastic_shear_strain == sb.plastic_shear_strain);
  }
  const DruckerPrager<double> dp({.youngs_modulus = kE,
                                  .poisson_ratio = kNu,
                                  .friction_angle_deg = 26,
                                  .dilatancy_angle_deg = 2,
                                  .matching = DruckerPragerMatching::inner});
  CHECK(dp.matching() == DruckerPragerMatching::inner);
  CHECK(
      dp.coefficients().alpha ==
      DruckerPrager<double>(kE, kNu, 26, 2, 0, DruckerPragerMatching::inner).coefficients().alpha);
  const CosseratDruckerPrager<double> cdp({.youngs_modulus = kE,
                                           .poisson_ratio = kNu,
                                           .cosserat_shear_modulus = 2 * kG,
                                           .characteristic_length = 0.01,
                                           .friction_angle_deg = 26,
                                           .dilatancy_angle_deg = 2,
                                           .invariant = {.a1 = 0.25, .a2 = 0.25, .a3 = 0.5}});
  CHECK(cdp.invariant_coefficients().a3 == 0.5);
  CHECK(cdp.coefficients().beta ==
        CosseratDruckerPrager<double>(kE, kNu, 2 * kG, 0.01, 26, 2).coefficients().beta);
  CHECK(LinearElastic<double>({.youngs_modulus = kE, .poisson_ratio = kNu}).shear_modulus() ==
        LinearElastic<double>(kE, kNu).shear_modulus());
  CHECK(CosseratElastic<double>({.youngs_modulus = kE,
                                 .poisson_ratio = kNu,
                                 .cosserat_shear_modulus = 0,
                                 .characteristic_length = 0.01})
            .bending_modulus() == CosseratElastic<double>(kE, kNu, 0, 0.01).bending_modulus());
}

TEST_CASE("Material parameters by name: a field left out or out of range is named") {
  // A required field left out of the designated initialiser (here the dilatancy angle).
  expect_error(
      [] {
        MohrCoulomb<double>({.youngs_modulus = kE, .poisson_ratio = kNu, .friction_angle_deg = 26});
      },
      {"MohrCoulomb", "dilatancy_angle_deg is not set",
       "MohrCoulombParameters{.dilatancy_angle_deg = ...}"});
  expect_error([] { LinearElastic<double>({.poisson_ratio = kNu}); },
               {"LinearElastic", "youngs_modulus is not set"});
  expect_error(
      [] {
        DruckerPrager<double>(
            {.youngs_modulus = kE, .friction_angle_deg = 26, .dilatancy_angle_deg = 2});
      },
      {"DruckerPrager", "poisson_ratio is not set"});
  expect_error(
      [] {
        CosseratElastic<double>(
            {.youngs_modulus = kE, .poisson_ratio = kNu, .cosserat_shear_modulus = 2 * kG});
      },
      {"CosseratElastic", "characteristic_length is not set"});
  expect_error(
      [] {
        CosseratDruckerPrager<double>({.youngs_modulus = kE,
                                       .poisson_ratio = kNu,
                                       .characteristic_length = 0.01,
                                       .friction_angle_deg = 26,
                                       .dilatancy_angle_deg = 2});
      },
      {"CosseratDruckerPrager", "cosserat_shear_modulus is not set"});
  // phi and psi given the wrong way round by name still fail by name: psi > phi.
  expect_error(
      [] {
        MohrCoulomb<double>({.youngs_modulus = kE,
                             .poisson_ratio = kNu,
                             .friction_angle_deg = 2,
                             .dilatancy_angle_deg = 26});
      },
      {"MohrCoulomb", "dilatancy_angle_deg = 26", "[0, 2]"});
  expect_error(
      [] {
        MohrCoulomb<double>({.youngs_modulus = kE,
                             .poisson_ratio = kNu,
                             .friction_angle_deg = 26,
                             .dilatancy_angle_deg = 2,
                             .tension_cutoff = 5.0});
      },
      {"MohrCoulomb", "tension_cutoff = 5", "[0, 0]"});
}
