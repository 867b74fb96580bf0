#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cosmpm/analysis/earth_pressure.hpp"
#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/core/error.hpp"

namespace ca = cosmpm::analysis;
using ca::EarthPressureCase;
using ca::EarthPressureProblem;

namespace {

// The paper's corn (Coetzee 2014, Table 1): phi = 26 deg, delta = 14 deg, rho = 778 kg/m^3.
constexpr double corn_gamma = 778 * 9.81;

EarthPressureProblem corn(double height) {
  return {.friction_angle_deg = 26,
          .wall_friction_deg = 14,
          .unit_weight = corn_gamma,
          .height = height};
}

double relative(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

}  // namespace

TEST_CASE("Smooth wall reproduces Rankine with weight, surcharge and cohesion") {
  // Rankine with cohesion (Bell): sigma_h = K (q + gamma z) +- 2 c sqrt(K), exact at every depth.
  for (const auto kind : {EarthPressureCase::passive, EarthPressureCase::active}) {
    for (double phi : {15.0, 26.0, 40.0}) {
      const EarthPressureProblem problem{.friction_angle_deg = phi,
                                         .wall_friction_deg = 0,
                                         .unit_weight = 15000,
                                         .height = 2,
                                         .surcharge = 8000,
                                         .cohesion = 3000};
      const ca::EarthPressureSolution solution = ca::sokolovski(kind, problem);
      const bool passive = kind == EarthPressureCase::passive;
      const double k = passive ? ca::rankine_kp(phi) : ca::rankine_ka(phi);
      CHECK(relative(solution.k_gamma, k) < 1e-4);
      for (const ca::WallStress& point : solution.wall) {
        const double expected = k * (problem.surcharge + problem.unit_weight * point.depth) +
                                (passive ? 2 : -2) * problem.cohesion * std::sqrt(k);
        CHECK(std::abs(point.normal_pressure - expected) < 1e-4 * std::abs(expected));
        CHECK(std::abs(point.shear_stress) < 1e-9 * std::abs(expected));
      }
      // Slip line of a smooth wall: straight at 45 -+ phi/2 from the tip (Rankine).
      const double exit =
          problem.height *
          std::tan(cosmpm::degrees_to_radians(passive ? 45 + phi / 2 : 45 - phi / 2));
      CHECK(relative(solution.slip_exit_distance, exit) < 1e-4);
    }
  }
}

TEST_CASE("Weightless wall reproduces the log-spiral closed form (Lancellotta 2002)") {
  // gamma = 0 and a surcharge q: sigma_n = K q along the whole wall, K from
  // log_spiral_k*_weightless. Cohesion by corresponding states: sigma_n + c cot phi =
  // K (q + c cot phi). Tolerance 1e-4 relative, as the issue asks.
  for (const auto kind : {EarthPressureCase::passive, EarthPressureCase::active}) {
    for (double phi : {20.0, 26.0, 35.0}) {
      for (double ratio : {0.25, 0.54, 1.0}) {
        const double delta = ratio * phi;
        const EarthPressureProblem problem{.friction_angle_deg = phi,
                                           .wall_friction_deg = delta,
                                           .unit_weight = 0,
                                           .height = 0.5,
                                           .surcharge = 1000,
                                           .cohesion = 200};
        const ca::EarthPressureSolution solution = ca::sokolovski(kind, problem);
        const double k = kind == EarthPressureCase::passive
                             ? ca::log_spiral_kp_weightless(phi, delta)
                             : ca::log_spiral_ka_weightless(phi, delta);
        const double shift = problem.cohesion / std::tan(cosmpm::degrees_to_radians(phi));
        for (const ca::WallStress& point : solution.wall) {
          CHECK(relative(point.normal_pressure + shift, k * (problem.surcharge + shift)) < 1e-4);
        }
      }
    }
  }
}

TEST_CASE("Forces, resultant depth and wall shear are consistent with K_gamma") {
  const ca::EarthPressureSolution s = ca::sokolovski_passive(corn(0.25));
  const double tan_delta = std::tan(cosmpm::degrees_to_radians(14));
  // Weight only: sigma_n = K gamma z, so P = K gamma h^2 / 2 at h/3 above the tip, and the
  // shear is sigma_n tan(delta) acting up on the wall (down on the soil).
  CHECK(s.horizontal_force_per_width ==
        doctest::Approx(s.k_gamma * corn_gamma * 0.25 * 0.25 / 2).epsilon(1e-12));
  CHECK(s.vertical_force_per_width ==
        doctest::Approx(-tan_delta * s.horizontal_force_per_width).epsilon(1e-9));
  CHECK(s.vertical_force_per_width < 0);
  CHECK(s.resultant_depth == doctest::Approx(2.0 / 3 * 0.25).epsilon(1e-4));
  CHECK(s.wall.front().depth == 0);
  CHECK(s.wall.back().depth == doctest::Approx(0.25).epsilon(1e-12));
  for (const ca::WallStress& point : s.wall) {
    CHECK(point.shear_stress == doctest::Approx(point.normal_pressure * tan_delta).epsilon(1e-9));
    // Linear profile of the self-similar solution, to the net's accuracy.
    CHECK(std::abs(point.normal_pressure - s.k_gamma * corn_gamma * point.depth) <
          1e-3 * s.k_gamma * corn_gamma * 0.25);
  }
  // Forces scale with gamma h^2; K_gamma does not depend on gamma or h.
  const ca::EarthPressureSolution deeper = ca::sokolovski_passive(corn(0.35));
  CHECK(deeper.k_gamma == doctest::Approx(s.k_gamma).epsilon(1e-12));
  CHECK(
      deeper.horizontal_force_per_width ==
      doctest::Approx(s.horizontal_force_per_width * (0.35 / 0.25) * (0.35 / 0.25)).epsilon(1e-9));
  // Active: the soil settles, the wall holds it up.
  const ca::EarthPressureSolution a = ca::sokolovski_active(corn(0.25));
  CHECK(a.vertical_force_per_width > 0);
  CHECK(a.wall.back().shear_stress < 0);
}

TEST_CASE("K_p converges under net refinement, with observed order and default accuracy") {
  // Three nets, each twice as fine in both directions. The observed order
  // p = log2(|K1 - K2| / |K2 - K3|) must be clearly positive and the differences shrink; the
  // Richardson estimate of the limit then bounds the error of the default net.
  for (double delta : {14.0, 26.0}) {
    const EarthPressureProblem problem{
        .friction_angle_deg = 26, .wall_friction_deg = delta, .unit_weight = 1, .height = 1};
    const double k1 = ca::sokolovski_passive(problem, {40, 20}).k_gamma;
    const double k2 = ca::sokolovski_passive(problem, {80, 40}).k_gamma;
    const double k3 = ca::sokolovski_passive(problem, {160, 80}).k_gamma;
    const double order = std::log2(std::abs(k1 - k2) / std::abs(k2 - k3));
    MESSAGE("phi = 26, delta = ", delta, ": K_p = ", k1, ", ", k2, ", ", k3, "; observed order ",
            order);
    CHECK(std::abs(k2 - k3) < std::abs(k1 - k2));
    CHECK(order > 1.0);
    const double limit = k3 + (k3 - k2) / (std::pow(2.0, order) - 1);
    const double k_default = ca::sokolovski_passive(problem).k_gamma;
    CHECK(relative(k_default, limit) < 1e-3);  // the documented accuracy of the default net
  }
}

TEST_CASE("Passive above active, K_p rising with delta and with phi") {
  double previous = 0;
  for (double delta = 0; delta <= 26; delta += 2) {
    const EarthPressureProblem problem{
        .friction_angle_deg = 26, .wall_friction_deg = delta, .unit_weight = 1, .height = 1};
    const double kp = ca::sokolovski_passive(problem).k_gamma;
    const double ka = ca::sokolovski_active(problem).k_gamma;
    CHECK(kp > ka);
    CHECK(kp > previous);
    previous = kp;
  }
  previous = 0;
  for (double phi = 10; phi <= 45; phi += 5) {
    const double kp =
        ca::sokolovski_passive(
            {.friction_angle_deg = phi, .wall_friction_deg = 10, .unit_weight = 1, .height = 1})
            .k_gamma;
    CHECK(kp > previous);
    previous = kp;
  }
}

TEST_CASE("K_p lies between the weightless log-spiral and Coulomb's planar wedge") {
  // With wall friction, Coulomb's plane overestimates passive pressure (planar mechanism), and
  // the weight term exceeds the weightless coefficient (Caquot-Kerisel tables list
  // K_p,gamma > K_p,q for delta > 0). For the corn: 3.458 < K_p < 3.799 (closed forms).
  for (double phi : {20.0, 26.0, 35.0}) {
    for (double ratio : {0.3, 0.54, 1.0}) {
      const double delta = ratio * phi;
      const double kp = ca::sokolovski_passive({.friction_angle_deg = phi,
                                                .wall_friction_deg = delta,
                                                .unit_weight = 1,
                                                .height = 1})
                            .k_gamma;
      CHECK(kp > ca::log_spiral_kp_weightless(phi, delta));
      CHECK(kp < ca::coulomb_kp(phi, delta));
    }
  }
}

TEST_CASE("The slip line runs from the wall tip to the surface between Rankine and Coulomb") {
  for (double height : {0.15, 0.25, 0.35}) {
    const ca::EarthPressureSolution s = ca::sokolovski_passive(corn(height));
    REQUIRE(s.slip_line.size() >= 3);
    CHECK(s.slip_line.front().distance == doctest::Approx(0.0));
    CHECK(s.slip_line.front().depth == doctest::Approx(height).epsilon(1e-12));
    CHECK(s.slip_line.back().depth == 0);
    CHECK(s.slip_line.back().distance == s.slip_exit_distance);
    // Rankine exit h tan(45 + phi/2); Coulomb exit h cot(rho) of the critical plane.
    const double rankine_exit = height * std::tan(cosmpm::degrees_to_radians(45 + 13));
    const double coulomb_exit =
        height * ca::coulomb_wedge(EarthPressureCase::passive, 26, 14).exit_distance_per_height;
    CHECK(s.slip_exit_distance > rankine_exit);
    CHECK(s.slip_exit_distance < coulomb_exit);
    // The line rises monotonically away from the wall.
    for (std::size_t i = 1; i < s.slip_line.size(); ++i) {
      CHECK(s.slip_line[i].distance >= s.slip_line[i - 1].distance);
      CHECK(s.slip_line[i].depth <= s.slip_line[i - 1].depth);
    }
  }
}

TEST_CASE("Bad input throws cosmpm::Error naming the field and its range") {
  const auto throws_with = [](EarthPressureProblem problem, const std::string& needle,
                              ca::CharacteristicsResolution resolution = {}) {
    try {
      (void)ca::sokolovski_passive(problem, resolution);
    } catch (const cosmpm::Error& error) {
      const std::string message = error.what();
      CHECK_MESSAGE(message.find(needle) != std::string::npos, message);
      CHECK(message.find("analysis::sokolovski_passive") != std::string::npos);
      return;
    }
    FAIL("expected cosmpm::Error containing ", needle);
  };
  EarthPressureProblem p = corn(0.25);
  p.wall_friction_deg = 27;
  throws_with(p, "wall_friction_deg = 27 is outside the valid range [0, 26]");
  p = corn(0.25), p.wall_friction_deg = -1;
  throws_with(p, "wall_friction_deg = -1");
  p = corn(0.25), p.friction_angle_deg = 0;
  throws_with(p, "friction_angle_deg = 0 is outside the valid range (0, 90)");
  p = corn(0.25), p.friction_angle_deg = 90;
  throws_with(p, "friction_angle_deg = 90");
  p = corn(0.25), p.friction_angle_deg = 61, p.wall_friction_deg = 0;
  throws_with(p, "friction_angle_deg = 61 is outside the valid range (0, 60]");
  p = corn(0.25), p.height = 0;
  throws_with(p, "height = 0");
  p = corn(0.25), p.height = -0.1;
  throws_with(p, "height = -0.1");
  p = corn(0.25), p.unit_weight = -1;
  throws_with(p, "unit_weight = -1");
  p = corn(0.25), p.surcharge = -5;
  throws_with(p, "surcharge = -5");
  p = corn(0.25), p.cohesion = -5;
  throws_with(p, "cohesion = -5");
  throws_with(corn(0.25), "resolution.wall_lines = 1", {1, 40});
  throws_with(corn(0.25), "resolution.fan_rays = 0", {80, 0});
  throws_with({.friction_angle_deg = 26, .unit_weight = 0, .height = 1}, "all 0");
  // Fields left unset are NaN and rejected rather than defaulted.
  throws_with({.friction_angle_deg = 26, .unit_weight = corn_gamma}, "height = nan");
  throws_with({.friction_angle_deg = 26, .height = 0.25}, "unit_weight = nan");
  throws_with({.unit_weight = 1, .height = 1}, "friction_angle_deg = nan");
}

TEST_CASE("Property: random phi, delta stay between the classical bounds (fixed seed)") {
  // Passive: log-spiral weightless < K_p < Coulomb (see above). Active: Coulomb's plane
  // slightly underestimates and wall friction lowers the smooth-wall value, so
  // coulomb_ka <= K_a <= rankine_ka. Coarse nets keep the test fast; the margins are far
  // larger than their discretisation error (< 1e-3 relative).
  std::mt19937 random(20141106);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int sample = 0; sample < 25; ++sample) {
    const double phi = 12 + 33 * unit(random);
    const double delta = (0.1 + 0.9 * unit(random)) * phi;
    const EarthPressureProblem problem{
        .friction_angle_deg = phi, .wall_friction_deg = delta, .unit_weight = 1, .height = 1};
    const ca::EarthPressureSolution passive = ca::sokolovski_passive(problem, {40, 20});
    const ca::EarthPressureSolution active = ca::sokolovski_active(problem, {40, 20});
    CAPTURE(phi);
    CAPTURE(delta);
    CHECK(passive.k_gamma > ca::log_spiral_kp_weightless(phi, delta));
    if (phi + delta < 90) CHECK(passive.k_gamma < ca::coulomb_kp(phi, delta));
    CHECK(active.k_gamma > ca::coulomb_ka(phi, delta));
    CHECK(active.k_gamma < ca::rankine_ka(phi));
    // The wall friction is fully mobilised along the whole wall in both cases.
    const double tan_delta = std::tan(cosmpm::degrees_to_radians(delta));
    const ca::WallStress& tip_p = passive.wall.back();
    const ca::WallStress& tip_a = active.wall.back();
    CHECK(tip_p.shear_stress == doctest::Approx(tip_p.normal_pressure * tan_delta).epsilon(1e-9));
    CHECK(tip_a.shear_stress == doctest::Approx(-tip_a.normal_pressure * tan_delta).epsilon(1e-9));
  }
}
