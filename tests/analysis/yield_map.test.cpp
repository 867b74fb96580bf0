// Yield-point maps: stresses on, inside and at the apex of the Mohr-Coulomb surface, and the
// plastic flag of the last update.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cosmpm/analysis/yield_map.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Soil = material::MohrCoulomb<>;

// A plane-strain stress with principal values s1 (xx axis rotated by theta) and s3, s_zz.
SymTensor2D<> rotated(double s1, double s3, double zz, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return SymTensor2D<>(s1 * c * c + s3 * s * s, s1 * s * s + s3 * c * c, zz, (s1 - s3) * s * c);
}

TEST_CASE("yield points of Mohr-Coulomb stresses: on the surface, inside, at the apex") {
  const Soil cohesionless(1e6, 0.3, 30, 0);
  // phi = 30 deg: k = (1 + sin phi) / (1 - sin phi) = 3; f = 0 when s3 = 3 s1 (tension
  // positive, s3 the most compressive), whatever the orientation.
  const std::vector<SymTensor2D<>> stress{
      rotated(-1000, -3000, -2000, 0.0),      // on the surface
      rotated(-1000, -3000, -2000, 0.7),      // on the surface, rotated
      rotated(-1100, -3000, -2000, 0.3),      // inside: s3 / s1 = 2.7 < 3
      SymTensor2D<>(-2000, -2000, -2000, 0),  // hydrostatic: inside
      SymTensor2D<>::Zero(),                  // stress free: the apex of a cohesionless cone
  };
  CHECK(analysis::yield_points(cohesionless, std::span<const SymTensor2D<>>(stress)) ==
        std::vector<std::uint8_t>{1, 1, 0, 0, 1});
  // With cohesion the apex moves into tension: a stress-free point is inside.
  const Soil cohesive(1e6, 0.3, 30, 0, 1000.0);
  const std::vector<SymTensor2D<>> free{SymTensor2D<>::Zero()};
  CHECK(analysis::yield_points(cohesive, std::span<const SymTensor2D<>>(free)) ==
        std::vector<std::uint8_t>{0});
  CHECK_THROWS_AS(analysis::yield_points(cohesive, std::span<const SymTensor2D<>>(free), -1.0),
                  Error);
}

TEST_CASE("yield and plastic points of a simulation: the stress map and the last update's flag") {
  using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {4, 4});
  const Soil soil(1e6, 0.3, 30, 0);
  Sim sim(grid, soil);
  sim.add_particles({Vec<2>(0.3, 0.3), Vec<2>(0.6, 0.6)}, 0.01, 1000.0, Vec<2>(0.25, 0.25));
  auto& stress = sim.particles().get<particles::field::Stress<Soil>>();
  auto& state = sim.particles().get<particles::field::MaterialState<Soil>>();
  // Particle 0 yields under a shear increment from a surface state; particle 1 stays elastic.
  stress[0] = rotated(-1000, -3000, -2000, 0.0);
  stress[1] = SymTensor2D<>(-2000, -2000, -2000, 0);
  soil.update(stress[0], state[0], SymTensor2D<>(0, 0, 0, 1e-4));
  soil.update(stress[1], state[1], SymTensor2D<>(0, 0, 0, 1e-6));
  CHECK(analysis::plastic_points(sim) == std::vector<std::uint8_t>{1, 0});
  CHECK(analysis::yield_points(sim) == std::vector<std::uint8_t>{1, 0});
}

}  // namespace
