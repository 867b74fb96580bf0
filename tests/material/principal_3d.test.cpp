// detail::Spectral3D, the split of a 3D trial stress the Mohr-Coulomb return uses: accurate
// to rounding for every gap between principal values, down to repeated ones. Eigen's closed
// form (computeDirect) fails this below gaps of about 1e-5 of the spread (checked: 4638 of
// the checks fail with it), so a faster split must keep the iterative solver there.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "cosmpm/material/detail/principal_3d.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace {

using Split = cosmpm::material::detail::Spectral3D<double>;

std::array<double, 6> components(const Eigen::Matrix3d& m) {
  return {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)};
}

}  // namespace

TEST_CASE("Spectral3D: principal values and the rebuilt stress to rounding, for any gap") {
  std::mt19937_64 rng(26);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Gaps between s1 and s2 (then between s2 and s3) as fractions of the spread s1 - s3:
  // either side of the 1e-3 switch, far below it, and exactly repeated values.
  const double gaps[] = {0.5, 0.1, 1e-2, 2e-3, 1.001e-3, 0.999e-3, 5e-4, 1e-5, 1e-8, 1e-12, 0.0};
  for (const double gap : gaps) {
    for (const bool upper : {true, false}) {
      for (int trial = 0; trial < 200; ++trial) {
        CAPTURE(gap);
        CAPTURE(upper);
        CAPTURE(trial);
        // Compression of a few kPa around a mean, in a random frame.
        const double s3 = -6e3 + 2e3 * unit(rng), spread = 1e3 + 900 * unit(rng);
        const double s1 = s3 + spread;
        const double s2 = upper ? s1 - gap * spread : s3 + gap * spread;
        const Eigen::Matrix3d r = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng))
                                      .normalized()
                                      .toRotationMatrix();
        const Eigen::Matrix3d stress = r * Eigen::Vector3d(s1, s2, s3).asDiagonal() * r.transpose();
        const Split split(components(stress));
        // Rounding of the rotated input alone is a few 1e-16 of |s3|.
        const double tolerance = 1e-12 * std::abs(s3);
        CHECK(std::abs(split.s1() - s1) <= tolerance);
        CHECK(std::abs(split.s2() - s2) <= tolerance);
        CHECK(std::abs(split.s3() - s3) <= tolerance);
        CHECK(split.s1() >= split.s2());
        CHECK(split.s2() >= split.s3());
        // The trial's own values put back along its directions give the trial again.
        const auto back = split.back(split.s1(), split.s2(), split.s3());
        const auto expected = components(stress);
        for (int c = 0; c < 6; ++c) CHECK(std::abs(back[c] - expected[c]) <= tolerance);
        // A return to new values keeps the directions: (r1, r2, r3) along the trial's axes.
        const Eigen::Matrix3d returned =
            r * Eigen::Vector3d(s1 - 100, s2 - 50, s3 + 30).asDiagonal() * r.transpose();
        const auto moved = split.back(split.s1() - 100, split.s2() - 50, split.s3() + 30);
        const auto wanted = components(returned);
        // Directions are determined to rounding / gap (for any solver), and this return moves
        // the pair apart by 50 Pa: compare where that stays within the tolerance.
        if (gap >= 1e-2) {
          for (int c = 0; c < 6; ++c) CHECK(std::abs(moved[c] - wanted[c]) <= tolerance);
        }
      }
    }
  }
}

TEST_CASE("Spectral3D: a non-finite trial gives non-finite principal values") {
  const Split split({std::nan(""), -1e3, -1e3, 0.0, 0.0, 0.0});
  CHECK_FALSE(std::isfinite(split.s1() + split.s2() + split.s3()));
}
