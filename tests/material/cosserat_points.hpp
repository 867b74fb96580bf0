#pragma once
// Cosserat Drucker-Prager states like the kernel benchmark's, shared by the batch tests
// (tests/material/cosserat_batch.test.cpp) and the host-width pack tests (tests/native).
#include <array>
#include <cstddef>
#include <random>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"

namespace cosserat_points {

using cosmpm::CosseratTensor2D;
using cosmpm::material::PlasticState;

// The paper's Cosserat corn (Table 1), as in the benchmark.
inline constexpr double kE = 2.76e6;
inline constexpr double kNu = 0.2;
inline constexpr double kG = kE / (2 * (1 + kNu));
inline constexpr double kL = 0.01;
inline constexpr double kPhi = 26.0;
inline constexpr double kPsi = 2.0;
inline constexpr double kBulk = kE / (3 * (1 - 2 * kNu));

struct Points {
  std::vector<CosseratTensor2D<double>> stress, increment;
  std::vector<PlasticState> state;
};

// States like the benchmark's (benchmarks/material/material.bench.cpp): old stresses of a few kPa
// compression, K0 in [0.3, 1], shear and couple stresses, increments up to 4e-4 and curvatures
// up to 1e-4 / l; about half of them plastic. A fraction `tension` goes beyond the apex pressure
// `model_apex`: half pulled apart by 3e-3 volumetric strain (to the apex), half just beyond it
// with a large shear (to the cone).
// The states start with some plastic strain and a stale plastic flag, which update must add to
// and overwrite.
inline Points benchmark_like(std::size_t count, unsigned seed, double tension = 0.0,
                             double model_apex = 0.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> depth_stress(-6e3, -0.5e3), k0(0.3, 1.0), unit(-1, 1),
      uniform(0, 1);
  Points p;
  for (std::size_t i = 0; i < count; ++i) {
    const double vertical = depth_stress(rng), k = k0(rng), shear = 0.1 * vertical * unit(rng);
    CosseratTensor2D<double> s, de;
    s << k * vertical, vertical, k * vertical, shear * (1 + 0.1 * unit(rng)),
        shear * (1 + 0.1 * unit(rng)), 0.1 * kL * vertical * unit(rng),
        0.1 * kL * vertical * unit(rng);
    const double exy = 4e-4 * unit(rng);
    de << 4e-4 * unit(rng), 4e-4 * unit(rng), 0.0, exy + 2e-5 * unit(rng), exy + 2e-5 * unit(rng),
        1e-4 / kL * unit(rng), 1e-4 / kL * unit(rng);
    if (uniform(rng) < tension) {
      if (uniform(rng) < 0.5) {
        de.head<3>().array() += 3e-3;  // pulled apart: at the apex
      } else {
        // A trial p just above the apex pressure (up to 200 Pa) and a large shear: the
        // return stays on the cone beyond the apex pressure.
        const double p_old = (s[0] + s[1] + s[2]) / 3;
        const double p_trial = model_apex + 200 * uniform(rng);
        de.head<3>().array() += (p_trial - p_old) / (3 * kBulk) - (de[0] + de[1] + de[2]) / 3;
        de[3] += 6e-3 * unit(rng);
        de[4] = de[3];
      }
    }
    p.stress.push_back(s);
    p.increment.push_back(de);
    p.state.push_back({1e-3 * uniform(rng), uniform(rng) < 0.5 ? 1.0 : 0.0});
  }
  return p;
}

// Models with two distinct mode rates (the paper's corn, Gc = 2 G), three (Gc = 20 G: a slow
// series start, so some lanes have not stopped after the batch's two steps) and one.
inline std::array<cosmpm::material::CosseratDruckerPrager<double>, 3> models_by_rates() {
  return {{{kE, kNu, 2 * kG, kL, kPhi, kPsi},
           {kE, kNu, 20 * kG, kL, kPhi, kPsi, 300.0, {0.375, 0.125, 1.0}},
           {kE, kNu, 2 * kG, kL, kPhi, kPsi, 300.0, {0.375, 0.125, 0.5}}}};
}

}  // namespace cosserat_points
