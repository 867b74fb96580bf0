// Whether this machine's cores scale at the moment: a plain loop with no shared writes, run on
// one and on two threads beside the step benchmarks. On this VM the host sometimes places both
// vCPUs on the two hardware threads of one core (docs/performance.md, "Deterministic
// threads"); a two-thread step figure means something about our code only when this loop
// scales at the same time. Each item is an independent chain of 256 multiply-adds on 16,800
// values (the step benchmarks' particle count): bound by arithmetic, not memory, and about as
// long on one thread as a step (0.3 ms here), so the fork and join weigh as much as in a step.
//
// That loop is bound by the latency of its chains: one chain per vector register in flight
// leaves most of a core's arithmetic units idle, so two hardware threads of ONE core run it
// nearly twice as fast as one, and it scales whether or not the vCPUs share a core. Our steps
// are bound by throughput (many independent operations per particle), so
// host/throughput_loop runs the same arithmetic with 32 items per chain step (eight
// independent vector registers with AVX, enough to keep both multiply-add units busy): it
// scales only on two separate cores. Read the two together: both near 2 = two cores; the
// plain loop near 2 and this one near 1 = two threads of one core, where no throughput-bound
// step can scale.
//
// Neither loop moves data between the vCPUs, and on this VM that is what decided whether the
// step scaled: host/cache_halves updates two arrays of 1 MB (about a third of the step's
// particle data), each thread always its own half; host/cache_halves_swapped gives each half
// to the other thread every pass, so every line read was last written on the other vCPU (what
// a step did when its passes handed particles to threads as they came free). docs/
// performance.md ("Two threads and the host") has the figures; scripts/bench_scaling.py runs
// these controls beside the steps.
//   build/release/benchmarks/cosmpm_bench_host --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstddef>
#include <vector>

#include "cosmpm/core/parallel.hpp"

namespace {

constexpr std::size_t item_count = 16800;
constexpr int chain_length = 256;

void plain_loop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> values(item_count, 1.0);
  for (auto _ : state) {
    const auto count = static_cast<cosmpm::Index>(values.size());
    cosmpm::parallel_for(threads, count, [&](cosmpm::Index i) {
      double x = values[static_cast<std::size_t>(i)];
      // Contracts towards 1, so the values stay finite however many iterations run.
      for (int k = 0; k < chain_length; ++k) x = 0.5 * x + 0.5;
      values[static_cast<std::size_t>(i)] = x;
    });
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(item_count));
  state.counters["threads"] = threads;
}

// The same chains, 32 items advanced together in each step of the chain.
void throughput_loop(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  constexpr long block = 32;
  static_assert(item_count % block == 0);
  std::vector<double> values(item_count, 1.0);
  for (auto _ : state) {
    const auto blocks = static_cast<cosmpm::Index>(values.size()) / block;
    // The region's work is the items, not the blocks: it runs on a team as the plain loop does.
    cosmpm::parallel_region(threads, static_cast<long>(values.size()), [&] {
      const cosmpm::Share share = cosmpm::static_share(blocks);
      for (cosmpm::Index b = share.first; b < share.last; ++b) {
        double x[block];
        double* const v = values.data() + b * block;
        for (long j = 0; j < block; ++j) x[j] = v[j];
        for (int k = 0; k < chain_length; ++k) {
          for (long j = 0; j < block; ++j) x[j] = 0.5 * x[j] + 0.5;
        }
        for (long j = 0; j < block; ++j) v[j] = x[j];
      }
    });
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(item_count));
  state.counters["threads"] = threads;
}

// Two arrays of cache_bytes each, a[i] = a[i] / 2 + b[i] then b[i] = b[i] / 2 + a[i] over each
// thread's half; `swapped`: the halves change threads every pass.
void cache_halves(benchmark::State& state, bool swapped) {
  constexpr std::size_t cache_bytes = std::size_t{1} << 20;
  const int threads = static_cast<int>(state.range(0));
  const long n = static_cast<long>(cache_bytes / sizeof(double));
  std::vector<double> a(static_cast<std::size_t>(n), 1.0), b(static_cast<std::size_t>(n), 2.0);
  long pass = 0;
  for (auto _ : state) {
    cosmpm::parallel_region(threads, n, [&] {
      const int thread = cosmpm::current_thread();
      const int team = cosmpm::current_team_size();
      const long half = swapped ? (thread + pass) % team : thread;
      const long first = n * half / team, last = n * (half + 1) / team;
      double* const x = a.data();
      double* const y = b.data();
      for (long i = first; i < last; ++i) x[i] = 0.5 * x[i] + y[i];
      for (long i = first; i < last; ++i) y[i] = 0.5 * y[i] + x[i];
    });
    ++pass;
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["threads"] = threads;
}

// What starting and ending a parallel region costs, against handing work to a thread that is
// already running. A step opens four to eight regions on two threads (core/parallel.hpp runs
// none on one); libgomp ends each with a futex wake, and releases a team of two with another,
// made whether or not a thread sleeps, and a system call costs about 1 us on this VM
// (docs/performance.md, "What a parallel region costs"). fork_join/omp_region: an empty `omp
// parallel` of `threads`, its time per region; fork_join/spin_handover: inside one region,
// thread 0 hands a token to thread 1 and waits for it back, one atomic each way, its items
// round trips: the floor a team that stayed between the passes would pay per pass.
void omp_region(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  long entered = 0;
  for (auto _ : state) {
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads) reduction(+ : entered)
#endif
    { entered += 1; }
  }
  benchmark::DoNotOptimize(entered);
  state.SetItemsProcessed(state.iterations());
  state.counters["threads"] = threads;
}

// fork_join/team_region: an empty region of the engine's own team (core/thread_team.hpp), as the
// stages open theirs; fork_join/team_barrier: a barrier inside one, per barrier.
void team_region(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::atomic<long> entered{0};
  for (auto _ : state) {
    cosmpm::parallel_region(threads, cosmpm::parallel_threshold,
                            [&] { entered.fetch_add(1, std::memory_order_relaxed); });
  }
  benchmark::DoNotOptimize(entered.load());
  state.SetItemsProcessed(state.iterations());
  state.counters["threads"] = threads;
}

void team_barrier(benchmark::State& state) {
  constexpr long barriers = 10000;  // per benchmark iteration
  for (auto _ : state) {
    cosmpm::parallel_region(2, cosmpm::parallel_threshold, [&] {
      for (long k = 0; k < barriers; ++k) cosmpm::team_barrier();
    });
  }
  state.SetItemsProcessed(state.iterations() * barriers);
}

void spin_handover(benchmark::State& state) {
  constexpr long handovers = 100000;  // per benchmark iteration
  std::atomic<long> token{0};
  for (auto _ : state) {
    token.store(0, std::memory_order_relaxed);
    cosmpm::parallel_region(2, cosmpm::parallel_threshold, [&] {
      const int thread = cosmpm::current_thread();
      const int team = cosmpm::current_team_size();
      // Thread 0 moves the token to odd values, thread 1 to even ones; alone, a thread does both.
      for (long k = 0; k < 2 * handovers; ++k) {
        if (team > 1 && (k % 2) != thread) continue;
        while (token.load(std::memory_order_acquire) != k) {
        }
        token.store(k + 1, std::memory_order_release);
      }
    });
  }
  state.SetItemsProcessed(state.iterations() * handovers);
}

}  // namespace

BENCHMARK(omp_region)->Name("fork_join/omp_region")->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(team_region)->Name("fork_join/team_region")->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(team_barrier)->Name("fork_join/team_barrier")->UseRealTime();
BENCHMARK(spin_handover)->Name("fork_join/spin_handover")->UseRealTime();
BENCHMARK_CAPTURE(cache_halves, own, false)
    ->Name("host/cache_halves")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK_CAPTURE(cache_halves, swapped, true)
    ->Name("host/cache_halves_swapped")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(plain_loop)->Name("host/plain_loop")->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(throughput_loop)->Name("host/throughput_loop")->Arg(1)->Arg(2)->UseRealTime();
