// ns per call of the constitutive kernels over 4096 trial states stored as the engine stores
// them (std::vector<stress_type>, std::vector<state_type>), the paper's corn parameters.
// Each iteration copies the old stress into the working array and updates it in place, the
// memory traffic of the engine's stress-update stage. Run:
//   build/benchmarks/cosmpm_bench_material --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "batch_run.hpp"
#include "cosmpm/material.hpp"

namespace {

using namespace cosmpm::material;
using cosmpm::CosseratTensor2D;
using cosmpm::SymTensor2D;
using cosmpm::material::benchmarks::run;

constexpr std::size_t kCount = 4096;
constexpr double kE = 2.76e6, kNu = 0.2, kPhi = 26.0, kPsi = 2.0;  // corn, Table 1
constexpr double kG = kE / (2 * (1 + kNu));

enum class Mix { mixed, elastic, plane, compression_edge, extension_edge, apex };

// Old stresses of a few kPa compression (K = sigma_xx / sigma_yy in [0.3, 1]) and increments of
// up to 4e-4 strain; `mix` selects states by the Mohr-Coulomb region their trial falls in
// (rejection sampling), or takes them all (mixed; the label gives the plastic fraction).
struct ClassicalBatch {
  std::vector<SymTensor2D<double>> old, work, increment;
  std::vector<PlasticState> state;
  double plastic_fraction = 0;
};

ClassicalBatch classical_batch(Mix mix) {
  const MohrCoulomb<double> mc(kE, kNu, kPhi, kPsi);
  const double bulk = mc.bulk_modulus();
  std::mt19937_64 rng(2014);
  std::uniform_real_distribution<double> depth_stress(-6e3, -0.5e3), k0(0.3, 1.0), unit(-1.0, 1.0);
  ClassicalBatch batch;
  int plastic = 0;
  while (batch.old.size() < kCount) {
    const double vertical = depth_stress(rng);
    const double k = k0(rng);
    const SymTensor2D<double> old(k * vertical, vertical, k * vertical, 0.1 * vertical * unit(rng));
    SymTensor2D<double> de(4e-4 * unit(rng), 4e-4 * unit(rng), 0.0, 4e-4 * unit(rng));
    if (mix == Mix::apex) de.head<3>().array() += 3e-3;  // pulled apart: all-round tension
    // Classify the trial with the model itself (one call, outside the timing).
    SymTensor2D<double> trial = old;
    PlasticState st;
    const MohrCoulombRegion region = mc.update_region(trial, st, de);
    const bool wanted =
        mix == Mix::mixed || (mix == Mix::elastic && region == MohrCoulombRegion::elastic) ||
        (mix == Mix::plane && region == MohrCoulombRegion::plane) ||
        (mix == Mix::compression_edge && region == MohrCoulombRegion::compression_edge) ||
        (mix == Mix::extension_edge && region == MohrCoulombRegion::extension_edge) ||
        (mix == Mix::apex && region == MohrCoulombRegion::apex);
    if (!wanted) continue;
    plastic += region != MohrCoulombRegion::elastic;
    batch.old.push_back(old);
    batch.increment.push_back(de);
  }
  (void)bulk;
  batch.work = batch.old;
  batch.state.assign(kCount, PlasticState{});
  batch.plastic_fraction = double(plastic) / double(kCount);
  return batch;
}

void BM_LinearElastic(benchmark::State& bench) {
  static auto batch = classical_batch(Mix::mixed);
  const LinearElastic<double> model(kE, kNu);
  struct {
    std::vector<SymTensor2D<double>>& old;
    std::vector<SymTensor2D<double>>& work;
    std::vector<SymTensor2D<double>>& increment;
    std::vector<NoState> state;
  } view{batch.old, batch.work, batch.increment, std::vector<NoState>(kCount)};
  run(bench, model, view);
}

// Per point through update(), or (batched) through update_batch, on one mix of regions.
template <bool batched>
void mohr_coulomb(benchmark::State& bench) {
  static const Mix mixes[] = {Mix::mixed,          Mix::elastic, Mix::plane, Mix::compression_edge,
                              Mix::extension_edge, Mix::apex};
  static const char* names[] = {"mixed",          "elastic", "plane", "compression_edge",
                                "extension_edge", "apex"};
  const auto index = static_cast<std::size_t>(bench.range(0));
  auto batch = classical_batch(mixes[index]);
  const MohrCoulomb<double> model(kE, kNu, kPhi, kPsi);
  bench.SetLabel(std::string(names[index]) + ", plastic fraction " +
                 std::to_string(batch.plastic_fraction));
  run<batched>(bench, model, batch);
}

void BM_MohrCoulomb(benchmark::State& bench) {
  mohr_coulomb<false>(bench);
}
void BM_MohrCoulomb_batch(benchmark::State& bench) {
  mohr_coulomb<true>(bench);
}

void BM_DruckerPrager(benchmark::State& bench) {
  auto batch = classical_batch(Mix::mixed);
  const DruckerPrager<double> model(kE, kNu, kPhi, kPsi);
  run(bench, model, batch);
}

struct CosseratBatch {
  std::vector<CosseratTensor2D<double>> old, work, increment;
  std::vector<PlasticState> state;
};

// The classical batch with non-symmetric shear, curvature (|kappa| l up to 1e-4) and couple
// stresses of the same order (m / l ~ a tenth of the stress).
CosseratBatch cosserat_batch() {
  const auto classical = classical_batch(Mix::mixed);
  std::mt19937_64 rng(1991);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double l = 0.01;
  CosseratBatch batch;
  for (std::size_t i = 0; i < kCount; ++i) {
    const auto& s = classical.old[i];
    const auto& e = classical.increment[i];
    CosseratTensor2D<double> old, de;
    old << s[0], s[1], s[2], s[3] * (1 + 0.1 * unit(rng)), s[3] * (1 + 0.1 * unit(rng)),
        0.1 * l * s[1] * unit(rng), 0.1 * l * s[1] * unit(rng);
    de << e[0], e[1], e[2], e[3] + 2e-5 * unit(rng), e[3] + 2e-5 * unit(rng), 1e-4 / l * unit(rng),
        1e-4 / l * unit(rng);
    batch.old.push_back(old);
    batch.increment.push_back(de);
  }
  batch.work = batch.old;
  batch.state.assign(kCount, PlasticState{});
  return batch;
}

void BM_CosseratElastic(benchmark::State& bench) {
  auto batch = cosserat_batch();
  const CosseratElastic<double> model(kE, kNu, 2 * kG, 0.01);
  struct {
    std::vector<CosseratTensor2D<double>>& old;
    std::vector<CosseratTensor2D<double>>& work;
    std::vector<CosseratTensor2D<double>>& increment;
    std::vector<NoState> state;
  } view{batch.old, batch.work, batch.increment, std::vector<NoState>(kCount)};
  run(bench, model, view);
}

// mixed: the Cosserat batch as it is; elastic / plastic: only its states whose trial is
// elastic / plastic for the model, cycled to fill the batch. The label gives the mix.
CosseratBatch cosserat_drucker_prager_batch(const CosseratDruckerPrager<double>& model,
                                            std::size_t index, std::string& label) {
  static const char* names[] = {"mixed", "elastic", "plastic"};
  const auto all = cosserat_batch();
  CosseratBatch batch;
  for (std::size_t i = 0; i < kCount; ++i) {
    auto s = all.old[i];
    PlasticState st;
    model.update(s, st, all.increment[i]);
    if (index == 0 || (index == 1) == (st.plastic == 0.0)) {
      batch.old.push_back(all.old[i]);
      batch.increment.push_back(all.increment[i]);
    }
  }
  const std::size_t selected = batch.old.size();
  int plastic = 0;
  for (std::size_t i = 0; i < kCount; ++i) {
    if (i >= selected) {
      batch.old.push_back(batch.old[i - selected]);
      batch.increment.push_back(batch.increment[i - selected]);
    }
    auto s = batch.old[i];
    PlasticState st;
    model.update(s, st, batch.increment[i]);
    plastic += st.plastic == 1.0;
  }
  batch.work = batch.old;
  batch.state.assign(kCount, PlasticState{});
  label = std::string(names[index]) + ", plastic fraction " +
          std::to_string(double(plastic) / double(kCount));
  return batch;
}

// Per point through update(), or (batched) through update_batch.
template <bool batched>
void cosserat_drucker_prager(benchmark::State& bench) {
  const CosseratDruckerPrager<double> model(kE, kNu, 2 * kG, 0.01, kPhi, kPsi);
  std::string label;
  auto batch =
      cosserat_drucker_prager_batch(model, static_cast<std::size_t>(bench.range(0)), label);
  bench.SetLabel(label);
  run<batched>(bench, model, batch);
}

void BM_CosseratDruckerPrager(benchmark::State& bench) {
  cosserat_drucker_prager<false>(bench);
}
void BM_CosseratDruckerPrager_batch(benchmark::State& bench) {
  cosserat_drucker_prager<true>(bench);
}

}  // namespace

BENCHMARK(BM_LinearElastic);
BENCHMARK(BM_MohrCoulomb)->DenseRange(0, 5);
BENCHMARK(BM_MohrCoulomb_batch)->DenseRange(0, 5);
BENCHMARK(BM_DruckerPrager);
BENCHMARK(BM_CosseratElastic);
BENCHMARK(BM_CosseratDruckerPrager)->DenseRange(0, 2);
BENCHMARK(BM_CosseratDruckerPrager_batch)->DenseRange(0, 2);
