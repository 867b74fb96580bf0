// Whether this machine's cores scale at the moment: a plain loop with no shared writes, run on
// one and on two threads beside the step benchmarks. On this VM the host sometimes places both
// vCPUs on the two hardware threads of one core (docs/performance.md, "Deterministic
// threads"); a two-thread step figure means something about our code only when this loop
// scales at the same time. Each item is an independent chain of 256 multiply-adds on 16,800
// values (the step benchmarks' particle count): bound by arithmetic, not memory, and about as
// long on one thread as a step (0.3 ms here), so the fork and join weigh as much as in a step.
//   build/release/benchmarks/cosmpm_bench_host --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t item_count = 16800;
constexpr int chain_length = 256;

void plain_loop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> values(item_count, 1.0);
  for (auto _ : state) {
    const auto count = static_cast<long>(values.size());
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
    for (long i = 0; i < count; ++i) {
      double x = values[static_cast<std::size_t>(i)];
      // Contracts towards 1, so the values stay finite however many iterations run.
      for (int k = 0; k < chain_length; ++k) x = 0.5 * x + 0.5;
      values[static_cast<std::size_t>(i)] = x;
    }
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(item_count));
  state.counters["threads"] = threads;
}

}  // namespace

BENCHMARK(plain_loop)->Name("host/plain_loop")->Arg(1)->Arg(2)->UseRealTime();
