// continuum::Classical at Dim = 3: the strain increment and the Jaumann rotation of the stress
// against the matrix formulas they implement, the plane-strain continuum recovered from the 3D
// one, and rotation objectivity over a finite rigid rotation.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace {
using namespace cosmpm;
using Elastic2 = material::LinearElastic<double>;
using Elastic3 = material::LinearElastic<double, 3>;
using Classical2 = continuum::Classical<Elastic2>;
using Classical3 = continuum::Classical<Elastic3>;
using Stress3 = Elastic3::stress_type;

static_assert(Classical3::dim == 3);
static_assert(Classical2::dim == 2);

Mat<3> random_matrix(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<3> m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = u(rng);
  }
  return m;
}
Stress3 random_stress(std::mt19937_64& rng) {
  const Mat<3> a = random_matrix(rng, 1e4);
  return material::from_tensor<3, double>(Eigen::Matrix3d(a + a.transpose()));
}
}  // namespace

TEST_CASE("Classical<3>: increment = sym(L) dt and rotation = sigma + W sigma - sigma W") {
  std::mt19937_64 rng(7);
  const double dt = 1e-3;
  for (int trial = 0; trial < 200; ++trial) {
    const Mat<3> L = random_matrix(rng, 50.0);
    const Stress3 old = random_stress(rng);
    Stress3 stress = old;
    continuum::ParticleRates<3, 0> rates;
    rates.velocity_gradient = L;
    const Stress3 increment = Classical3::rotate_and_increment(rates, dt, stress);
    // References from the matrices: D = (L + L^T) dt / 2, W = (L - L^T) dt / 2.
    const Eigen::Matrix3d D = 0.5 * (L + L.transpose()) * dt;
    const Eigen::Matrix3d W = 0.5 * (L - L.transpose()) * dt;
    const Eigen::Matrix3d S = material::to_tensor<3, double>(old);
    const Stress3 expected_increment = material::from_tensor<3, double>(D);
    const Stress3 expected_stress = material::from_tensor<3, double>(S + W * S - S * W);
    // Round-off: a few ulps of |sigma| (1e4) times |W| (~0.05), and of |D|.
    CHECK((increment - expected_increment).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((stress - expected_stress).cwiseAbs().maxCoeff() < 1e-10);
  }
}

TEST_CASE("Classical<3>: an in-plane velocity gradient gives the plane-strain update") {
  // L in the xy plane, stress with xz = yz = 0: the 3D update's xx, yy, zz, xy equal the 2D
  // one's and xz, yz stay zero (the 3D formula reduces to rotate_by_spin term by term).
  std::mt19937_64 rng(11);
  const double dt = 2e-4;
  for (int trial = 0; trial < 100; ++trial) {
    Mat<3> L3 = random_matrix(rng, 20.0);
    L3.row(2).setZero();
    L3.col(2).setZero();
    Stress3 s3 = random_stress(rng);
    s3[4] = s3[5] = 0.0;
    SymTensor2D<double> s2(s3[0], s3[1], s3[2], s3[3]);
    continuum::ParticleRates<3, 0> r3;
    r3.velocity_gradient = L3;
    continuum::ParticleRates<2, 0> r2;
    r2.velocity_gradient = L3.topLeftCorner<2, 2>();
    const auto e3 = Classical3::rotate_and_increment(r3, dt, s3);
    const auto e2 = Classical2::rotate_and_increment(r2, dt, s2);
    for (int c = 0; c < 4; ++c) {
      CHECK(s3[c] == doctest::Approx(s2[c]).epsilon(1e-14));
      CHECK(e3[c] == doctest::Approx(e2[c]).epsilon(1e-14));
    }
    CHECK(s3[4] == 0.0);
    CHECK(s3[5] == 0.0);
    CHECK(e3[4] == 0.0);
    CHECK(e3[5] == 0.0);
  }
}

TEST_CASE("Classical<3>: a rigid rotation rotates the stress and keeps its invariants") {
  // A spin Omega about the axis n for a time T: the Jaumann (forward Euler) update converges
  // to R sigma R^T, R = exp(Omega T [n]x), at first order in dt: each step is exact to
  // O((Omega dt)^2), so 4000 steps over a quarter turn drift by ~ N (Omega dt)^2 = 6e-4 of
  // |sigma| (measured 9.2e-4). The tolerance 2e-3 would fail for a wrong sign or a missing
  // term (an error of order |sigma|).
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0;
  const double omega = 3.0, turn = 0.5 * pi / omega;
  const int steps = 4000;
  const double dt = turn / steps;
  Eigen::Matrix3d skew;
  skew << 0, -n[2], n[1], n[2], 0, -n[0], -n[1], n[0], 0;
  // v = Omega n x x: L = Omega [n]x.
  continuum::ParticleRates<3, 0> rates;
  rates.velocity_gradient = omega * skew;
  std::mt19937_64 rng(3);
  const Stress3 initial = random_stress(rng);
  Stress3 stress = initial;
  for (int i = 0; i < steps; ++i) {
    const auto increment = Classical3::rotate_and_increment(rates, dt, stress);
    CHECK(increment.cwiseAbs().maxCoeff() < 1e-15);  // no strain in a rigid rotation
  }
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(omega * turn, n).toRotationMatrix();  // Rodrigues, independent
  const Eigen::Matrix3d S0 = material::to_tensor<3, double>(initial);
  const Eigen::Matrix3d expected = R * S0 * R.transpose();
  const Eigen::Matrix3d got = material::to_tensor<3, double>(stress);
  const double size = S0.norm();
  MESSAGE("rigid rotation: relative difference " << (got - expected).norm() / size);
  CHECK((got - expected).norm() / size < 2e-3);
  // The trace is kept exactly by each step (tr(W S - S W) = 0), up to round-off.
  CHECK(std::abs(got.trace() - S0.trace()) / size < 1e-12);
}

TEST_CASE("Classical<3>: the packed stress update equals the one-particle update bit for bit") {
  const Elastic3 model(2.76e6, 0.2);
  std::mt19937_64 rng(5);
  const double dt = 1e-4;
  for (int trial = 0; trial < 50; ++trial) {
    const Mat<3> L = random_matrix(rng, 10.0);
    Stress3 stress = random_stress(rng);
    Stress3 strain = random_stress(rng) * 1e-8;
    std::array<double, 6> s_values, e_values;
    for (int c = 0; c < 6; ++c) {
      s_values[c] = stress[c];
      e_values[c] = strain[c];
    }
    std::array<std::array<double, 3>, 3> l_values;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) l_values[i][j] = L(i, j);
    }
    continuum::ParticleRates<3, 0> rates;
    rates.velocity_gradient = L;
    material::NoState state;
    Classical3::update_stress(model, rates, dt, stress, state, strain);
    Classical3::update_stress_values(model, l_values, dt, s_values, e_values);
    for (int c = 0; c < 6; ++c) {
      CHECK(s_values[c] == stress[c]);
      CHECK(e_values[c] == strain[c]);
    }
  }
}

TEST_CASE("Classical<3>: internal force coefficients are -V sigma as a full 3 x 3 tensor") {
  Stress3 s;
  s << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  const auto b = Classical3::internal_force_coefficients(s, 0.5);
  const Eigen::Matrix3d full = material::to_tensor<3, double>(s);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) CHECK(b[i][j] == -0.5 * full(i, j));
  }
}
