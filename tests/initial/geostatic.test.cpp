#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "cosmpm/initial/geostatic.hpp"

TEST_CASE("jaky_k0 is 1 - sin(phi) and rejects angles outside (0, 90)") {
  // phi = 30 deg: sin = 1/2 exactly, K0 = 0.5. phi = 26 deg (corn): 1 - 0.438371 = 0.561629.
  CHECK(cosmpm::initial::jaky_k0(30.0) == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(cosmpm::initial::jaky_k0(26.0) == doctest::Approx(0.5616294).epsilon(1e-6));
  CHECK_THROWS_AS(cosmpm::initial::jaky_k0(0.0), cosmpm::Error);
  CHECK_THROWS_AS(cosmpm::initial::jaky_k0(90.0), cosmpm::Error);
}

TEST_CASE("geostatic_stress: sigma_yy = -rho g depth, sigma_xx = sigma_zz = K0 sigma_yy") {
  // Corn, rho = 778 kg/m^3, g = 9.81, 0.35 m deep (the deepest blade case):
  // sigma_yy = -778 * 9.81 * 0.35 = -2671.263 Pa.
  const double k0 = cosmpm::initial::jaky_k0(26.0);
  const auto s = cosmpm::initial::geostatic_stress(778.0, 9.81, 0.35, k0);
  CHECK(s[1] == doctest::Approx(-2671.263).epsilon(1e-12));
  CHECK(s[0] == doctest::Approx(k0 * -2671.263).epsilon(1e-12));
  CHECK(s[2] == s[0]);
  CHECK(s[3] == 0.0);
  // The free surface is stress free.
  CHECK(cosmpm::initial::geostatic_stress(778.0, 9.81, 0.0, k0).norm() == 0.0);
  const auto c = cosmpm::initial::geostatic_cosserat_stress(778.0, 9.81, 0.35, k0);
  CHECK(c[0] == s[0]);
  CHECK(c[1] == s[1]);
  CHECK(c[2] == s[2]);
  CHECK(c.tail<4>().norm() == 0.0);
}

TEST_CASE("geostatic_stress rejects bad input with the parameter named") {
  try {
    (void)cosmpm::initial::geostatic_stress(778.0, 9.81, -0.1, 0.5);
    FAIL("expected cosmpm::Error");
  } catch (const cosmpm::Error& error) {
    const std::string message = error.what();
    CHECK(message.find("geostatic_stress: depth = -0.1") != std::string::npos);
    CHECK(message.find("[0, inf)") != std::string::npos);
  }
  CHECK_THROWS_AS((void)cosmpm::initial::geostatic_stress(0.0, 9.81, 0.1, 0.5), cosmpm::Error);
  CHECK_THROWS_AS((void)cosmpm::initial::geostatic_stress(778.0, 0.0, 0.1, 0.5), cosmpm::Error);
  CHECK_THROWS_AS((void)cosmpm::initial::geostatic_stress(778.0, 9.81, 0.1, -0.5), cosmpm::Error);
}
