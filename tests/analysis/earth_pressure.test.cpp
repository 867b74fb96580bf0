#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cosmpm/analysis/earth_pressure.hpp"
#include "cosmpm/core/error.hpp"

namespace ca = cosmpm::analysis;
using ca::EarthPressureCase;
using cosmpm::degrees_to_radians;

TEST_CASE("Rankine coefficients: tan^2(45 +- phi/2) and reciprocal") {
  // phi = 30 deg: Kp = tan^2(60 deg) = 3 and Ka = 1/3 exactly (hand calculation).
  CHECK(ca::rankine_kp(30) == doctest::Approx(3.0).epsilon(1e-14));
  CHECK(ca::rankine_ka(30) == doctest::Approx(1.0 / 3).epsilon(1e-14));
  for (double phi = 5; phi < 80; phi += 7.5) {
    const double t = std::tan(degrees_to_radians(45 + phi / 2));
    CHECK(ca::rankine_kp(phi) == doctest::Approx(t * t).epsilon(1e-12));
    CHECK(ca::rankine_kp(phi) * ca::rankine_ka(phi) == doctest::Approx(1.0).epsilon(1e-14));
  }
}

TEST_CASE("Coulomb closed form equals the searched critical wedge and Rankine for delta = 0") {
  for (double phi : {15.0, 26.0, 35.0, 44.0}) {
    // A smooth wall: the planar wedge is Rankine's (textbook identity).
    CHECK(ca::coulomb_kp(phi, 0) == doctest::Approx(ca::rankine_kp(phi)).epsilon(1e-12));
    CHECK(ca::coulomb_ka(phi, 0) == doctest::Approx(ca::rankine_ka(phi)).epsilon(1e-12));
    for (double ratio : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const double delta = ratio * phi;
      // The wedge search minimises the force polygon numerically: an independent route to the
      // same number, agreeing to the golden-section tolerance (relative 1e-9).
      const ca::CoulombWedge active = ca::coulomb_wedge(EarthPressureCase::active, phi, delta);
      CHECK(active.k == doctest::Approx(ca::coulomb_ka(phi, delta)).epsilon(1e-9));
      if (phi + delta < 90) {
        const ca::CoulombWedge passive = ca::coulomb_wedge(EarthPressureCase::passive, phi, delta);
        CHECK(passive.k == doctest::Approx(ca::coulomb_kp(phi, delta)).epsilon(1e-9));
      }
    }
    // Smooth wall: the critical plane is at 45 -+ phi/2 from the horizontal.
    CHECK(ca::coulomb_wedge(EarthPressureCase::passive, phi, 0).plane_angle_deg ==
          doctest::Approx(45 - phi / 2).epsilon(1e-6));
    CHECK(ca::coulomb_wedge(EarthPressureCase::active, phi, 0).plane_angle_deg ==
          doctest::Approx(45 + phi / 2).epsilon(1e-6));
  }
}

TEST_CASE("Weightless log-spiral coefficients: Lancellotta's form equals the fan derivation") {
  // Independent form (docs/theory/earth_pressure.md): the Rankine surface state
  // p0 = q / (1 -+ sin phi), the fan multiplies p by exp(+-2 Delta tan phi), and the wall
  // normal stress is p (1 + sin phi cos 2 theta_w).
  for (double phi : {10.0, 26.0, 40.0}) {
    const double s = std::sin(degrees_to_radians(phi)), tp = std::tan(degrees_to_radians(phi));
    for (double ratio : {0.0, 0.3, 0.54, 0.8, 1.0}) {
      const double delta = degrees_to_radians(ratio * phi);
      const double omega = std::asin(std::min(1.0, std::sin(delta) / s));
      const double theta_p = 0.5 * (delta + omega);
      const double kp = (1 + s * std::cos(2 * theta_p)) / (1 - s) * std::exp(2 * theta_p * tp);
      CHECK(ca::log_spiral_kp_weightless(phi, ratio * phi) == doctest::Approx(kp).epsilon(1e-12));
      const double fan_a = 0.5 * (omega - delta);
      const double theta_a = 0.5 * cosmpm::pi + fan_a;
      const double ka = (1 + s * std::cos(2 * theta_a)) / (1 + s) * std::exp(-2 * fan_a * tp);
      CHECK(ca::log_spiral_ka_weightless(phi, ratio * phi) == doctest::Approx(ka).epsilon(1e-12));
    }
    CHECK(ca::log_spiral_kp_weightless(phi, 0) == doctest::Approx(ca::rankine_kp(phi)));
    CHECK(ca::log_spiral_ka_weightless(phi, 0) == doctest::Approx(ca::rankine_ka(phi)));
  }
  // Coulomb's planar K also multiplies a surcharge; the exact weightless (fan) solution lies
  // below it, since the plane is only one kinematically admissible passive mechanism.
  CHECK(ca::coulomb_kp(26, 14) > ca::log_spiral_kp_weightless(26, 14));
  CHECK(ca::coulomb_kp(30, 30) > ca::log_spiral_kp_weightless(30, 30));
}

TEST_CASE("Closed forms reject bad angles with the name, value and range") {
  CHECK_THROWS_AS(ca::rankine_kp(0), cosmpm::Error);
  CHECK_THROWS_AS(ca::rankine_kp(90), cosmpm::Error);
  CHECK_THROWS_AS(ca::rankine_ka(-5), cosmpm::Error);
  CHECK_THROWS_AS(ca::coulomb_kp(26, 27), cosmpm::Error);
  CHECK_THROWS_AS(ca::coulomb_kp(26, -1), cosmpm::Error);
  CHECK_THROWS_AS(ca::coulomb_kp(50, 45), cosmpm::Error);  // phi + delta >= 90: no wedge
  CHECK_THROWS_AS(ca::coulomb_ka(26, 30), cosmpm::Error);
  CHECK_THROWS_AS(ca::log_spiral_kp_weightless(26, 26.5), cosmpm::Error);
  CHECK_THROWS_AS(ca::log_spiral_ka_weightless(std::nan(""), 0), cosmpm::Error);
  try {
    (void)ca::coulomb_kp(26, 30);
    FAIL("expected cosmpm::Error");
  } catch (const cosmpm::Error& error) {
    const std::string message = error.what();
    CHECK(message.find("analysis::coulomb_kp") != std::string::npos);
    CHECK(message.find("wall_friction_deg = 30") != std::string::npos);
    CHECK(message.find("[0, 26]") != std::string::npos);
  }
}
