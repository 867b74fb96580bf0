// The blade-stress estimates of dem/blade_stress.hpp on contact sets with known answers.
#include <doctest/doctest.h>

#include <vector>

#include "cosmpm/dem/blade_stress.hpp"

using cosmpm::dem::FaceContact;

TEST_CASE("blade stress: evenly spaced equal forces give force / spacing") {
  // 35 contacts 10 mm apart, 20 N/m each: 2 kPa everywhere, in any order.
  std::vector<FaceContact> contacts;
  for (int k = 34; k >= 0; --k) contacts.push_back({0.005 + 0.01 * k, 20.0, 5.0});
  const auto stress = cosmpm::dem::neighbour_stress(contacts);
  REQUIRE(stress.size() == 34);
  for (const auto& s : stress) {
    CHECK(s.normal == doctest::Approx(2000.0));
    CHECK(s.shear == doctest::Approx(500.0));
  }
  CHECK(stress.front().along == doctest::Approx(0.01));
}

TEST_CASE("blade stress: a linear force profile is recovered at the midpoints") {
  // F_k = a s_k at spacing d: (F_k + F_k+1) / 2 / d = a s_mid / d, exact for a linear profile.
  std::vector<FaceContact> contacts;
  for (int k = 0; k < 20; ++k) contacts.push_back({0.01 * k, 100.0 * 0.01 * k, 0.0});
  for (const auto& s : cosmpm::dem::neighbour_stress(contacts)) {
    CHECK(s.normal == doctest::Approx(100.0 * s.along / 0.01));
  }
}

TEST_CASE("blade stress: binned averages add up to the mean total force") {
  cosmpm::dem::FaceStressAverage average(0.35, 0.025);
  double total = 0.0;
  for (int instant = 0; instant < 4; ++instant) {
    std::vector<FaceContact> contacts;
    for (int k = 0; k < 30; ++k) {
      const double along = 0.003 + 0.0115 * k + 0.001 * instant;
      contacts.push_back({along, 10.0 + k + instant, 1.0});
      total += 10.0 + k + instant;
    }
    average.add(contacts);
  }
  double integral = 0.0;
  for (const auto& bin : average.bins()) integral += bin.binned_normal * average.bin_length();
  CHECK(average.instants() == 4);
  CHECK(integral == doctest::Approx(total / 4.0).epsilon(1e-12));
  CHECK(average.bins().size() == 14);
}

TEST_CASE("blade stress: bad bins are errors naming the value") {
  CHECK_THROWS_WITH_AS(cosmpm::dem::FaceStressAverage(0.35, 0.0),
                       doctest::Contains("bin length = 0"), cosmpm::Error);
}
