// ns per call of the 3D constitutive kernels (Dim = 3, six components) over 4096 trial states
// stored as the engine would store them, the paper's corn parameters; the same scheme as
// material.bench.cpp (copy the old stress, update in place). Run:
//   build/release/benchmarks/cosmpm_bench_material --benchmark_filter=3D
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "batch_run.hpp"
#include "cosmpm/material.hpp"

namespace {

using namespace cosmpm::material;
using Vec6 = SymmetricTensor<3, double>;
using cosmpm::material::benchmarks::run;

constexpr std::size_t kCount = 4096;
constexpr double kE = 2.76e6, kNu = 0.2, kPhi = 26.0, kPsi = 2.0;  // corn, Table 1

enum class Mix { mixed, elastic, plane, compression_edge, extension_edge, apex };

struct Batch3D {
  std::vector<Vec6> old, work, increment;
  std::vector<PlasticState> state;
  double plastic_fraction = 0;
};

// Old stresses of a few kPa compression (K0 in [0.3, 1]) with shears of a tenth of it, in a
// random frame; increments of up to 4e-4 strain (the plane-strain benchmark's, in all six
// components); `mix` selects the Mohr-Coulomb region of the trial by rejection. Timed as the
// plane-strain kernels are (batch_run.hpp).
Batch3D batch_3d(Mix mix) {
  const MohrCoulomb<double, 3> mc(kE, kNu, kPhi, kPsi);
  std::mt19937_64 rng(2014);
  std::uniform_real_distribution<double> depth_stress(-6e3, -0.5e3), k0(0.3, 1.0), unit(-1.0, 1.0);
  Batch3D batch;
  int plastic = 0;
  while (batch.old.size() < kCount) {
    const double vertical = depth_stress(rng), k = k0(rng);
    const Eigen::Matrix3d r = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng))
                                  .normalized()
                                  .toRotationMatrix();
    Eigen::Matrix3d s = Eigen::Vector3d(k * vertical, vertical, k * vertical).asDiagonal();
    s(0, 1) = s(1, 0) = 0.1 * vertical * unit(rng);
    const Vec6 old = from_tensor<3>(Eigen::Matrix3d(r * s * r.transpose()));
    Vec6 de;
    for (int c = 0; c < 6; ++c) de[c] = 4e-4 * unit(rng);
    if (mix == Mix::apex) de.head<3>().array() += 3e-3;  // pulled apart: all-round tension
    Vec6 trial = old;
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
  batch.work = batch.old;
  batch.state.assign(kCount, PlasticState{});
  batch.plastic_fraction = double(plastic) / double(kCount);
  return batch;
}

const char* const kMixNames[] = {"mixed",          "elastic", "plane", "compression_edge",
                                 "extension_edge", "apex"};

void BM_3D_LinearElastic(benchmark::State& bench) {
  static auto batch = batch_3d(Mix::mixed);
  struct {
    std::vector<Vec6>& old;
    std::vector<Vec6>& work;
    std::vector<Vec6>& increment;
    std::vector<NoState> state;
  } view{batch.old, batch.work, batch.increment, std::vector<NoState>(kCount)};
  run(bench, LinearElastic<double, 3>(kE, kNu), view);
}

void BM_3D_MohrCoulomb(benchmark::State& bench) {
  const auto index = static_cast<std::size_t>(bench.range(0));
  auto batch = batch_3d(static_cast<Mix>(index));
  bench.SetLabel(std::string(kMixNames[index]) + ", plastic fraction " +
                 std::to_string(batch.plastic_fraction));
  run(bench, MohrCoulomb<double, 3>(kE, kNu, kPhi, kPsi), batch);
}

void BM_3D_DruckerPrager(benchmark::State& bench) {
  auto batch = batch_3d(Mix::mixed);
  run(bench, DruckerPrager<double, 3>(kE, kNu, kPhi, kPsi), batch);
}

}  // namespace

BENCHMARK(BM_3D_LinearElastic);
BENCHMARK(BM_3D_MohrCoulomb)->DenseRange(0, 5);
BENCHMARK(BM_3D_DruckerPrager);
