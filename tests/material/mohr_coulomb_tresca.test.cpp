// MohrCoulomb at phi = 0 (with psi = 0, c > 0): Tresca, f = s1 - s3 - 2 c. The principal-space
// return keeps its plane and edge regions and has no apex (detail/mohr_coulomb_return.hpp).
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "test_helpers.hpp"

using cosmpm::SymTensor2D;
using cosmpm::material::MohrCoulomb;
using cosmpm::material::MohrCoulombParameters;
using cosmpm::material::MohrCoulombRegion;
using cosmpm::material::PlasticState;
using cosmpm::material::SymmetricTensor;
namespace testing = cosmpm::material::testing;
namespace conformance = cosmpm::material::conformance;

namespace {

// E = 2.5 MPa, nu = 0.25: G = lambda = 1 MPa, so the hand calculations below stay readable.
constexpr double kE = 2.5e6, kNu = 0.25, kShear = 1e6;
constexpr double kC = 10e3;  // undrained strength c (Pa)

MohrCoulombParameters tresca(double cohesion = kC) {
  return {.youngs_modulus = kE,
          .poisson_ratio = kNu,
          .friction_angle_deg = 0,
          .dilatancy_angle_deg = 0,
          .cohesion = cohesion};
}

// Sorted principal values of a plane-strain stress (independent of the model's split).
Eigen::Vector3d principal(const SymTensor2D<double>& a) {
  Eigen::Matrix2d m;
  m << a[0], a[3], a[3], a[1];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(m);
  Eigen::Vector3d v(solver.eigenvalues()[0], solver.eigenvalues()[1], a[2]);
  std::sort(v.data(), v.data() + 3, std::greater<>());
  return v;
}
Eigen::Vector3d principal(const SymmetricTensor<3, double>& s) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cosmpm::material::to_tensor<3>(s));
  return solver.eigenvalues().reverse();
}

using cosmpm::material::testing::expect_error;

// A random stress of a few c, compressive on average, and a random rotation (3D).
template <int Dim>
SymmetricTensor<Dim, double> random_stress(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> normal(-6 * scale, 1 * scale), shear(-scale, scale);
  SymmetricTensor<Dim, double> s;
  for (int i = 0; i < 3; ++i) s[i] = normal(rng);
  for (int i = 3; i < s.size(); ++i) s[i] = shear(rng);
  return s;
}

}  // namespace

TEST_CASE("Tresca: the returned stress lies on max(s1 - s3) = 2 c and keeps the mean stress") {
  // Random trials up to several c of deviator, in plane strain and in 3D. On the surface to
  // 1e-10 of the stress scale (the conformance kit's tolerance); psi = 0, so the plastic strain
  // is deviatoric and the mean stress is the trial's, to rounding.
  std::mt19937_64 rng(29);
  const auto check = [&]<int Dim>(const MohrCoulomb<double, Dim>& model) {
    int plastic = 0;
    for (int n = 0; n < 5000; ++n) {
      using Stress = SymmetricTensor<Dim, double>;
      const Stress old = random_stress<Dim>(rng, kC) * 0.2;
      const Stress trial = random_stress<Dim>(rng, kC);
      Stress stress = old;
      PlasticState state;
      const SymmetricTensor<Dim, double> d = trial - old;
      SymmetricTensor<Dim, double> de = d / (2 * kShear);
      const double mean = (d[0] + d[1] + d[2]) / 3, bulk = kShear + 2 * kShear / 3;
      for (int i = 0; i < 3; ++i) de[i] = mean / (3 * bulk) + (d[i] - mean) / (2 * kShear);
      model.update(stress, state, de);
      const Eigen::Vector3d s = principal(stress);
      const double scale = 6 * kC;
      CHECK(s[0] - s[2] <= 2 * kC + 1e-10 * scale);
      CHECK(model.yield_function(stress) == doctest::Approx(s[0] - s[2] - 2 * kC).scale(scale));
      if (state.plastic == 1.0) {
        ++plastic;
        CHECK(std::abs(s[0] - s[2] - 2 * kC) <= 1e-10 * scale);
        CHECK(std::abs(stress.template head<3>().mean() - trial.template head<3>().mean()) <=
              1e-10 * scale);
      }
    }
    CHECK(plastic > 1000);
  };
  check(MohrCoulomb<double, 2>(tresca()));
  check(MohrCoulomb<double, 3>(tresca()));
}

TEST_CASE("Tresca: the closed-form regions agree with the general multi-surface return") {
  // The oracle (detail::multisurface_return) tries every active set of the three sorted Tresca
  // planes s1 - s3, s2 - s3, s1 - s2 <= 2 c (and, with a cut-off, the three planes s_i <= t):
  // the plane and both edges are hit, the apex never (there is none).
  const double g = kShear, lambda = kShear;
  const auto d_times = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    return Eigen::Vector3d::Constant(lambda * v.sum()) + 2 * g * v;
  };
  for (const double cutoff : {-1.0, 5e3}) {  // -1: no cut-off
    MohrCoulombParameters p = tresca();
    if (cutoff >= 0) p.tension_cutoff = cutoff;
    const MohrCoulomb<double> model(p);
    CHECK(model.apex_stress() == std::numeric_limits<double>::infinity());
    cosmpm::material::detail::PlaneSet<double> planes;
    planes.add({1, 0, -1}, 2 * kC, d_times({1, 0, -1}));
    planes.add({0, 1, -1}, 2 * kC, d_times({0, 1, -1}));
    planes.add({1, -1, 0}, 2 * kC, d_times({1, -1, 0}));
    if (cutoff >= 0) {
      for (int i = 0; i < 3; ++i)
        planes.add(Eigen::Vector3d::Unit(i), cutoff, d_times(Eigen::Vector3d::Unit(i)));
    }
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> uniform(-8 * kC, 2 * kC);
    std::array<int, 6> hits{};
    for (int n = 0; n < 20000; ++n) {
      Eigen::Vector3d trial(uniform(rng), uniform(rng), uniform(rng));
      std::sort(trial.data(), trial.data() + 3, std::greater<>());
      Eigen::Vector3d result = Eigen::Vector3d::Zero(), oracle = Eigen::Vector3d::Zero();
      const auto region = model.principal_return(trial, result);
      ++hits[static_cast<int>(region)];
      if (region == MohrCoulombRegion::elastic) continue;
      REQUIRE(cosmpm::material::detail::multisurface_return(planes, trial, 1e-9 * kC, oracle));
      CHECK((result - oracle).norm() <= 1e-9 * kC);
    }
    CAPTURE(cutoff);
    CHECK(hits[static_cast<int>(MohrCoulombRegion::apex)] == 0);
    if (cutoff < 0) {
      for (const auto region :
           {MohrCoulombRegion::elastic, MohrCoulombRegion::plane,
            MohrCoulombRegion::compression_edge, MohrCoulombRegion::extension_edge})
        CHECK(hits[static_cast<int>(region)] > 100);
    } else {
      CHECK(hits[static_cast<int>(MohrCoulombRegion::tension)] > 100);
    }
  }
}

TEST_CASE("Tresca: a hand-calculated return in plane strain with sigma_zz carried") {
  // Old stress (-60, -40, -50, 0) kPa and a tensor shear increment of 0.01: the trial adds
  // 2 G 0.01 = 20 kPa of shear, (-60, -40, -50, 20) kPa. Its Mohr circle in the plane has
  // centre -50 kPa and radius sqrt(10^2 + 20^2) = 22.36 kPa, so s1 = -27.64, s3 = -72.36 kPa
  // (sigma_zz = -50 kPa the intermediate), f = 44.72 - 20 = 24.72 kPa > 0. The plane return
  // with psi = 0 removes f / 2 from s1 and adds it to s3: the circle shrinks to radius c about
  // the same centre and along the same directions, sigma_zz untouched:
  //   sigma_xx = -50 - 10 (10 / 22.36) = -54.472 kPa, sigma_yy = -45.528 kPa,
  //   sigma_xy = 10 (20 / 22.36) = 8.944 kPa, sigma_zz = -50 kPa;
  // the plastic strain is f / (4 G) (1, 0, -1) in principal axes, so its sqrt(2 e:e) is
  // f / (2 G) = 0.012361.
  const MohrCoulomb<double> model(tresca());
  REQUIRE(model.shear_modulus() == doctest::Approx(kShear));
  REQUIRE(model.lame_lambda() == doctest::Approx(kShear));
  SymTensor2D<double> stress(-60e3, -40e3, -50e3, 0);
  PlasticState state;
  const auto region = model.update_region(stress, state, SymTensor2D<double>(0, 0, 0, 0.01));
  CHECK(region == MohrCoulombRegion::plane);
  const double radius = std::sqrt(10e3 * 10e3 + 20e3 * 20e3);
  CHECK(stress[0] == doctest::Approx(-50e3 - kC * 10e3 / radius).epsilon(1e-12));
  CHECK(stress[1] == doctest::Approx(-50e3 + kC * 10e3 / radius).epsilon(1e-12));
  CHECK(stress[2] == doctest::Approx(-50e3).epsilon(1e-12));
  CHECK(stress[3] == doctest::Approx(kC * 20e3 / radius).epsilon(1e-12));
  CHECK(stress[0] == doctest::Approx(-54472.136).epsilon(1e-7));
  CHECK(stress[3] == doctest::Approx(8944.272).epsilon(1e-7));
  CHECK(state.plastic == 1.0);
  CHECK(state.plastic_shear_strain == doctest::Approx((2 * radius - 2 * kC) / (2 * kShear)));
  CHECK(state.plastic_shear_strain == doctest::Approx(0.012361).epsilon(1e-4));
}

TEST_CASE("Tresca: the corner returns (two active planes) keep the mean stress") {
  // With psi = 0 both edge flows are deviatoric, so an edge return lands on the edge line at
  // the trial's mean stress p: the extension edge s2 = s3 at (p + 4c/3, p - 2c/3, p - 2c/3),
  // the compression edge s1 = s2 at (p + 2c/3, p + 2c/3, p - 4c/3).
  const MohrCoulomb<double> model(tresca());
  const SymTensor2D<double> old(-50e3, -50e3, -50e3, 0);
  const auto aim = [&](const SymTensor2D<double>& trial) {
    return testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
  };
  {
    // Extension edge: trial (-50, -50, -20, 0) kPa, sigma_zz the largest. s1 - s3 = 30 kPa,
    // f = 10 kPa; the plane return (-25, -50, -45) would leave the sector (s2 < s3), so both
    // planes s1 - s3 and s1 - s2 are active. p = -40 kPa: sigma_zz = -26.667 kPa,
    // sigma_xx = sigma_yy = -46.667 kPa.
    SymTensor2D<double> stress = old;
    PlasticState state;
    CHECK(model.update_region(stress, state, aim({-50e3, -50e3, -20e3, 0})) ==
          MohrCoulombRegion::extension_edge);
    CHECK(stress[0] == doctest::Approx(-40e3 - 2 * kC / 3).epsilon(1e-12));
    CHECK(stress[1] == doctest::Approx(-40e3 - 2 * kC / 3).epsilon(1e-12));
    CHECK(stress[2] == doctest::Approx(-40e3 + 4 * kC / 3).epsilon(1e-12));
    CHECK(std::abs(stress[3]) <= 1e-9 * kC);
    CHECK(stress[2] == doctest::Approx(-26666.667).epsilon(1e-7));
  }
  {
    // Compression edge: in-plane principal stresses -20 and -22 kPa (axes rotated by 0.6 rad),
    // sigma_zz = -60 kPa the smallest. f = 40 - 20 = 20 kPa; the plane return (-30, -22, -50)
    // would put s1 below s2, so s1 - s3 and s2 - s3 are active. p = -34 kPa: the in-plane
    // stresses meet at -27.333 kPa (no shear left), sigma_zz = -47.333 kPa.
    SymTensor2D<double> stress = old;
    PlasticState state;
    CHECK(model.update_region(stress, state,
                              aim(testing::rotate(SymTensor2D<double>(-20e3, -22e3, -60e3, 0),
                                                  0.6))) == MohrCoulombRegion::compression_edge);
    CHECK(stress[0] == doctest::Approx(-34e3 + 2 * kC / 3).epsilon(1e-12));
    CHECK(stress[1] == doctest::Approx(-34e3 + 2 * kC / 3).epsilon(1e-12));
    CHECK(stress[2] == doctest::Approx(-34e3 - 4 * kC / 3).epsilon(1e-12));
    CHECK(std::abs(stress[3]) <= 1e-9 * kC);
    CHECK(stress[2] == doctest::Approx(-47333.333).epsilon(1e-7));
  }
}

TEST_CASE("Tresca: the phi -> 0 limit of Mohr-Coulomb") {
  // Away from the (distant) apex, phi = 1e-4 deg must return within O(sin phi) of phi = 0:
  // the Tresca branch is the limit of the general one, not a separate model.
  MohrCoulombParameters near = tresca();
  near.friction_angle_deg = 1e-4;
  const MohrCoulomb<double> limit(tresca()), general(near);
  std::mt19937_64 rng(37);
  int plastic = 0;
  for (int n = 0; n < 2000; ++n) {
    const SymTensor2D<double> old = random_stress<2>(rng, kC) * 0.2;
    const SymTensor2D<double> de = testing::increment_to(
        kShear, kShear, old, random_stress<2>(rng, kC));  // G = lambda for both
    SymTensor2D<double> a = old, b = old;
    PlasticState sa, sb;
    limit.update(a, sa, de);
    general.update(b, sb, de);
    plastic += sa.plastic == 1.0 ? 1 : 0;
    // sin(1e-4 deg) = 1.7e-6 times stresses of up to 6 c.
    CHECK(testing::relative_difference(a, b) <= 1e-4);
  }
  CHECK(plastic > 500);
}

TEST_CASE("Tresca: bad input names the value and the valid range") {
  MohrCoulombParameters p = tresca(0.0);
  expect_error([&] { MohrCoulomb<double>{p}; },
               {"MohrCoulomb", "friction_angle_deg = 0", "cohesion = 0", "(0, inf)"});
  p.cohesion = -1e3;
  expect_error([&] { MohrCoulomb<double>{p}; }, {"MohrCoulomb", "cohesion = -1000", "[0, inf)"});
  p = tresca();
  p.friction_angle_deg = -2;
  expect_error([&] { MohrCoulomb<double>{p}; },
               {"MohrCoulomb", "friction_angle_deg = -2", "[0, 90)"});
  p = tresca();
  p.dilatancy_angle_deg = 1;  // psi <= phi = 0
  expect_error([&] { MohrCoulomb<double>{p}; },
               {"MohrCoulomb", "dilatancy_angle_deg = 1", "[0, 0]"});
  p = tresca();
  p.tension_cutoff = -5.0;  // no apex: any cut-off >= 0
  expect_error([&] { MohrCoulomb<double, 3>{p}; },
               {"MohrCoulomb", "tension_cutoff = -5", "[0, inf]"});
  CHECK_NOTHROW(MohrCoulomb<double, 3>{tresca()});
}

TEST_CASE("Tresca: the conformance kit in plane strain and 3D") {
  // Tangent steps one per region, at hand-picked trials (kPa) away from region boundaries;
  // c = 2 kPa so that the kit's random steps (about 5 kPa, strains of 1e-3 E) are both kinds.
  const double c = 2e3;
  const cosmpm::material::LinearElastic<double> elastic2(
      {.youngs_modulus = kE, .poisson_ratio = kNu});
  const cosmpm::material::LinearElastic<double, 3> elastic3(
      {.youngs_modulus = kE, .poisson_ratio = kNu});
  const std::array<std::pair<Eigen::Vector3d, MohrCoulombRegion>, 4> trials{{
      {{-6e3, -7e3, -8e3}, MohrCoulombRegion::elastic},
      {{-2e3, -6e3, -10e3}, MohrCoulombRegion::plane},
      {{-2e3, -2.4e3, -10e3}, MohrCoulombRegion::compression_edge},
      {{-2e3, -9.6e3, -10e3}, MohrCoulombRegion::extension_edge},
  }};
  {
    using Model = MohrCoulomb<double, 2>;
    const Model model(tresca(c));
    const SymTensor2D<double> old(-5e3, -4e3, -4.5e3, 300);
    std::vector<conformance::Step<Model>> tangent_steps;
    for (const auto& [t, region] : trials) {
      // sigma_zz the intermediate principal stress, on the compression edge the smallest, on
      // the extension edge the largest.
      SymTensor2D<double> principal_axes(t[0], t[2], t[1], 0);
      if (region == MohrCoulombRegion::compression_edge) principal_axes = {t[0], t[1], t[2], 0};
      if (region == MohrCoulombRegion::extension_edge) principal_axes = {t[1], t[2], t[0], 0};
      const SymTensor2D<double> trial = testing::rotate(principal_axes, -0.5);
      const SymTensor2D<double> de =
          testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
      SymTensor2D<double> stress = old;
      PlasticState state;
      REQUIRE(model.update_region(stress, state, de) == region);
      tangent_steps.push_back({old, PlasticState{}, de});
    }
    const auto steps = conformance::random_steps(model, 2000, 41, 5e3, 1e-3);
    const auto report =
        conformance::check_constitutive_model(model, elastic2, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 300);
    CHECK(report.plastic > 300);
    CHECK(report.tangents == trials.size());
  }
  {
    using Model = MohrCoulomb<double, 3>;
    using Vec6 = SymmetricTensor<3, double>;
    const Model model(tresca(c));
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(0.9, 0.3, -0.2, 0.4).normalized().toRotationMatrix();
    const auto rotated = [&](const Eigen::Vector3d& values) {
      const Eigen::Matrix3d m = r * values.asDiagonal() * r.transpose();
      return cosmpm::material::from_tensor<3>(m);
    };
    const Vec6 old = rotated({-4e3, -4.5e3, -5e3});
    std::vector<conformance::Step<Model>> tangent_steps;
    for (const auto& [t, region] : trials) {
      const Vec6 d = rotated(t) - old;
      Vec6 de = d / (2 * model.shear_modulus());
      const double mean = (d[0] + d[1] + d[2]) / 3, bulk = model.bulk_modulus();
      for (int i = 0; i < 3; ++i)
        de[i] = mean / (3 * bulk) + (d[i] - mean) / (2 * model.shear_modulus());
      Vec6 stress = old;
      PlasticState state;
      REQUIRE(model.update_region(stress, state, de) == region);
      tangent_steps.push_back({old, PlasticState{}, de});
    }
    const auto steps = conformance::random_steps(model, 2000, 43, 5e3, 1e-3);
    const auto report =
        conformance::check_constitutive_model(model, elastic3, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 300);
    CHECK(report.plastic > 300);
    CHECK(report.tangents == trials.size());
  }
}
