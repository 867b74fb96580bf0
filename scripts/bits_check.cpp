// Bits of the step schemes, for comparing two trees: checksums of every particle's position,
// velocity and stress after 300 steps of the benchmark's soil block, for each scheme the step
// benchmarks time, with and without the fused schemes' records dropped at step 150, on the
// threads given as the argument (default 1). Built and run against each tree by
// scripts/bits_check.sh: a change meant to give the same results must leave every line alike,
// and the lines must not depend on the thread count.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"
#include "step_support.hpp"

namespace {

using namespace cosmpm;

// FNV-1a over the doubles' bits.
struct Checksum {
  unsigned long long value = 1469598103934665603ull;
  void add(const double* data, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
      unsigned long long bits;
      std::memcpy(&bits, data + i, sizeof bits);
      value = (value ^ bits) * 1099511628211ull;
    }
  }
};

template <class Sim>
unsigned long long checksum_of(const Sim& sim) {
  const auto& particles = sim.particles();
  const auto& x = particles.template get<particles::field::Position<2>>();
  const auto& v = particles.template get<particles::field::Velocity<2>>();
  const auto& stress = particles.template get<particles::field::Stress<typename Sim::model_type>>();
  Checksum sum;
  sum.add(x.data()->data(), 2 * x.size());
  sum.add(v.data()->data(), 2 * v.size());
  sum.add(stress.data()->data(), stress.size() * static_cast<std::size_t>(stress[0].size()));
  return sum.value;
}

template <class Kernel, class Continuum, class Integrator>
using Sim = Simulation<2, Kernel, Continuum, contact::SingleField, Integrator>;

// drop: the particles taken for writing at step 150, which drops a fused scheme's records.
template <class Sim>
void run(const char* name, bool drop, int threads) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.2, 0.5), {120, 50});
  auto sim = benchmarks::soil_block<Sim>(grid, Vec<2>(1.2, 0.35), threads);
  const double dt = sim.time_step();
  for (int step = 0; step < 300; ++step) {
    if (drop && step == 150) (void)sim.particles();
    sim.step(dt);
  }
  std::printf("%-14s drop=%d %016llx\n", name, drop ? 1 : 0, checksum_of(sim));
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  using Elastic = continuum::Classical<material::LinearElastic<>>;
  using MohrCoulomb = continuum::Classical<material::MohrCoulomb<>>;
  using Cosserat = continuum::Cosserat<material::CosseratDruckerPrager<>>;
  for (const bool drop : {false, true}) {
    run<Sim<shape::Linear, Elastic, integrator::FusedUSL>>("fused-usl", drop, threads);
    run<Sim<shape::QuadraticBSpline, Elastic, integrator::FusedUSL>>("fused-usl-quad", drop,
                                                                     threads);
    run<Sim<shape::Linear, MohrCoulomb, integrator::FusedMUSL>>("fused-musl-mc", drop, threads);
    run<Sim<shape::Linear, Cosserat, integrator::FusedMUSL>>("fused-musl-co", drop, threads);
    run<Sim<shape::Linear, Elastic, integrator::USL>>("usl", drop, threads);
    run<Sim<shape::Linear, MohrCoulomb, integrator::MUSL>>("musl-mc", drop, threads);
    run<Sim<shape::Linear, Cosserat, integrator::MUSL>>("musl-co", drop, threads);
  }
}
