// DruckerPrager<double, 3> and LinearElastic<double, 3>: the plane-strain kernels with six
// components.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "test_helpers.hpp"

using cosmpm::material::DruckerPrager;
using cosmpm::material::DruckerPragerMatching;
using cosmpm::material::LinearElastic;
using cosmpm::material::PlasticState;
using cosmpm::material::SymmetricTensor;
namespace conformance = cosmpm::material::conformance;
namespace testing = cosmpm::material::testing;

namespace {

using Vec6 = SymmetricTensor<3, double>;
constexpr double kE = 2.76e6;  // corn, the paper's Table 1
constexpr double kNu = 0.2;
constexpr double kPhi = 26.0;

// q = sqrt(J2) written out over the 3x3 tensor.
double q_of(const Vec6& s) {
  const Eigen::Matrix3d m = cosmpm::material::to_tensor<3>(s);
  const Eigen::Matrix3d dev = m - m.trace() / 3 * Eigen::Matrix3d::Identity();
  return std::sqrt(dev.cwiseProduct(dev).sum() / 2);
}

}  // namespace

TEST_CASE("LinearElastic 3D: Hooke's law with tensor shears, and the conformance kit") {
  const LinearElastic<double, 3> model({.youngs_modulus = kE, .poisson_ratio = kNu});
  const double g = model.shear_modulus(), lambda = model.lame_lambda();
  Vec6 stress = Vec6::Zero();
  cosmpm::material::NoState none;
  const Vec6 de(1e-4, -2e-4, 3e-4, 1e-4, -2e-4, 5e-5);
  model.update(stress, none, de);
  // sigma_ij = lambda tr(eps) delta_ij + 2 G eps_ij, the shears tensor components.
  for (int i = 0; i < 3; ++i) CHECK(stress[i] == doctest::Approx(lambda * 2e-4 + 2 * g * de[i]));
  for (int c = 3; c < 6; ++c) CHECK(stress[c] == doctest::Approx(2 * g * de[c]));
  const auto steps = conformance::random_steps(model, 1000, 1, 5e3, 1e-3);
  const std::vector<conformance::Step<LinearElastic<double, 3>>> tangent_steps{
      {Vec6(-1e3, -2e3, -1e3, 300, 100, -200), {}, de}};
  const auto report = conformance::check_constitutive_model(model, model, steps, tangent_steps);
  CHECK_MESSAGE(report.passed(), report.summary());
  CHECK(report.packed_lanes >= 2000);
}

TEST_CASE("DruckerPrager 3D: on the cone, flow along g, the apex, and plane strain recovered") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const double psi : {0.0, 10.0}) {
    const DruckerPrager<double, 3> model(kE, kNu, kPhi, psi, 1e3);
    const DruckerPrager<double> plane(model.parameters());
    const double beta = model.coefficients().beta;
    int smooth = 0, apex = 0;
    for (int n = 0; n < 3000; ++n) {
      Vec6 old, de;
      for (int c = 0; c < 6; ++c) {
        old[c] = 500 * uniform(rng) - (c < 3 ? 2e3 : 0.0);
        de[c] = 4e-3 * uniform(rng);
      }
      if (n % 10 == 0) de.head<3>().array() += 1e-2;                     // beyond the apex
      if (n % 10 == 1) de.tail<2>().setZero(), old.tail<2>().setZero();  // plane strain
      Vec6 stress = old;
      PlasticState state;
      model.update(stress, state, de);
      const double scale = stress.cwiseAbs().maxCoeff() + 1e3;
      CHECK(model.yield_function(stress) / scale <= 1e-10);
      if (n % 10 == 1) {  // the plane-strain model gives the same step
        cosmpm::SymTensor2D<double> s2 = old.head<4>();
        PlasticState st2;
        plane.update(s2, st2, cosmpm::SymTensor2D<double>(de.head<4>()));
        CHECK(testing::relative_difference(stress.head<4>(), s2) <= 1e-14);
        CHECK(stress.tail<2>().norm() == 0.0);
        CHECK(st2.plastic_shear_strain == state.plastic_shear_strain);
      }
      if (state.plastic == 0.0) continue;
      CHECK(std::abs(model.yield_function(stress)) / scale <= 1e-10);
      const Eigen::Matrix<double, 6, 6> compliance = model.elastic_tangent().inverse();
      const Vec6 plastic = de - compliance * (stress - old);
      if (q_of(stress) > 1e-9 * scale) {
        ++smooth;
        // d eps_p = dl (s / 2q + beta / 3 I) (tensor components), dl = the plastic strain.
        const double p = stress.head<3>().mean();
        Vec6 expected = stress / (2 * q_of(stress));
        expected.head<3>().array() += beta / 3 - p / (2 * q_of(stress));
        expected *= state.plastic_shear_strain;
        CHECK(testing::relative_difference(plastic, expected) <= 1e-7);
      } else {
        ++apex;
        CHECK(stress[0] == doctest::Approx(model.apex_pressure()));
      }
    }
    CHECK(smooth > 500);
    CHECK(apex > 50);
  }
}

TEST_CASE("DruckerPrager 3D: the conformance kit, tangents on the cone and at the apex") {
  const LinearElastic<double, 3> elastic(kE, kNu);
  const Vec6 old(-2e3, -1.5e3, -1.8e3, 300, -100, 200);
  unsigned seed = 21;
  for (const auto matching : {DruckerPragerMatching::plane_strain, DruckerPragerMatching::outer,
                              DruckerPragerMatching::inner}) {
    const DruckerPrager<double, 3> model({.youngs_modulus = kE,
                                          .poisson_ratio = kNu,
                                          .friction_angle_deg = kPhi,
                                          .dilatancy_angle_deg = 10,
                                          .cohesion = 1e3,
                                          .matching = matching});
    const auto to = [&](const Vec6& trial) {
      return Vec6(model.elastic_tangent().inverse() * (trial - old));
    };
    const std::vector<conformance::Step<DruckerPrager<double, 3>>> tangent_steps{
        {old, {}, to(Vec6(-10e3, -40e3, -20e3, 3e3, -2e3, 1e3))},  // cone
        {old, {}, to(Vec6(-5e3, -8e3, -30e3, -4e3, 2e3, 5e3))},    // cone
        {old, {}, to(Vec6(9e3, 8e3, 7e3, 100, 50, -80))}};         // apex
    const auto steps = conformance::random_steps(model, 1500, seed++, 5e3, 1e-3);
    const auto report = conformance::check_constitutive_model(model, elastic, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 200);
    CHECK(report.plastic > 200);
  }
}
