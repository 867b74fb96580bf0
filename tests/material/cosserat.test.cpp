#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "test_helpers.hpp"

using cosmpm::CosseratTensor2D;
using cosmpm::SymTensor2D;
using cosmpm::material::CosseratDruckerPrager;
using cosmpm::material::CosseratElastic;
using cosmpm::material::DruckerPrager;
using cosmpm::material::DruckerPragerMatching;
using cosmpm::material::PlasticState;
namespace testing = cosmpm::material::testing;
namespace conformance = cosmpm::material::conformance;

namespace {

// The paper's Cosserat corn (Table 1): E = 2.76 MPa, nu = 0.2, Gc = 2G, l = 10 mm, phi = 26,
// psi = 2 deg.
constexpr double kE = 2.76e6;
constexpr double kNu = 0.2;
constexpr double kG = kE / (2 * (1 + kNu));
constexpr double kGc = 2 * kG;
constexpr double kL = 0.01;
constexpr double kPhi = 26.0;

CosseratTensor2D<double> random_stress(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> normal(-3 * scale, 0.5 * scale);
  std::uniform_real_distribution<double> shear(-scale, scale);
  CosseratTensor2D<double> s;
  s << normal(rng), normal(rng), normal(rng), shear(rng), shear(rng), kL * shear(rng),
      kL * shear(rng);
  return s;
}

// The strain increment that takes `old` elastically to `trial`.
template <class Model>
CosseratTensor2D<double> increment_to(const Model& model, const CosseratTensor2D<double>& old,
                                      const CosseratTensor2D<double>& trial) {
  return model.elastic_tangent().inverse() * (trial - old);
}

// d q / d sigma written out from q^2 = a1 s_ij s_ij + a2 s_ij s_ji + a3 m.m / l^2.
CosseratTensor2D<double> q_gradient(const CosseratTensor2D<double>& s, double a1, double a2,
                                    double a3) {
  const double p = (s[0] + s[1] + s[2]) / 3;
  const double d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
  const double q2 = a1 * (d0 * d0 + d1 * d1 + d2 * d2 + s[3] * s[3] + s[4] * s[4]) +
                    a2 * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * s[3] * s[4]) +
                    a3 * (s[5] * s[5] + s[6] * s[6]) / (kL * kL);
  const double q = std::sqrt(q2);
  CosseratTensor2D<double> n;
  n << (a1 + a2) * d0 / q, (a1 + a2) * d1 / q, (a1 + a2) * d2 / q, (a1 * s[3] + a2 * s[4]) / q,
      (a1 * s[4] + a2 * s[3]) / q, a3 * s[5] / (kL * kL * q), a3 * s[6] / (kL * kL * q);
  return n;
}

}  // namespace

TEST_CASE("CosseratElastic: the de Borst law, written out by hand") {
  const CosseratElastic<double> model(kE, kNu, kGc, kL);
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  CosseratTensor2D<double> de;
  de << 1e-4, -2e-4, 0.0, 3e-4, -1e-4, 0.02, -0.01;
  CosseratTensor2D<double> stress = CosseratTensor2D<double>::Zero();
  cosmpm::material::NoState none;
  model.update(stress, none, de);
  const double tr = 1e-4 - 2e-4;
  CHECK(stress[0] == doctest::Approx(lambda * tr + 2 * kG * 1e-4));
  CHECK(stress[1] == doctest::Approx(lambda * tr + 2 * kG * -2e-4));
  CHECK(stress[2] == doctest::Approx(lambda * tr));
  CHECK(stress[3] == doctest::Approx((kG + kGc) * 3e-4 + (kG - kGc) * -1e-4));
  CHECK(stress[4] == doctest::Approx((kG + kGc) * -1e-4 + (kG - kGc) * 3e-4));
  CHECK(stress[5] == doctest::Approx(2 * kG * kL * kL * 0.02));
  CHECK(stress[6] == doctest::Approx(2 * kG * kL * kL * -0.01));
  // The stiffest wave: max(lambda + 2G, G + Gc) = G + Gc = 3G for Gc = 2G, nu = 0.2.
  CHECK(model.p_wave_modulus() == doctest::Approx(3 * kG));
  // Symmetric shear without curvature is classical elasticity with tensor shear.
  const cosmpm::material::LinearElastic<double> classical(kE, kNu);
  SymTensor2D<double> s4 = SymTensor2D<double>::Zero();
  classical.update(s4, none, SymTensor2D<double>(1e-4, -2e-4, 0, 2e-4));
  de << 1e-4, -2e-4, 0.0, 2e-4, 2e-4, 0, 0;
  stress.setZero();
  model.update(stress, none, de);
  CHECK(stress[3] == doctest::Approx(s4[3]));
  CHECK(stress[4] == doctest::Approx(s4[3]));
  CHECK(stress[0] == doctest::Approx(s4[0]));
}

TEST_CASE("CosseratDruckerPrager: reduces to the classical Drucker-Prager for symmetric stress") {
  // sigma_12 = sigma_21 and m = 0 (and symmetric, curvature-free increments): with the default
  // a1 + a2 = 1/2, q = sqrt(J2) and the Cosserat return must equal the classical one.
  for (const double psi : {0.0, 2.0, 26.0}) {
    const CosseratDruckerPrager<double> polar(kE, kNu, kGc, kL, kPhi, psi, 1e3);
    const DruckerPrager<double> classical(kE, kNu, kPhi, psi, 1e3,
                                          DruckerPragerMatching::plane_strain_per_angle);
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> normal(-15e3, 2.5e3), shear(-5e3, 5e3);
    int plastic = 0;
    for (int n = 0; n < 3000; ++n) {
      const SymTensor2D<double> old(normal(rng) * 0.1, normal(rng) * 0.1, normal(rng) * 0.1,
                                    shear(rng) * 0.1);
      const SymTensor2D<double> trial(normal(rng), normal(rng), normal(rng), shear(rng));
      const SymTensor2D<double> de =
          testing::increment_to(classical.shear_modulus(), classical.lame_lambda(), old, trial);
      SymTensor2D<double> s_classical = old;
      PlasticState st_classical;
      classical.update(s_classical, st_classical, de);
      CosseratTensor2D<double> s_polar, de_polar;
      s_polar << old[0], old[1], old[2], old[3], old[3], 0, 0;
      de_polar << de[0], de[1], de[2], de[3], de[3], 0, 0;
      PlasticState st_polar;
      polar.update(s_polar, st_polar, de_polar);
      CosseratTensor2D<double> expected;
      expected << s_classical[0], s_classical[1], s_classical[2], s_classical[3], s_classical[3], 0,
          0;
      CHECK(testing::relative_difference(s_polar, expected) <= 1e-12);
      CHECK(st_polar.plastic == st_classical.plastic);
      CHECK(st_polar.plastic_shear_strain ==
            doctest::Approx(st_classical.plastic_shear_strain).epsilon(1e-10));
      plastic += st_polar.plastic == 1.0;
    }
    CHECK(plastic > 500);
  }
}

TEST_CASE("CosseratDruckerPrager: returned stress on the surface, plastic strain along g") {
  std::mt19937_64 rng(31);
  const double a1 = 0.375, a2 = 0.125, a3 = 1.0;
  for (const double psi : {0.0, 2.0, 26.0}) {
    const CosseratDruckerPrager<double> model(kE, kNu, kGc, kL, kPhi, psi, 1e3);
    const double beta = model.coefficients().beta;
    const Eigen::Matrix<double, 7, 7> compliance = model.elastic_tangent().inverse();
    int smooth = 0, apex = 0;
    for (int n = 0; n < 3000; ++n) {
      const CosseratTensor2D<double> old = random_stress(rng, 5e3) * 0.1;
      CosseratTensor2D<double> trial = random_stress(rng, 5e3);
      if (n % 10 == 0) {  // all-round tension beyond the apex
        trial *= 0.01;
        trial.head<3>().array() += 10e3;
      }
      const CosseratTensor2D<double> de = increment_to(model, old, trial);
      CosseratTensor2D<double> stress = old;
      PlasticState state;
      model.update(stress, state, de);
      const double scale = stress.cwiseAbs().maxCoeff() + 1e3;
      CHECK(model.yield_function(stress) / scale <= 1e-10);
      if (state.plastic == 0.0) continue;
      CHECK(std::abs(model.yield_function(stress)) / scale <= 1e-10);
      if (model.invariant_q(stress) > 1e-9 * scale) {
        ++smooth;
        // d eps_p = dl (dq/dsigma + beta/3 I) at the returned stress, dl = the state's increment.
        const CosseratTensor2D<double> plastic = de - compliance * (stress - old);
        CosseratTensor2D<double> expected = q_gradient(stress, a1, a2, a3);
        expected.head<3>().array() += beta / 3;
        expected *= state.plastic_shear_strain;
        CHECK(testing::relative_difference(plastic, expected) <= 1e-7);
      } else {
        ++apex;
        CHECK(stress[0] == doctest::Approx(model.apex_pressure()));
        CHECK(stress.tail<4>().norm() == 0.0);
      }
    }
    CHECK(smooth > 500);
    CHECK(apex > 10);
  }
}

TEST_CASE("Cosserat models: the consistent tangents match finite differences") {
  // Elastic, the smooth cone with every mode active (non-symmetric shear, couple stresses, so
  // the modes shrink at different rates and the Newton solve matters), and the apex.
  const CosseratDruckerPrager<double> model(kE, kNu, kGc, kL, kPhi, 10.0, 1e3);
  const CosseratElastic<double> elastic(kE, kNu, kGc, kL);
  CosseratTensor2D<double> old;
  old << -2e3, -1.5e3, -1.8e3, 300, 100, 2.0, -1.0;
  CosseratTensor2D<double> t_elastic, t_cone, t_cone2, t_apex;
  t_elastic << -20e3, -21e3, -19e3, 100, 50, 3.0, 1.0;
  t_cone << -10e3, -40e3, -20e3, 3e3, -1e3, 40.0, -30.0;
  t_cone2 << -5e3, -8e3, -30e3, -4e3, 2e3, -10.0, 80.0;
  t_apex << 9e3, 8e3, 7e3, 100, -50, 1.0, 0.5;
  for (const auto& trial : {t_elastic, t_cone, t_cone2, t_apex}) {
    const CosseratTensor2D<double> de = increment_to(model, old, trial);
    CosseratTensor2D<double> stress = old;
    PlasticState state;
    CosseratDruckerPrager<double>::tangent_type tangent;
    model.update(stress, state, de, tangent);
    const auto numeric = testing::finite_difference_tangent(model, old, PlasticState{}, de);
    if (numeric.norm() == 0.0) {
      CHECK(tangent.norm() == 0.0);
    } else {
      CHECK(testing::relative_difference(tangent, numeric) <= 1e-6);
    }
  }
  const CosseratTensor2D<double> de = increment_to(elastic, old, t_cone);
  CosseratTensor2D<double> stress = old;
  cosmpm::material::NoState none;
  CosseratElastic<double>::tangent_type tangent;
  elastic.update(stress, none, de, tangent);
  CHECK(testing::relative_difference(
            tangent, testing::finite_difference_tangent(elastic, old, none, de)) <= 1e-6);
}

TEST_CASE("CosseratDruckerPrager: plane-strain biaxial compression reaches the matched peak") {
  // Symmetric loading keeps s_xy = s_yx = 0 and m = 0, so the limit is the classical one:
  // sin(phi_ps) = alpha sqrt(1 - beta^2/3) / (1 - alpha beta / 3) and the peak deviator
  // 2 sin(phi_ps) / (1 - sin(phi_ps)) confining; with plane_strain matching, the Mohr-Coulomb
  // peak (k - 1) confining.
  const double confining = 10e3;
  for (const auto matching :
       {DruckerPragerMatching::plane_strain, DruckerPragerMatching::plane_strain_per_angle}) {
    const CosseratDruckerPrager<double> model(kE, kNu, kGc, kL, kPhi, 2.0, 0.0, {}, matching);
    const double alpha = model.coefficients().alpha, beta = model.coefficients().beta;
    const double s = alpha * std::sqrt(1 - beta * beta / 3) / (1 - alpha * beta / 3);
    const auto stress = testing::biaxial_compression(model, confining, -1e-3, 2000);
    CHECK(stress[0] == doctest::Approx(-confining).epsilon(1e-10));
    CHECK(stress[0] - stress[1] == doctest::Approx(2 * s / (1 - s) * confining).epsilon(1e-6));
    if (matching == DruckerPragerMatching::plane_strain) {
      const double sp = std::sin(cosmpm::degrees_to_radians(kPhi));
      CHECK(stress[0] - stress[1] ==
            doctest::Approx((1 + sp) / (1 - sp) * confining - confining).epsilon(1e-6));
    }
  }
}

TEST_CASE("CosseratDruckerPrager: Gc = 0 with a1 != a2 and psi = 0 (a mode that never shrinks)") {
  // With Gc = 0 the skew mode has no stiffness (c_1 = 2 Gc (a1 - a2) = 0) and with psi = 0 the
  // cone does not move (alpha beta K = 0), so its rate r_1 is zero: the skew stress keeps its
  // old value and the other modes must absorb the whole return. Compressive volumetric
  // increments keep q0 = k - alpha p_trial above the skew part of an admissible old stress, so
  // a return exists for every state drawn here.
  const double c = 1e3;
  const CosseratDruckerPrager<double> model(kE, kNu, 0.0, kL, kPhi, 0.0, c);
  REQUIRE(model.coefficients().beta == 0.0);
  const double a1 = 0.375, a2 = 0.125, a3 = 1.0;  // the defaults, a1 != a2
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> strain(-2e-3, 2e-3), unit(-1.0, 1.0);
  int plastic = 0;
  for (int n = 0; n < 3000; ++n) {
    CosseratTensor2D<double> old = random_stress(rng, 5e3) * 0.1;
    if (model.yield_function(old) > 0) continue;
    CosseratTensor2D<double> de;
    for (int i = 0; i < 7; ++i) de[i] = strain(rng);
    de.tail<2>() /= kL;  // curvature: strain / l gives couple stresses m / l of stress size
    const double volumetric = de[0] + de[1] + de[2];
    if (volumetric > 0) de.head<3>().array() -= volumetric;  // compressive: q0 does not drop
    CosseratTensor2D<double> stress = old;
    PlasticState state;
    CosseratDruckerPrager<double>::tangent_type tangent;
    model.update(stress, state, de, tangent);
    REQUIRE(stress.allFinite());
    REQUIRE(tangent.allFinite());
    const double scale = stress.cwiseAbs().maxCoeff() + c;
    CHECK(model.yield_function(stress) / scale <= 1e-10);
    // The skew stress has no stiffness, elastic or plastic.
    CHECK(stress[3] - stress[4] == doctest::Approx(old[3] - old[4]).epsilon(1e-12));
    if (state.plastic == 0.0) continue;
    ++plastic;
    CHECK(std::abs(model.yield_function(stress)) / scale <= 1e-10);
    // Associated deviatoric flow, beta = 0: d eps_p = dl dq/dsigma. The elastic tangent is
    // singular in the skew direction, so compare the stress change D (de - d eps_p) instead.
    const CosseratTensor2D<double> flow =
        state.plastic_shear_strain * q_gradient(stress, a1, a2, a3);
    CHECK(testing::relative_difference(stress - old, model.elastic_tangent() * (de - flow)) <=
          1e-9);
    if (n % 20 == 0) {
      const auto numeric = testing::finite_difference_tangent(model, old, PlasticState{}, de);
      CHECK(testing::relative_difference(tangent, numeric) <= 1e-6);
    }
  }
  CHECK(plastic > 500);
}

TEST_CASE("Cosserat models: the conformance kit") {
  // The paper's parameters and models with three, two and one distinct mode rates (which the
  // batch merges), Gc = 0 among them; tangent steps: the cone with every mode active (two
  // trials) and the apex.
  using Model = CosseratDruckerPrager<double>;
  const CosseratElastic<double> elastic(kE, kNu, kGc, kL);
  CosseratTensor2D<double> old;
  old << -2e3, -1.5e3, -1.8e3, 300, 100, 2.0, -1.0;
  CosseratTensor2D<double> t_cone, t_cone2, t_apex;
  t_cone << -10e3, -40e3, -20e3, 3e3, -1e3, 40.0, -30.0;
  t_cone2 << -5e3, -8e3, -30e3, -4e3, 2e3, -10.0, 80.0;
  t_apex << 9e3, 8e3, 7e3, 100, -50, 1.0, 0.5;
  {
    const auto steps = conformance::random_steps(elastic, 1000, 1, 5e3, 1e-3, kL);
    const std::vector<conformance::Step<CosseratElastic<double>>> tangent_steps{
        {old, {}, increment_to(elastic, old, t_cone)}};
    const auto report =
        conformance::check_constitutive_model(elastic, elastic, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic == 1000);
  }
  struct Case {
    double gc;
    cosmpm::material::CosseratInvariantCoefficients<double> a;
    double psi, cohesion;
  };
  unsigned seed = 2;
  for (const Case& c :
       {Case{kGc, {}, 2.0, 0.0}, Case{20 * kGc, {}, 10.0, 1e3},
        Case{0.0, {0.25, 0.25, 0.5}, 2.0, 300.0}, Case{kGc, {0.375, 0.125, 0.5}, 26.0, 1e3}}) {
    const Model model({.youngs_modulus = kE,
                       .poisson_ratio = kNu,
                       .cosserat_shear_modulus = c.gc,
                       .characteristic_length = kL,
                       .friction_angle_deg = kPhi,
                       .dilatancy_angle_deg = c.psi,
                       .cohesion = c.cohesion,
                       .invariant = c.a});
    const CosseratElastic<double> part(kE, kNu, c.gc, kL);
    // Steps from the elastic law's inverse need Gc > 0; for Gc = 0 the increments of the
    // Gc = 2G model give trials of the same size.
    const CosseratElastic<double>& aim = c.gc > 0 ? part : elastic;
    std::vector<conformance::Step<Model>> tangent_steps;
    for (const auto& trial : {t_cone, t_cone2, t_apex})
      tangent_steps.push_back({old, PlasticState{}, increment_to(aim, old, trial)});
    const auto steps = conformance::random_steps(model, 1500, seed++, 5e3, 1e-3, kL);
    const auto report = conformance::check_constitutive_model(model, part, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 200);
    CHECK(report.plastic > 200);
  }
}
