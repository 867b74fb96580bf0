#pragma once
// Mohr-Coulomb states for the batch tests (tests/material/mohr_coulomb_batch.test.cpp) and the
// host-width pack tests (tests/native): every return region, separated points, non-finite
// increments.
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"

namespace mohr_coulomb_points {

using cosmpm::material::PlasticState;
using Stress = cosmpm::material::MohrCoulomb<double>::stress_type;
using Strain = cosmpm::material::MohrCoulomb<double>::strain_type;

struct Points {
  std::vector<Stress> stress;
  std::vector<PlasticState> state;
  std::vector<Strain> increment;
};

// Old stresses around -20 kPa with deviators up to the yield surface and beyond, increments of
// 1e-5 to 1e-2 (elastic to far past the apex), every 7th point with a gap of either sign (only
// a positive one is a separated point), plastic shear strains on both sides of the dilatancy
// cut-off of the variant that has one (0.05), and every 97th increment not finite.
inline Points random_points(std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> size_class(0, 3);
  Points points;
  for (std::size_t i = 0; i < count; ++i) {
    const double mean = -2e4 * std::abs(normal(rng));
    Stress s(mean + 5e3 * normal(rng), mean + 5e3 * normal(rng), mean + 5e3 * normal(rng),
             5e3 * normal(rng));
    const double size = std::pow(10.0, -5 + size_class(rng));
    Strain de(size * normal(rng), size * normal(rng), size * normal(rng), size * normal(rng));
    if (i % 97 == 3)
      de[i % 4] = i % 2 ? std::numeric_limits<double>::quiet_NaN()
                        : std::numeric_limits<double>::infinity();
    PlasticState st;
    st.plastic_shear_strain = 0.1 * std::abs(normal(rng));
    st.plastic = i % 2 ? 1.0 : 0.0;  // stale flags, overwritten by both paths
    st.separation = i % 7 == 0 ? 1e-2 * normal(rng) : 0.0;
    points.stress.push_back(s);
    points.state.push_back(st);
    points.increment.push_back(de);
  }
  return points;
}

inline cosmpm::material::MohrCoulombParameters corn() {
  // The flat blade's corn (docs/validation.md): E = 2.76 MPa, nu = 0.2, phi = 26, psi = 2 deg.
  return {.youngs_modulus = 2.76e6,
          .poisson_ratio = 0.2,
          .friction_angle_deg = 26,
          .dilatancy_angle_deg = 2};
}

}  // namespace mohr_coulomb_points
