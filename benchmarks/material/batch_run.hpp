#pragma once
// The timed loop of the material benchmarks: each iteration copies the old stresses into the
// working array and updates them in place, the memory traffic of the engine's stress-update
// stage; the counter ns_per_call is the time per point.
#include <benchmark/benchmark.h>

#include <cstddef>

namespace cosmpm::material::benchmarks {

// `batch` holds the arrays old, work, state and increment of its points. batched: the copies
// first, then one model.update_batch call over the whole batch.
template <bool batched = false, class Model, class Batch>
void run(benchmark::State& bench, const Model& model, Batch& batch) {
  // The array pointers are read once: the loop's stores would otherwise make the compiler
  // reload them through the batch for every point.
  const auto* const old = batch.old.data();
  auto* const work = batch.work.data();
  auto* const state = batch.state.data();
  const auto* const increment = batch.increment.data();
  const std::size_t count = batch.old.size();
  for (auto _ : bench) {
    if constexpr (batched) {
      for (std::size_t i = 0; i < count; ++i) work[i] = old[i];
      model.update_batch(batch.work, batch.state, batch.increment);
    } else {
      for (std::size_t i = 0; i < count; ++i) {
        work[i] = old[i];
        model.update(work[i], state[i], increment[i]);
      }
    }
    benchmark::DoNotOptimize(work);
    benchmark::ClobberMemory();
  }
  bench.counters["ns_per_call"] =
      benchmark::Counter(double(bench.iterations()) * double(count),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace cosmpm::material::benchmarks
