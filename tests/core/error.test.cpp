#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "cosmpm/core/error.hpp"

TEST_CASE("require_in_range names the value, the range and the source") {
  using cosmpm::Bounds;
  CHECK_NOTHROW(cosmpm::require_in_range("here", "phi", 26.0, 0.0, 90.0));
  try {
    cosmpm::require_in_range("MohrCoulomb", "friction_angle_deg", 95.0, 0.0, 90.0);
    FAIL("expected cosmpm::Error");
  } catch (const cosmpm::Error& error) {
    const std::string message = error.what();
    CHECK(message.find("MohrCoulomb") != std::string::npos);
    CHECK(message.find("friction_angle_deg = 95") != std::string::npos);
    CHECK(message.find("(0, 90)") != std::string::npos);
  }
  CHECK_THROWS_AS(cosmpm::require_in_range("x", "v", 0.0, 0.0, 1.0), cosmpm::Error);
  CHECK_NOTHROW(cosmpm::require_in_range("x", "v", 0.0, 0.0, 1.0, Bounds::left_closed));
  CHECK_THROWS_AS(cosmpm::require_in_range("x", "v", 1.0, 0.0, 1.0, Bounds::left_closed),
                  cosmpm::Error);
  CHECK_NOTHROW(cosmpm::require_in_range("x", "v", 1.0, 0.0, 1.0, Bounds::closed));
  // NaN is never in range, whatever the bounds.
  CHECK_THROWS_AS(cosmpm::require_in_range("x", "v", std::nan(""), 0.0, 1.0, Bounds::closed),
                  cosmpm::Error);
  CHECK_THROWS_AS(cosmpm::require_positive("x", "E", 0.0), cosmpm::Error);
  CHECK_THROWS_AS(cosmpm::require_positive("x", "E", std::numeric_limits<double>::infinity()),
                  cosmpm::Error);
  CHECK_THROWS_AS(cosmpm::require_non_negative("x", "c", -1e-12), cosmpm::Error);
  CHECK_NOTHROW(cosmpm::require_non_negative("x", "c", 0.0));
}
