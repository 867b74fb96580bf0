// The paper's shear-strain intensity J' on strains whose value is known by hand, and its
// invariance under a rotation of the plane.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "cosmpm/analysis/shear_strain_intensity.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;

TEST_CASE("J' of pure shear, uniaxial and equal biaxial strain") {
  // Pure shear e_xy = g: ((0)^2 + 0 + 0) / 6 + g^2 = g^2.
  CHECK(analysis::shear_strain_intensity(SymTensor2D<>(0, 0, 0, 0.02)) == doctest::Approx(4e-4));
  // Uniaxial e_xx = e: (e^2 + 0 + e^2) / 6 = e^2 / 3, either axis.
  CHECK(analysis::shear_strain_intensity(SymTensor2D<>(0.03, 0, 0, 0)) == doctest::Approx(3e-4));
  CHECK(analysis::shear_strain_intensity(SymTensor2D<>(0, 0.03, 0, 0)) == doctest::Approx(3e-4));
  // Equal biaxial e_xx = e_yy = e (the zz term of the formula is zero): (0 + 2 e^2) / 6.
  CHECK(analysis::shear_strain_intensity(SymTensor2D<>(0.03, 0.03, 0, 0)) == doctest::Approx(3e-4));
  // e_zz does not enter the paper's formula.
  CHECK(analysis::shear_strain_intensity(SymTensor2D<>(0, 0, 0.5, 0)) == 0.0);
}

TEST_CASE("J' is invariant under a rotation of the plane") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int n = 0; n < 50; ++n) {
    Mat<2> e;
    e << u(rng), u(rng), 0.0, u(rng);
    e(1, 0) = e(0, 1);
    const double theta = 10.0 * u(rng) * pi;
    Mat<2> q;
    q << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
    const Mat<2> rotated = q * e * q.transpose();
    const double before =
        analysis::shear_strain_intensity(SymTensor2D<>(e(0, 0), e(1, 1), 0, e(0, 1)));
    const double after = analysis::shear_strain_intensity(
        SymTensor2D<>(rotated(0, 0), rotated(1, 1), 0, rotated(0, 1)));
    CHECK(after == doctest::Approx(before).epsilon(1e-12));
  }
}

TEST_CASE("J' of a simulation's particles reads their accumulated strain") {
  using Soil = material::MohrCoulomb<>;
  using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {4, 4});
  Sim sim(grid, Soil(1e6, 0.3, 30, 0));
  sim.add_particles({Vec<2>(0.3, 0.3), Vec<2>(0.6, 0.6)}, 0.01, 1000.0, Vec<2>(0.25, 0.25));
  auto& strain = sim.particles().get<particles::field::Strain<Soil>>();
  strain[0] = SymTensor2D<>(0, 0, 0, 0.1);
  strain[1] = SymTensor2D<>(0.03, 0, 0, 0);
  const std::vector<double> j = analysis::shear_strain_intensity(sim);
  CHECK(j[0] == doctest::Approx(0.01));
  CHECK(j[1] == doctest::Approx(3e-4));
}

}  // namespace
