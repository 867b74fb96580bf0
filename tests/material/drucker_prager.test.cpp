#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "test_helpers.hpp"

using cosmpm::SymTensor2D;
using cosmpm::material::DruckerPrager;
using cosmpm::material::DruckerPragerMatching;
using cosmpm::material::PlasticState;
namespace testing = cosmpm::material::testing;
namespace conformance = cosmpm::material::conformance;

namespace {

constexpr double kE = 2.76e6;  // corn, the paper's Table 1
constexpr double kNu = 0.2;
constexpr double kPhi = 26.0;

double sin_deg(double degrees) {
  return std::sin(cosmpm::degrees_to_radians(degrees));
}

SymTensor2D<double> random_stress(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> normal(-3 * scale, 0.5 * scale);
  std::uniform_real_distribution<double> shear(-scale, scale);
  return {normal(rng), normal(rng), normal(rng), shear(rng)};
}

double q_of(const SymTensor2D<double>& s) {
  const double p = (s[0] + s[1] + s[2]) / 3;
  return std::sqrt(((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p)) /
                       2 +
                   s[3] * s[3]);
}

constexpr std::array<DruckerPragerMatching, 4> kMatchings{
    DruckerPragerMatching::plane_strain, DruckerPragerMatching::plane_strain_per_angle,
    DruckerPragerMatching::outer, DruckerPragerMatching::inner};

}  // namespace

TEST_CASE("DruckerPrager: the matchings pass through the Mohr-Coulomb corners they name") {
  const double c = 3e3;
  const double sp = sin_deg(kPhi);
  const double k = (1 + sp) / (1 - sp);
  const double offset = 2 * c * std::sqrt(k);
  // Outer: through the triaxial-compression corner s1 = s2 = x, s3 = k x - offset.
  // Inner: through the triaxial-extension corner s1 = y, s2 = s3 = k y - offset.
  const DruckerPrager<double> outer(kE, kNu, kPhi, 2.0, c, DruckerPragerMatching::outer);
  const DruckerPrager<double> inner(kE, kNu, kPhi, 2.0, c, DruckerPragerMatching::inner);
  for (const double x : {-1e3, -10e3, -50e3}) {
    const double scale = std::abs(k * x - offset);
    CHECK(std::abs(outer.yield_function({x, k * x - offset, x, 0})) <= 1e-12 * scale);
    CHECK(std::abs(inner.yield_function({x, k * x - offset, k * x - offset, 0})) <= 1e-12 * scale);
  }
  // Per-angle plane strain: the classical alpha = 3 tan(phi) / sqrt(9 + 12 tan^2 phi).
  const auto per_angle = cosmpm::material::drucker_prager_coefficients<double>(
      kPhi, 2.0, c, DruckerPragerMatching::plane_strain_per_angle);
  const double t = std::tan(cosmpm::degrees_to_radians(kPhi));
  CHECK(per_angle.alpha == doctest::Approx(3 * t / std::sqrt(9 + 12 * t * t)).epsilon(1e-14));
  // Every matching: apex at c cot(phi), like Mohr-Coulomb.
  for (const auto matching : kMatchings) {
    const DruckerPrager<double> model(kE, kNu, kPhi, 2.0, c, matching);
    CHECK(model.apex_pressure() == doctest::Approx(c / std::tan(cosmpm::degrees_to_radians(kPhi))));
  }
  // plane_strain with psi = phi is the associated formula.
  const auto associated = cosmpm::material::drucker_prager_coefficients<double>(
      kPhi, kPhi, c, DruckerPragerMatching::plane_strain);
  CHECK(associated.alpha == doctest::Approx(per_angle.alpha).epsilon(1e-14));
}

TEST_CASE("DruckerPrager: returned stresses are on the cone, the plastic flow follows g") {
  std::mt19937_64 rng(9);
  for (const auto matching : kMatchings) {
    for (const double psi : {0.0, 2.0, 26.0}) {
      const DruckerPrager<double> model(kE, kNu, kPhi, psi, 1e3, matching);
      const double beta = model.coefficients().beta;
      int smooth = 0, apex = 0;
      for (int n = 0; n < 3000; ++n) {
        const SymTensor2D<double> old = random_stress(rng, 5e3) * 0.1;
        // Every tenth trial in all-round tension beyond the apex, to reach the apex region.
        SymTensor2D<double> trial = random_stress(rng, 5e3);
        if (n % 10 == 0) trial = SymTensor2D<double>::Constant(10e3) + 0.01 * trial;
        const SymTensor2D<double> de =
            testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
        SymTensor2D<double> stress = old;
        PlasticState state;
        model.update(stress, state, de);
        const double scale = stress.cwiseAbs().maxCoeff() + 1e3;
        CHECK(model.yield_function(stress) / scale <= 1e-10);
        if (state.plastic == 0.0) continue;
        CHECK(std::abs(model.yield_function(stress)) / scale <= 1e-10);
        const SymTensor2D<double> plastic =
            de - testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, stress);
        const double volumetric = plastic[0] + plastic[1] + plastic[2];
        if (q_of(stress) > 1e-9 * scale) {
          ++smooth;
          // d eps_p = dl (s / 2q + beta / 3 I): volumetric / shear = beta, the deviator along s,
          // and the state's shear strain is dl = sqrt(2 e:e).
          CHECK(volumetric / state.plastic_shear_strain == doctest::Approx(beta).epsilon(1e-7));
          const double p = (stress[0] + stress[1] + stress[2]) / 3;
          const double q = q_of(stress);
          for (int i = 0; i < 3; ++i)
            CHECK(plastic[i] - volumetric / 3 ==
                  doctest::Approx(state.plastic_shear_strain * (stress[i] - p) / (2 * q))
                      .epsilon(1e-7)
                      .scale(state.plastic_shear_strain));
          CHECK(plastic[3] == doctest::Approx(state.plastic_shear_strain * stress[3] / (2 * q))
                                  .epsilon(1e-7)
                                  .scale(state.plastic_shear_strain));
        } else {
          ++apex;
          CHECK(stress[0] == doctest::Approx(model.apex_pressure()));
        }
      }
      CHECK(smooth > 500);
      CHECK(apex > 10);  // the apex region is reached on purpose by the tension trials
    }
  }
}

TEST_CASE("DruckerPrager: the consistent tangent matches finite differences") {
  const DruckerPrager<double> model(kE, kNu, kPhi, 10.0, 1e3);
  const SymTensor2D<double> old(-2e3, -1.5e3, -1.8e3, 300);
  for (const auto& trial : {SymTensor2D<double>(-20e3, -21e3, -19e3, 100),  // elastic
                            SymTensor2D<double>(-10e3, -40e3, -20e3, 3e3),  // cone
                            SymTensor2D<double>(-5e3, -8e3, -30e3, -4e3),   // cone
                            SymTensor2D<double>(9e3, 8e3, 7e3, 100)}) {     // apex
    const SymTensor2D<double> de =
        testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
    SymTensor2D<double> stress = old;
    PlasticState state;
    DruckerPrager<double>::tangent_type tangent;
    model.update(stress, state, de, tangent);
    const auto numeric = testing::finite_difference_tangent(model, old, PlasticState{}, de);
    if (numeric.norm() == 0.0) {
      CHECK(tangent.norm() == 0.0);
    } else {
      CHECK(testing::relative_difference(tangent, numeric) <= 1e-6);
    }
  }
}

TEST_CASE("DruckerPrager: plane-strain biaxial compression reaches the matched peak") {
  // At the plane-strain limit state (d eps_zz = 0 with constant stress) the cone f = q + alpha p
  // and g = q + beta p give sin(phi_ps) = alpha sqrt(1 - beta^2/3) / (1 - alpha beta / 3)
  // (docs/theory/materials.md), so the peak deviator is 2 sin(phi_ps) / (1 - sin(phi_ps)) times
  // the confining stress. For plane_strain matching sin(phi_ps) = sin(phi): the Mohr-Coulomb
  // peak (k - 1) confining.
  const double confining = 10e3;
  for (const auto matching : kMatchings) {
    const DruckerPrager<double> model(kE, kNu, kPhi, 2.0, 0.0, matching);
    const double alpha = model.coefficients().alpha, beta = model.coefficients().beta;
    const double s = alpha * std::sqrt(1 - beta * beta / 3) / (1 - alpha * beta / 3);
    // sigma_zz converges to its limit exponentially with the plastic strain, so the test goes
    // far (the return is exact for any step, small-strain kinematics make the size harmless).
    const auto stress = testing::biaxial_compression(model, confining, -1e-3, 2000);
    CHECK(stress[0] == doctest::Approx(-confining).epsilon(1e-10));
    CHECK(stress[0] - stress[1] == doctest::Approx(2 * s / (1 - s) * confining).epsilon(1e-6));
    if (matching == DruckerPragerMatching::plane_strain) {
      const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
      CHECK(stress[0] - stress[1] == doctest::Approx((k - 1) * confining).epsilon(1e-6));
    }
  }
}

TEST_CASE("DruckerPrager: the conformance kit") {
  // Every matching, with and without dilatancy and cohesion; tangent steps on the cone (two
  // trials, kPa) and at the apex, away from the boundary between them.
  using Model = DruckerPrager<double>;
  const cosmpm::material::LinearElastic<double> elastic(
      {.youngs_modulus = kE, .poisson_ratio = kNu});
  const SymTensor2D<double> old(-2e3, -1.5e3, -1.8e3, 300);
  unsigned seed = 1;
  for (const auto matching : kMatchings) {
    for (const auto& [psi, cohesion] : {std::pair{2.0, 0.0}, std::pair{10.0, 1e3}}) {
      const Model model({.youngs_modulus = kE,
                         .poisson_ratio = kNu,
                         .friction_angle_deg = kPhi,
                         .dilatancy_angle_deg = psi,
                         .cohesion = cohesion,
                         .matching = matching});
      std::vector<conformance::Step<Model>> tangent_steps;
      for (const auto& trial : {SymTensor2D<double>(-10e3, -40e3, -20e3, 3e3),
                                SymTensor2D<double>(-5e3, -8e3, -30e3, -4e3),
                                SymTensor2D<double>(9e3, 8e3, 7e3, 100)}) {
        tangent_steps.push_back(
            {old, PlasticState{},
             testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial)});
      }
      const auto steps = conformance::random_steps(model, 1500, seed++, 5e3, 1e-3);
      const auto report =
          conformance::check_constitutive_model(model, elastic, steps, tangent_steps);
      CHECK_MESSAGE(report.passed(), report.summary());
      CHECK(report.elastic > 200);
      CHECK(report.plastic > 200);
    }
  }
}
