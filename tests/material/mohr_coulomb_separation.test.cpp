// MohrCoulombParameters::separation: a cohesionless point that dilated at the apex keeps the
// plastic volumetric strain of that return as a gap and stays stress-free until compression has
// closed it (mohr_coulomb.hpp). Hand-calculated values with G = lambda = 1 MPa.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "test_helpers.hpp"

using cosmpm::material::MohrCoulomb;
using cosmpm::material::MohrCoulombParameters;
using cosmpm::material::MohrCoulombRegion;
using cosmpm::material::PlasticState;
using Stress = MohrCoulomb<double>::stress_type;
using Strain = MohrCoulomb<double>::strain_type;

namespace {

// E = 2.5 MPa, nu = 0.25: G = lambda = 1 MPa, K = lambda + 2 G / 3 = 5/3 MPa.
constexpr double kE = 2.5e6, kNu = 0.25, kLambda = 1e6, kShear = 1e6;
constexpr double kBulk = kLambda + 2.0 * kShear / 3.0;

MohrCoulombParameters sand(bool separation) {
  return {.youngs_modulus = kE,
          .poisson_ratio = kNu,
          .friction_angle_deg = 30,
          .dilatancy_angle_deg = 5,
          .separation = separation};
}

Strain strain(double xx, double yy, double xy) {
  return Strain(xx, yy, 0.0, xy);
}

}  // namespace

TEST_CASE("separation: an apex return opens a gap of p_trial / K, held stress-free until closed") {
  const MohrCoulomb<double> model(sand(true));
  REQUIRE(model.separates());
  Stress stress(-1000.0, -1000.0, -1000.0, 0.0);
  PlasticState state;

  // Stretch: de = (1e-3, 1e-3) in plane strain. Trial: xx = yy = -1000 + (lambda + 2 G) 1e-3 +
  // lambda 1e-3 = 3000, zz = -1000 + lambda 2e-3 = 1000: all tension, the apex (zero stress).
  // Trial mean 2333.3 Pa; the gap is 2333.3 / K = 1.4e-3 = tr(de) - (0 - p_old) / K.
  CHECK(model.update_region(stress, state, strain(1e-3, 1e-3, 0.0)) == MohrCoulombRegion::apex);
  CHECK(stress.norm() == 0.0);
  CHECK(state.separation == doctest::Approx(1.4e-3).epsilon(1e-12));
  const double shear_after_apex = state.plastic_shear_strain;

  // Compress by less than the gap, with shear: still apart, no stress; the gap shrinks by the
  // volumetric increment (1e-3) and all the deviator is plastic: e = (-1/6, -1/6, 1/3) 1e-3 and
  // e_xy = 0.2e-3, sqrt(2 e:e) = sqrt(2 (1/36 + 1/36 + 1/9 + 2 * 0.04) 1e-6).
  const Strain squeeze = strain(-0.5e-3, -0.5e-3, 0.2e-3);
  CHECK(model.update_region(stress, state, squeeze) == MohrCoulombRegion::separated);
  CHECK(stress.norm() == 0.0);
  CHECK(state.separation == doctest::Approx(0.4e-3).epsilon(1e-12));
  CHECK(state.plastic == 1.0);
  const double deviator = std::sqrt(2.0 * (1.0 / 36 + 1.0 / 36 + 1.0 / 9 + 2 * 0.04) * 1e-6);
  CHECK(state.plastic_shear_strain - shear_after_apex == doctest::Approx(deviator));

  // Compress by 1.2e-3: the first third closes the gap, the rest loads the packing from zero:
  // de = (-0.4e-3, -0.4e-3) elastic, xx = yy = -(lambda + 2 G) 0.4e-3 - lambda 0.4e-3 = -1600,
  // zz = -lambda 0.8e-3 = -800; f = 800 - 2400 sin 30 < 0.
  CHECK(model.update_region(stress, state, strain(-0.6e-3, -0.6e-3, 0.0)) ==
        MohrCoulombRegion::elastic);
  CHECK(state.separation == 0.0);
  CHECK(stress[0] == doctest::Approx(-1600.0).epsilon(1e-12));
  CHECK(stress[1] == doctest::Approx(-1600.0).epsilon(1e-12));
  CHECK(stress[2] == doctest::Approx(-800.0).epsilon(1e-12));
  CHECK(stress[3] == doctest::Approx(0.0).scale(1.0));
}

TEST_CASE("separation: without it the swollen point is stressed at its first compression") {
  const MohrCoulomb<double> model(sand(false));
  Stress stress(-1000.0, -1000.0, -1000.0, 0.0);
  PlasticState state;
  CHECK(model.update_region(stress, state, strain(1e-3, 1e-3, 0.0)) == MohrCoulombRegion::apex);
  CHECK(state.separation == 0.0);
  // The same squeeze as above: an elastic trial from zero, xx = yy = -2000 (+ shear).
  model.update(stress, state, strain(-0.5e-3, -0.5e-3, 0.0));
  CHECK(stress[0] == doctest::Approx(-2000.0));
  CHECK(stress[2] == doctest::Approx(-1000.0));
}

TEST_CASE("separation: a point that never reaches the apex is updated bit for bit as without") {
  const MohrCoulomb<double> with(sand(true));
  const MohrCoulomb<double> without(sand(false));
  std::mt19937 random(12);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Stress a(-2e4, -3e4, -2.5e4, 1e3);
  Stress b = a;
  PlasticState sa, sb;
  int plastic_steps = 0;
  for (int step = 0; step < 2000; ++step) {
    // Compression with shear drifting one way: the point yields in shear, never at the apex.
    const Strain de = strain(1e-5 * (uniform(random) - 0.3), 1e-5 * (uniform(random) - 0.3),
                             5e-5 * (uniform(random) + 0.5));
    with.update(a, sa, de);
    without.update(b, sb, de);
    REQUIRE(sa.separation == 0.0);
    plastic_steps += sa.plastic == 1.0;
  }
  CHECK(plastic_steps > 100);  // the sequence does reach the yield surface
  for (int c = 0; c < 4; ++c) CHECK(a[c] == b[c]);
  CHECK(sa.plastic_shear_strain == sb.plastic_shear_strain);
}

TEST_CASE("separation in 3D: the same gap and the same closing") {
  MohrCoulombParameters p = sand(true);
  const MohrCoulomb<double, 3> model(p);
  MohrCoulomb<double, 3>::stress_type stress;
  stress << -1000.0, -1000.0, -1000.0, 0.0, 0.0, 0.0;
  PlasticState state;
  MohrCoulomb<double, 3>::strain_type de;
  // Isotropic stretch 1e-3 per axis: trial mean -1000 + K 3e-3 = 4000, the gap 4000 / K = 2.4e-3.
  de << 1e-3, 1e-3, 1e-3, 0.0, 0.0, 0.0;
  CHECK(model.update_region(stress, state, de) == MohrCoulombRegion::apex);
  CHECK(state.separation == doctest::Approx(2.4e-3).epsilon(1e-12));
  // Compress 3e-3: 2.4e-3 closes the gap, 0.6e-3 (0.2e-3 per axis) loads: -K 0.6e-3 = -1000.
  de << -1e-3, -1e-3, -1e-3, 0.0, 0.0, 0.0;
  CHECK(model.update_region(stress, state, de) == MohrCoulombRegion::elastic);
  CHECK(state.separation == 0.0);
  for (int c = 0; c < 3; ++c) CHECK(stress[c] == doctest::Approx(-1000.0).epsilon(1e-12));
}

TEST_CASE("separation needs a cohesionless packing") {
  MohrCoulombParameters p = sand(true);
  p.cohesion = 5e3;
  cosmpm::material::testing::expect_error([&] { (void)MohrCoulomb<double>(p); },
                                          {"separation", "cohesion = 5000", "valid: 0"});
}
