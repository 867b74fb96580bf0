#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "conformance.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "test_helpers.hpp"

using cosmpm::SymTensor2D;
using cosmpm::material::MohrCoulomb;
using cosmpm::material::MohrCoulombRegion;
using cosmpm::material::PlasticState;
namespace testing = cosmpm::material::testing;
namespace conformance = cosmpm::material::conformance;

namespace {

// The paper's corn (Table 1): E = 2.76 MPa, nu = 0.2, phi = 26 deg.
constexpr double kE = 2.76e6;
constexpr double kNu = 0.2;
constexpr double kPhi = 26.0;

double sin_deg(double degrees) {
  return std::sin(cosmpm::degrees_to_radians(degrees));
}

// Sorted principal values of a plane-strain tensor (independent of the model's own code).
Eigen::Vector3d principal(const SymTensor2D<double>& a) {
  Eigen::Matrix2d m;
  m << a[0], a[3], a[3], a[1];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(m);
  Eigen::Vector3d v(solver.eigenvalues()[0], solver.eigenvalues()[1], a[2]);
  std::sort(v.data(), v.data() + 3, std::greater<>());
  return v;
}

// Plastic strain of an update: total increment minus the elastic part of the stress change.
SymTensor2D<double> plastic_strain(const MohrCoulomb<double>& model, const SymTensor2D<double>& old,
                                   const SymTensor2D<double>& now, const SymTensor2D<double>& de) {
  return de - testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, now);
}

// A random stress of a few kPa compression, roughly as in the blade problem.
SymTensor2D<double> random_stress(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> normal(-3 * scale, 0.5 * scale);
  std::uniform_real_distribution<double> shear(-scale, scale);
  return {normal(rng), normal(rng), normal(rng), shear(rng)};
}

}  // namespace

TEST_CASE("MohrCoulomb: every returned stress is on or inside the yield surface") {
  std::mt19937_64 rng(11);
  for (const double cohesion : {0.0, 2e3}) {
    for (const double psi : {0.0, 2.0, 10.0, 26.0}) {
      const MohrCoulomb<double> model(kE, kNu, kPhi, psi, cohesion);
      int plastic = 0;
      for (int n = 0; n < 5000; ++n) {
        const SymTensor2D<double> old = random_stress(rng, 5e3) * 0.1;
        const SymTensor2D<double> trial = random_stress(rng, 5e3);
        SymTensor2D<double> stress = old;
        PlasticState state;
        model.update(stress, state,
                     testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial));
        // |f| relative to the stress magnitude (1e-10, the tolerance).
        const double scale = std::max(stress.cwiseAbs().maxCoeff(), cohesion) + 1.0;
        const double f = model.yield_function(stress) / scale;
        CHECK(f <= 1e-10);
        if (state.plastic == 1.0) {
          ++plastic;
          CHECK(std::abs(f) <= 1e-10);
        }
      }
      CHECK(plastic > 1000);  // the batch really exercises the return
    }
  }
}

TEST_CASE("MohrCoulomb: closed-form regions agree with the general multi-surface return") {
  // The oracle tries every active set of the six sorted planes (three Mohr-Coulomb, three
  // cut-off) and keeps the one satisfying Koiter's conditions; it shares no code with the
  // closed-form regions except the elastic matrix.
  std::mt19937_64 rng(3);
  for (const double cohesion : {0.0, 5e3}) {
    for (const double psi : {0.0, 2.0, 26.0}) {
      const MohrCoulomb<double> model(kE, kNu, kPhi, psi, cohesion);
      // Up to twice the apex stress in tension so that the apex region is reached.
      std::uniform_real_distribution<double> uniform(-30e3, 10e3 + 2 * model.apex_stress());
      const double g = model.shear_modulus(), lambda = model.lame_lambda();
      const auto d_times = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
        return Eigen::Vector3d::Constant(lambda * v.sum()) + 2 * g * v;
      };
      const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
      const double m = (1 + sin_deg(psi)) / (1 - sin_deg(psi));
      const double offset = 2 * cohesion * std::sqrt(k);
      cosmpm::material::detail::PlaneSet<double> planes;
      planes.add({k, 0, -1}, offset, d_times({m, 0, -1}));
      planes.add({0, k, -1}, offset, d_times({0, m, -1}));
      planes.add({k, -1, 0}, offset, d_times({m, -1, 0}));
      for (int i = 0; i < 3; ++i)
        planes.add(Eigen::Vector3d::Unit(i), model.apex_stress(),
                   d_times(Eigen::Vector3d::Unit(i)));
      std::array<int, 6> hits{};
      for (int n = 0; n < 20000; ++n) {
        Eigen::Vector3d trial(uniform(rng), uniform(rng), uniform(rng));
        std::sort(trial.data(), trial.data() + 3, std::greater<>());
        Eigen::Vector3d result = Eigen::Vector3d::Zero(), oracle = Eigen::Vector3d::Zero();
        const auto region = model.principal_return(trial, result);
        ++hits[static_cast<int>(region)];
        if (region == MohrCoulombRegion::elastic) continue;
        REQUIRE(cosmpm::material::detail::multisurface_return(planes, trial, 1e-9 * 3e4, oracle));
        CHECK((result - oracle).norm() <= 1e-9 * 3e4);
      }
      for (int r = 0; r < 5; ++r) CHECK(hits[r] > 0);  // elastic, plane, both edges, apex
    }
  }
}

TEST_CASE("MohrCoulomb: the tension cut-off below the apex agrees with the oracle") {
  const double cohesion = 10e3, cutoff = 1e3;
  const MohrCoulomb<double> model(kE, kNu, kPhi, 2.0, cohesion, cutoff);
  const double g = model.shear_modulus(), lambda = model.lame_lambda();
  const auto d_times = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    return Eigen::Vector3d::Constant(lambda * v.sum()) + 2 * g * v;
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uniform(-60e3, 20e3);
  int tension = 0;
  for (int n = 0; n < 5000; ++n) {
    Eigen::Vector3d trial(uniform(rng), uniform(rng), uniform(rng));
    std::sort(trial.data(), trial.data() + 3, std::greater<>());
    Eigen::Vector3d result;
    const auto region = model.principal_return(trial, result);
    if (region == MohrCoulombRegion::tension) ++tension;
    // Independent checks of Koiter's conditions: no principal stress above the cut-off, no
    // Mohr-Coulomb violation, and the removed stress is D times a non-negative combination of
    // the active flows (checked by non-negative multipliers of the cut-off part where only the
    // cut-off is active).
    CHECK(result.maxCoeff() <= cutoff * (1 + 1e-12));
    const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
    CHECK(k * result.maxCoeff() - result.minCoeff() - 2 * cohesion * std::sqrt(k) <= 1e-8);
    if (region == MohrCoulombRegion::tension && result[1] < cutoff - 1e-6 &&
        k * result[0] - result[2] - 2 * cohesion * std::sqrt(k) < -1e-6) {
      // Only s1 <= cut-off active: the correction is dl * D e1 = dl (lambda + 2G, lambda, lambda).
      const Eigen::Vector3d removed = trial - result;
      const Eigen::Vector3d flow = d_times(Eigen::Vector3d::Unit(0));
      CHECK(removed.cross(flow).norm() <= 1e-9 * removed.norm() * flow.norm());
      CHECK(removed.dot(flow) > 0);
    }
  }
  CHECK(tension > 100);
}

TEST_CASE("MohrCoulomb: every return region is hit on purpose") {
  const MohrCoulomb<double> model(kE, kNu, kPhi, 2.0);  // c = 0: apex and cut-off at 0
  const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
  Eigen::Vector3d result;
  // Yield plane: a generic compressive state, s2 well inside (hand-picked, kPa).
  REQUIRE(model.principal_return({-10e3, -20e3, -40e3}, result) == MohrCoulombRegion::plane);
  CHECK(std::abs(k * result[0] - result[2]) <= 1e-10 * 40e3);
  CHECK(result[0] > result[1]);
  CHECK(result[1] > result[2]);
  // Compression edge: s1 and s2 nearly equal, the plane return would cross s1 = s2.
  REQUIRE(model.principal_return({-10e3, -10.5e3, -40e3}, result) ==
          MohrCoulombRegion::compression_edge);
  CHECK(result[0] == doctest::Approx(result[1]).epsilon(1e-12));
  CHECK(std::abs(k * result[0] - result[2]) <= 1e-10 * 40e3);
  // Extension edge: s2 and s3 nearly equal.
  REQUIRE(model.principal_return({-10e3, -39e3, -40e3}, result) ==
          MohrCoulombRegion::extension_edge);
  CHECK(result[1] == doctest::Approx(result[2]).epsilon(1e-12));
  CHECK(std::abs(k * result[0] - result[2]) <= 1e-10 * 40e3);
  // Apex: all-round tension returns to c cot(phi) = 0.
  REQUIRE(model.principal_return({5e3, 3e3, 1e3}, result) == MohrCoulombRegion::apex);
  CHECK(result.norm() == 0.0);
  // Elastic.
  REQUIRE(model.principal_return({-10e3, -20e3, -21e3}, result) == MohrCoulombRegion::elastic);

  // Tension cut-off below the apex (c = 10 kPa, apex 20.5 kPa, cut-off 1 kPa): the plane, the
  // line s1 = s2 = cut-off and the point s1 = s2 = s3 = cut-off.
  const MohrCoulomb<double> cut(kE, kNu, kPhi, 2.0, 10e3, 1e3);
  REQUIRE(cut.principal_return({5e3, -2e3, -4e3}, result) == MohrCoulombRegion::tension);
  CHECK(result[0] == doctest::Approx(1e3).epsilon(1e-12));
  CHECK(result[1] < 1e3);
  REQUIRE(cut.principal_return({5e3, 4e3, -4e3}, result) == MohrCoulombRegion::tension);
  CHECK(result[0] == doctest::Approx(1e3).epsilon(1e-12));
  CHECK(result[1] == doctest::Approx(1e3).epsilon(1e-12));
  REQUIRE(cut.principal_return({5e3, 4e3, 3e3}, result) == MohrCoulombRegion::tension);
  CHECK((result - Eigen::Vector3d::Constant(1e3)).norm() <= 1e-9);

  // The same regions through update(): the trial built from a strain increment, with the
  // principal axes rotated in plane and sigma_zz taking each of the three ranks.
  const SymTensor2D<double> old(-1e3, -1e3, -1e3, 0);
  const auto aim = [&](double a, double b, double zz) {
    return testing::rotate(SymTensor2D<double>(a, b, zz, 0), 0.4);
  };
  const std::array<std::pair<SymTensor2D<double>, MohrCoulombRegion>, 5> cases{{
      {aim(-10e3, -40e3, -20e3), MohrCoulombRegion::plane},
      {aim(-10.5e3, -40e3, -10e3), MohrCoulombRegion::compression_edge},
      {aim(-10e3, -39e3, -40e3), MohrCoulombRegion::extension_edge},
      {aim(5e3, 3e3, 1e3), MohrCoulombRegion::apex},
      {aim(-20e3, -21e3, -10e3), MohrCoulombRegion::elastic},
  }};
  for (const auto& [trial, region] : cases) {
    SymTensor2D<double> stress = old;
    PlasticState state;
    CHECK(model.update_region(stress, state,
                              testing::increment_to(model.shear_modulus(), model.lame_lambda(), old,
                                                    trial)) == region);
    CHECK(state.plastic == (region == MohrCoulombRegion::elastic ? 0.0 : 1.0));
  }
}

TEST_CASE("MohrCoulomb: the plastic strain follows the plastic potential (dilatancy psi)") {
  // For every Mohr-Coulomb flow b = (m, 0, -1) and its edge combinations,
  // tr(d eps_p) / sum |d eps_p,i| = (m - 1) / (m + 1) = sin(psi).
  for (const double psi : {0.0, 2.0, 10.0, 26.0}) {
    const MohrCoulomb<double> model(kE, kNu, kPhi, psi);
    const SymTensor2D<double> old(-1e3, -1e3, -1e3, 0);
    for (const auto& trial : {testing::rotate(SymTensor2D<double>(-10e3, -40e3, -20e3, 0), 0.3),
                              testing::rotate(SymTensor2D<double>(-10.5e3, -40e3, -10e3, 0), 1.1),
                              testing::rotate(SymTensor2D<double>(-10e3, -39e3, -40e3, 0), -0.7)}) {
      SymTensor2D<double> stress = old;
      PlasticState state;
      const SymTensor2D<double> de =
          testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
      const auto region = model.update_region(stress, state, de);
      REQUIRE(region != MohrCoulombRegion::elastic);
      REQUIRE(region != MohrCoulombRegion::apex);
      const Eigen::Vector3d eps = principal(plastic_strain(model, old, stress, de));
      CHECK(eps.sum() / eps.cwiseAbs().sum() == doctest::Approx(sin_deg(psi)).epsilon(1e-8));
      if (region == MohrCoulombRegion::plane) {
        CHECK(std::abs(eps[1]) <= 1e-9 * eps.cwiseAbs().maxCoeff());  // no intermediate flow
      }
      // The state's plastic shear strain is sqrt(2 e:e) of the plastic deviator.
      const Eigen::Vector3d dev = eps - Eigen::Vector3d::Constant(eps.mean());
      CHECK(state.plastic_shear_strain ==
            doctest::Approx(std::sqrt(2 * dev.squaredNorm())).epsilon(1e-8));
    }
  }
}

TEST_CASE("MohrCoulomb: past the dilatancy cut-off the flow is isochoric") {
  // A cut-off at a plastic shear strain of 0.1: below it the model flows as psi = 26 deg, at
  // and above it exactly as psi = 0 (the same yield surface); without a cut-off, as psi at any
  // strain.
  cosmpm::material::MohrCoulombParameters p{.youngs_modulus = kE,
                                            .poisson_ratio = kNu,
                                            .friction_angle_deg = kPhi,
                                            .dilatancy_angle_deg = 26.0};
  const MohrCoulomb<double> dilating(p);
  p.dilatancy_cutoff_strain = 0.1;
  const MohrCoulomb<double> with_cutoff(p);
  p.dilatancy_angle_deg = 0.0;
  p.dilatancy_cutoff_strain.reset();
  const MohrCoulomb<double> isochoric(p);
  const SymTensor2D<double> old(-1e3, -1e3, -1e3, 0);
  const SymTensor2D<double> de =
      testing::increment_to(dilating.shear_modulus(), dilating.lame_lambda(), old,
                            testing::rotate(SymTensor2D<double>(-10e3, -40e3, -20e3, 0), 0.3));
  const auto update = [&](const MohrCoulomb<double>& model, double strain_so_far) {
    SymTensor2D<double> stress = old;
    PlasticState state;
    state.plastic_shear_strain = strain_so_far;
    REQUIRE(model.update_region(stress, state, de) == MohrCoulombRegion::plane);
    return stress;
  };
  for (const double strain_so_far : {0.0, 0.0999}) {
    CHECK(update(with_cutoff, strain_so_far) == update(dilating, strain_so_far));
  }
  for (const double strain_so_far : {0.1, 5.0}) {
    CHECK(update(with_cutoff, strain_so_far) == update(isochoric, strain_so_far));
    CHECK(update(dilating, strain_so_far) != update(isochoric, strain_so_far));
  }
  // The isochoric return removes no volume: tr(d eps_p) = 0.
  SymTensor2D<double> stress = old;
  PlasticState state;
  state.plastic_shear_strain = 0.2;
  with_cutoff.update(stress, state, de);
  const Eigen::Vector3d eps = principal(plastic_strain(with_cutoff, old, stress, de));
  CHECK(std::abs(eps.sum()) <= 1e-9 * eps.cwiseAbs().maxCoeff());
  // A cut-off must be positive and finite.
  for (const double bad : {0.0, -0.1, std::numeric_limits<double>::infinity()}) {
    p.dilatancy_cutoff_strain = bad;
    CHECK_THROWS_WITH_AS(MohrCoulomb<double>{p}, doctest::Contains("dilatancy_cutoff_strain"),
                         cosmpm::Error);
  }
}

TEST_CASE("MohrCoulomb: the consistent tangent matches finite differences in every region") {
  // Central differences with a step of 1e-6 of the increment; agreement to 1e-6 relative.
  const MohrCoulomb<double> model(kE, kNu, kPhi, 2.0, 1e3);
  const MohrCoulomb<double> cut(kE, kNu, kPhi, 2.0, 10e3, 1e3);
  const SymTensor2D<double> old(-2e3, -1.5e3, -1.8e3, 300);
  const std::array<SymTensor2D<double>, 6> trials{
      testing::rotate(SymTensor2D<double>(-20e3, -21e3, -10e3, 0), 0.2),    // elastic
      testing::rotate(SymTensor2D<double>(-10e3, -40e3, -20e3, 0), 0.3),    // plane
      testing::rotate(SymTensor2D<double>(-10.5e3, -40e3, -10e3, 0), 0.5),  // compression edge
      testing::rotate(SymTensor2D<double>(-10e3, -39e3, -40e3, 0), -0.4),   // extension edge
      testing::rotate(SymTensor2D<double>(-10.2e3, -10e3, -40e3, 0), 0.7),  // edge, a ~ b in plane
      testing::rotate(SymTensor2D<double>(8e3, 5e3, 6e3, 0), 0.1),          // apex
  };
  for (const auto& trial : trials) {
    const SymTensor2D<double> de =
        testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
    SymTensor2D<double> stress = old;
    PlasticState state;
    MohrCoulomb<double>::tangent_type tangent;
    model.update(stress, state, de, tangent);
    const auto numeric = testing::finite_difference_tangent(model, old, PlasticState{}, de);
    if (numeric.norm() == 0.0) {
      CHECK(tangent.norm() == 0.0);
    } else {
      CHECK(testing::relative_difference(tangent, numeric) <= 1e-6);
    }
  }
  for (const auto& trial :
       {SymTensor2D<double>(5e3, -2e3, -4e3, 1e3), SymTensor2D<double>(5e3, 4e3, -4e3, 500)}) {
    const SymTensor2D<double> de =
        testing::increment_to(cut.shear_modulus(), cut.lame_lambda(), old, trial);
    SymTensor2D<double> stress = old;
    PlasticState state;
    MohrCoulomb<double>::tangent_type tangent;
    CHECK(cut.update_region(stress, state, de) == MohrCoulombRegion::tension);
    stress = old;
    cut.update(stress, state, de, tangent);
    const auto numeric = testing::finite_difference_tangent(cut, old, PlasticState{}, de);
    CHECK(testing::relative_difference(tangent, numeric) <= 1e-6);
  }
}

TEST_CASE("MohrCoulomb: drained plane-strain biaxial compression reaches the analytic peak") {
  // With c = 0 and sigma_xx = -confining the least compressive stress, the limit state is
  // sigma_yy = k sigma_xx, so the peak deviator is (k - 1) confining,
  // k = (1 + sin phi) / (1 - sin phi) (Mohr-Coulomb in principal stresses).
  for (const double psi : {2.0, 26.0}) {
    const MohrCoulomb<double> model(kE, kNu, kPhi, psi);
    const double confining = 10e3;
    const auto stress = testing::biaxial_compression(model, confining, -2e-5, 1500);
    const double k = (1 + sin_deg(kPhi)) / (1 - sin_deg(kPhi));
    CHECK(stress[0] == doctest::Approx(-confining).epsilon(1e-10));
    CHECK(stress[0] - stress[1] == doctest::Approx((k - 1) * confining).epsilon(1e-8));
  }
}

TEST_CASE("MohrCoulomb: the scalar hot path equals the general principal-space path") {
  // update() has its own scalar code for the closed-form regions; update_region() goes through
  // principal_return() and the spectral helpers. Both must give the same stress and state.
  std::mt19937_64 rng(23);
  for (const auto& model :
       {MohrCoulomb<double>(kE, kNu, kPhi, 2.0), MohrCoulomb<double>(kE, kNu, kPhi, 10.0, 3e3),
        MohrCoulomb<double>(kE, kNu, kPhi, 2.0, 10e3, 1e3)}) {
    for (int n = 0; n < 5000; ++n) {
      const SymTensor2D<double> old = random_stress(rng, 5e3) * 0.1;
      SymTensor2D<double> trial = random_stress(rng, 5e3);
      if (n % 20 == 0) trial[3] = 0;                       // principal axes along x, y
      if (n % 20 == 1) trial[1] = trial[0], trial[3] = 0;  // equal in-plane trial stresses
      const SymTensor2D<double> de =
          testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
      SymTensor2D<double> fast = old, general = old;
      PlasticState fast_state, general_state;
      model.update(fast, fast_state, de);
      (void)model.update_region(general, general_state, de);
      CHECK(testing::relative_difference(fast, general) <= 1e-12);
      CHECK(fast_state.plastic == general_state.plastic);
      CHECK(fast_state.plastic_shear_strain ==
            doctest::Approx(general_state.plastic_shear_strain).epsilon(1e-10));
    }
  }
}

TEST_CASE("MohrCoulomb: the conformance kit") {
  // Corn (c = 0, the flat blade's model), a cohesive one with more dilatancy, and one with a
  // tension cut-off below the apex; tangent steps one per region, aimed at hand-picked trials
  // (kPa) away from the region boundaries.
  using Model = MohrCoulomb<double>;
  struct Case {
    Model model;
    std::vector<std::pair<SymTensor2D<double>, MohrCoulombRegion>> tangent_trials;
  };
  const SymTensor2D<double> old(-2e3, -1.5e3, -1.8e3, 300);
  const auto aim = [](double a, double b, double zz, double angle) {
    return testing::rotate(SymTensor2D<double>(a, b, zz, 0), angle);
  };
  const std::vector<std::pair<SymTensor2D<double>, MohrCoulombRegion>> cone_trials{
      {aim(-20e3, -21e3, -10e3, 0.2), MohrCoulombRegion::elastic},
      {aim(-10e3, -40e3, -20e3, 0.3), MohrCoulombRegion::plane},
      {aim(-10.5e3, -40e3, -10e3, 0.5), MohrCoulombRegion::compression_edge},
      {aim(-10e3, -39e3, -40e3, -0.4), MohrCoulombRegion::extension_edge},
      {aim(8e3, 5e3, 6e3, 0.1), MohrCoulombRegion::apex}};
  const std::vector<Case> cases{
      {Model({.youngs_modulus = kE,
              .poisson_ratio = kNu,
              .friction_angle_deg = kPhi,
              .dilatancy_angle_deg = 2}),
       {cone_trials[0], cone_trials[1], cone_trials[2], cone_trials[3]}},
      {Model({.youngs_modulus = kE,
              .poisson_ratio = kNu,
              .friction_angle_deg = kPhi,
              .dilatancy_angle_deg = 10,
              .cohesion = 1e3}),
       cone_trials},
      {Model({.youngs_modulus = kE,
              .poisson_ratio = kNu,
              .friction_angle_deg = kPhi,
              .dilatancy_angle_deg = 2,
              .cohesion = 10e3,
              .tension_cutoff = 1e3}),
       {{SymTensor2D<double>(5e3, -2e3, -4e3, 1e3), MohrCoulombRegion::tension},
        {SymTensor2D<double>(5e3, 4e3, -4e3, 500), MohrCoulombRegion::tension}}}};
  const cosmpm::material::LinearElastic<double> elastic(
      {.youngs_modulus = kE, .poisson_ratio = kNu});
  unsigned seed = 1;
  for (const auto& [model, trials] : cases) {
    const auto steps = conformance::random_steps(model, 2000, seed++, 5e3, 1e-3);
    std::vector<conformance::Step<Model>> tangent_steps;
    for (const auto& [trial, region] : trials) {
      const SymTensor2D<double> de =
          testing::increment_to(model.shear_modulus(), model.lame_lambda(), old, trial);
      SymTensor2D<double> stress = old;
      PlasticState state;
      REQUIRE(model.update_region(stress, state, de) == region);
      tangent_steps.push_back({old, PlasticState{}, de});
    }
    const auto report = conformance::check_constitutive_model(model, elastic, steps, tangent_steps);
    CHECK_MESSAGE(report.passed(), report.summary());
    CHECK(report.elastic > 300);  // both kinds of step, well represented
    CHECK(report.plastic > 300);
  }
}
