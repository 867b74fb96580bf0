// MohrCoulomb<double, 3>: the principal-space return of the plane-strain model in 3D.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "test_helpers.hpp"

using cosmpm::material::MohrCoulomb;
using cosmpm::material::MohrCoulombRegion;
using cosmpm::material::PlasticState;
using cosmpm::material::SymmetricTensor;
namespace conformance = cosmpm::material::conformance;
namespace testing = cosmpm::material::testing;

namespace {

using Vec6 = SymmetricTensor<3, double>;
using Model3 = MohrCoulomb<double, 3>;

// The paper's corn (Table 1): E = 2.76 MPa, nu = 0.2, phi = 26 deg.
constexpr double kE = 2.76e6;
constexpr double kNu = 0.2;
constexpr double kPhi = 26.0;

double sin_deg(double degrees) {
  return std::sin(cosmpm::degrees_to_radians(degrees));
}

// A stress with principal values (a, b, c) along the axes of rotation r.
Vec6 principal_stress(double a, double b, double c, const Eigen::Matrix3d& r) {
  const Eigen::Matrix3d m = r * Eigen::Vector3d(a, b, c).asDiagonal() * r.transpose();
  return cosmpm::material::from_tensor<3>(m);
}

// The strain increment that takes `old` elastically to `trial` (isotropic compliance, tensor
// shear).
Vec6 increment_to(double shear, double lambda, const Vec6& old, const Vec6& trial) {
  const Vec6 d = trial - old;
  const double bulk = lambda + 2.0 / 3.0 * shear;
  const double mean = (d[0] + d[1] + d[2]) / 3;
  Vec6 de = d / (2 * shear);
  for (int i = 0; i < 3; ++i) de[i] = mean / (3 * bulk) + (d[i] - mean) / (2 * shear);
  return de;
}

// Sorted principal values, descending (independent of the model's split).
Eigen::Vector3d principal(const Vec6& s) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cosmpm::material::to_tensor<3>(s));
  return solver.eigenvalues().reverse();
}

Eigen::Matrix3d rotation(double a, double b, double c, double d) {
  return Eigen::Quaterniond(a, b, c, d).normalized().toRotationMatrix();
}

}  // namespace

TEST_CASE("MohrCoulomb 3D: every return region is hit on purpose") {
  const Model3 model({.youngs_modulus = kE,
                      .poisson_ratio = kNu,
                      .friction_angle_deg = kPhi,
                      .dilatancy_angle_deg = 2});  // c = 0: the apex at 0
  const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
  const Eigen::Matrix3d r = rotation(0.9, 0.3, -0.2, 0.4);
  const Vec6 old = principal_stress(-1e3, -1e3, -1e3, r);
  // Trials (principal values in kPa, then rotated): the cases of the plane-strain test.
  const std::array<std::pair<Eigen::Vector3d, MohrCoulombRegion>, 7> cases{{
      {{-20e3, -21e3, -10e3}, MohrCoulombRegion::elastic},
      {{-10e3, -20e3, -40e3}, MohrCoulombRegion::plane},
      {{-10e3, -10.5e3, -40e3}, MohrCoulombRegion::compression_edge},
      {{-10e3, -39e3, -40e3}, MohrCoulombRegion::extension_edge},
      {{5e3, 3e3, 1e3}, MohrCoulombRegion::apex},
      {{-10e3, -10e3, -40e3}, MohrCoulombRegion::compression_edge},  // s1 = s2 exactly
      {{-10e3, -40e3, -40e3}, MohrCoulombRegion::extension_edge},    // s2 = s3 exactly
  }};
  for (const auto& [values, region] : cases) {
    CAPTURE(values.transpose());
    const Vec6 trial = principal_stress(values[0], values[1], values[2], r);
    Vec6 stress = old;
    PlasticState state;
    REQUIRE(model.update_region(
                stress, state,
                increment_to(model.shear_modulus(), model.lame_lambda(), old, trial)) == region);
    const Eigen::Vector3d s = principal(stress);
    const double scale = 40e3;
    if (region == MohrCoulombRegion::elastic) {
      CHECK(state.plastic == 0.0);
      continue;
    }
    CHECK(state.plastic == 1.0);
    CHECK(std::abs(k * s[0] - s[2]) <= 1e-10 * scale);  // on the yield surface (c = 0)
    if (region == MohrCoulombRegion::compression_edge)
      CHECK(std::abs(s[0] - s[1]) <= 1e-10 * scale);
    if (region == MohrCoulombRegion::extension_edge) CHECK(std::abs(s[1] - s[2]) <= 1e-10 * scale);
    if (region == MohrCoulombRegion::apex) CHECK(stress.norm() <= 1e-10 * scale);
    if (region == MohrCoulombRegion::plane) {
      CHECK(s[0] - s[1] > 1e3);
      CHECK(s[1] - s[2] > 1e3);
    }
  }
  // The tension cut-off below the apex (c = 10 kPa, apex 20.5 kPa, cut-off 1 kPa): the plane
  // s1 = cut-off, the line s1 = s2 = cut-off and the point s1 = s2 = s3 = cut-off.
  const Model3 cut({.youngs_modulus = kE,
                    .poisson_ratio = kNu,
                    .friction_angle_deg = kPhi,
                    .dilatancy_angle_deg = 2,
                    .cohesion = 10e3,
                    .tension_cutoff = 1e3});
  const std::array<std::pair<Eigen::Vector3d, int>, 3> tension{
      {{{5e3, -2e3, -4e3}, 1}, {{5e3, 4e3, -4e3}, 2}, {{5e3, 4e3, 3e3}, 3}}};
  for (const auto& [values, at_cutoff] : tension) {
    CAPTURE(values.transpose());
    const Vec6 trial = principal_stress(values[0], values[1], values[2], r);
    Vec6 stress = old;
    PlasticState state;
    REQUIRE(cut.update_region(stress, state,
                              increment_to(cut.shear_modulus(), cut.lame_lambda(), old, trial)) ==
            MohrCoulombRegion::tension);
    const Eigen::Vector3d s = principal(stress);
    for (int i = 0; i < 3; ++i) {
      if (i < at_cutoff) {
        CHECK(s[i] == doctest::Approx(1e3).epsilon(1e-10));
      } else {
        CHECK(s[i] < 1e3 - 1.0);
      }
    }
  }
}

TEST_CASE("MohrCoulomb 3D: the return is the principal return rotated back with the trial's axes") {
  // Independent of the model's split: Eigen's solver on the trial, the model's principal_return
  // on the sorted values (shared with the plane-strain model and checked there against the
  // active-set oracle), and the result rebuilt with the trial's eigenvectors.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const double cohesion : {0.0, 5e3}) {
    const Model3 model(kE, kNu, kPhi, 10.0, cohesion);
    int plastic = 0;
    for (int n = 0; n < 3000; ++n) {
      const Eigen::Matrix3d r = rotation(uniform(rng), uniform(rng), uniform(rng), uniform(rng));
      const Vec6 old = principal_stress(-2e3, -3e3, -4e3, r);
      Vec6 trial;
      for (int c = 0; c < 6; ++c) trial[c] = 20e3 * uniform(rng) - (c < 3 ? 15e3 : 0.0);
      Vec6 stress = old;
      PlasticState state;
      model.update(stress, state,
                   increment_to(model.shear_modulus(), model.lame_lambda(), old, trial));
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(
          cosmpm::material::to_tensor<3>(trial));
      const Eigen::Vector3d sorted = solver.eigenvalues().reverse();
      Eigen::Vector3d returned;
      model.principal_return(sorted, returned);
      const Eigen::Matrix3d axes = solver.eigenvectors().rowwise().reverse();
      const Vec6 expected = cosmpm::material::from_tensor<3>(
          Eigen::Matrix3d(axes * returned.asDiagonal() * axes.transpose()));
      CHECK(testing::relative_difference(stress, expected) <= 1e-12);
      plastic += state.plastic == 1.0;
    }
    CHECK(plastic > 1000);
  }
}

TEST_CASE("MohrCoulomb 3D: plane strain is the 3D model with xz = yz = 0") {
  // A plane-strain step (no xz, yz in the old stress or the increment) in 3D equals the
  // plane-strain model's step: stress, plastic strain and the tangent's plane-strain block.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const auto& [psi, cohesion, cutoff] :
       {std::tuple{2.0, 0.0, -1.0}, std::tuple{10.0, 3e3, -1.0}, std::tuple{2.0, 10e3, 1e3}}) {
    const MohrCoulomb<double> plane(cosmpm::material::MohrCoulombParameters{
        kE, kNu, kPhi, psi, cohesion, cutoff < 0 ? std::nullopt : std::optional(cutoff)});
    const Model3 solid(plane.parameters());
    int plastic = 0;
    for (int n = 0; n < 2000; ++n) {
      cosmpm::SymTensor2D<double> old(-2e3 + 1e3 * uniform(rng), -2e3 + 1e3 * uniform(rng),
                                      -2e3 + 1e3 * uniform(rng), 500 * uniform(rng));
      cosmpm::SymTensor2D<double> de;
      for (int c = 0; c < 4; ++c) de[c] = 4e-3 * uniform(rng);
      if (n % 7 == 0) de.head<3>().array() += 8e-3;  // tension: apex, cut-off
      Vec6 old3 = Vec6::Zero(), de3 = Vec6::Zero();
      old3.head<4>() = old;
      de3.head<4>() = de;
      PlasticState s2, s3;
      MohrCoulomb<double>::tangent_type t2;
      Model3::tangent_type t3;
      plane.update(old, s2, de, t2);
      solid.update(old3, s3, de3, t3);
      CHECK(testing::relative_difference(old3.head<4>(), old) <= 1e-12);
      CHECK(old3.tail<2>().cwiseAbs().maxCoeff() <= 1e-12 * old.cwiseAbs().maxCoeff() + 1e-9);
      CHECK(s3.plastic == s2.plastic);
      CHECK(s3.plastic_shear_strain == doctest::Approx(s2.plastic_shear_strain).epsilon(1e-10));
      // Relative to the elastic stiffness: in the tension regions both are zero to rounding.
      CHECK((t3.topLeftCorner<4, 4>() - t2).cwiseAbs().maxCoeff() <= 1e-9 * plane.p_wave_modulus());
      plastic += s2.plastic == 1.0;
    }
    CHECK(plastic > 500);
  }
}

TEST_CASE("MohrCoulomb 3D: the conformance kit, tangents in every region") {
  const cosmpm::material::LinearElastic<double, 3> elastic(
      {.youngs_modulus = kE, .poisson_ratio = kNu});
  const Eigen::Matrix3d r = rotation(0.3, -0.5, 0.7, 0.2);
  const Vec6 old = principal_stress(-2e3, -1.5e3, -1.8e3, r) + Vec6(0, 0, 0, 100, -50, 80);
  // Tangent steps: principal trials (kPa) rotated by another rotation, one per region, away
  // from the region boundaries (as in the plane-strain test), and s1 = s2 exactly on the edge.
  const Eigen::Matrix3d q = rotation(-0.2, 0.4, 0.1, 0.8);
  const std::vector<Eigen::Vector3d> cone{{-20e3, -21e3, -10e3},   {-10e3, -20e3, -40e3},
                                          {-10e3, -10.5e3, -40e3}, {-10e3, -39e3, -40e3},
                                          {-10e3, -10e3, -40e3},   {8e3, 5e3, 6e3}};
  const std::vector<Eigen::Vector3d> cut_trials{{5e3, -2e3, -4e3}, {5e3, 4e3, -4e3}};
  struct Case {
    Model3 model;
    std::vector<Eigen::Vector3d> trials;
  };
  const std::vector<Case> cases{{Model3({.youngs_modulus = kE,
                                         .poisson_ratio = kNu,
                                         .friction_angle_deg = kPhi,
                                         .dilatancy_angle_deg = 2}),
                                 cone},
                                {Model3({.youngs_modulus = kE,
                                         .poisson_ratio = kNu,
                                         .friction_angle_deg = kPhi,
                                         .dilatancy_angle_deg = 10,
                                         .cohesion = 1e3}),
                                 cone},
                                {Model3({.youngs_modulus = kE,
                                         .poisson_ratio = kNu,
                                         .friction_angle_deg = kPhi,
                                         .dilatancy_angle_deg = 2,
                                         .cohesion = 10e3,
                                         .tension_cutoff = 1e3}),
                                 cut_trials}};
  unsigned seed = 11;
  for (const auto& [model, trials] : cases) {
    std::vector<conformance::Step<Model3>> tangent_steps;
    for (const auto& t : trials) {
      tangent_steps.push_back({old, PlasticState{},
                               increment_to(model.shear_modulus(), model.lame_lambda(), old,
                                            principal_stress(t[0], t[1], t[2], q))});
    }
    const auto steps = conformance::random_steps(model, 2000, seed++, 5e3, 1e-3);
    const auto report = conformance::check_constitutive_model(model, elastic, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 300);
    CHECK(report.plastic > 300);
    CHECK(report.tangents == trials.size());
  }
}

TEST_CASE("MohrCoulomb 3D: the elastic pre-check's cone is inscribed in the yield surface") {
  // inside_inscribed_cone(p, J2) lets the 3D model skip the eigenproblem; it must never call a
  // trial elastic that is not, and it is the largest such cone: it touches the yield plane at
  // the Lode angle t with tan t = sqrt3 / (2 k + 1) (s1 = p + 2 sqrt(J2 / 3) cos t,
  // s2 and s3 the same with t -+ 2 pi / 3).
  const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
  const double m = (1 + sin_deg(2.0)) / (1 - sin_deg(2.0));
  for (const auto& [cohesion, cutoff] : {std::pair{0.0, 0.0}, std::pair{5e3, 1e3}}) {
    const double apex = cohesion / std::tan(cosmpm::degrees_to_radians(kPhi));
    const double offset = 2 * cohesion * std::sqrt(k);
    const auto elastic = cosmpm::material::detail::isotropic_elasticity<double>("test", kE, kNu);
    const cosmpm::material::detail::MohrCoulombReturn<double> cone(elastic, k, m, offset, apex,
                                                                   cohesion > 0 ? cutoff : apex);
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> uniform(-40e3, 10e3);
    int inside = 0;
    for (int n = 0; n < 20000; ++n) {
      Eigen::Vector3d s(uniform(rng), uniform(rng), uniform(rng));
      std::sort(s.data(), s.data() + 3, std::greater<>());
      const double p = s.mean();
      const double j2 = (s.array() - p).square().sum() / 2;
      if (!cone.inside_inscribed_cone(p, j2)) continue;
      ++inside;
      CHECK(k * s[0] - s[2] - offset <= 1e-9 * 40e3);
      if (cohesion > 0) CHECK(s[0] <= cutoff + 1e-9 * 40e3);
    }
    CHECK(inside > 1000);
    // The touching point at p = -10 kPa: on the yield plane, and the cone's boundary.
    const double p = -10e3;
    const double t = std::atan(std::sqrt(3.0) / (2 * k + 1));
    const double root_j2 = (offset - (k - 1) * p) / (2 * std::sqrt((k * k + k + 1) / 3));
    const double r = 2 * root_j2 / std::sqrt(3.0);
    const Eigen::Vector3d touch(p + r * std::cos(t), p + r * std::cos(t - 2 * cosmpm::pi / 3),
                                p + r * std::cos(t + 2 * cosmpm::pi / 3));
    CHECK(std::abs(k * touch[0] - touch[2] - offset) <= 1e-10 * 10e3);
    CHECK(cone.inside_inscribed_cone(p, root_j2 * root_j2 * (1 - 1e-9)));
    CHECK_FALSE(cone.inside_inscribed_cone(p, root_j2 * root_j2 * (1 + 1e-9)));
  }
}
