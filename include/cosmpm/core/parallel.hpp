#pragma once
#include <algorithm>

#include "cosmpm/core/types.hpp"
// OpenMP without warnings when it is off: loops compile serially and stay correct.
#if defined(_OPENMP)
#include <omp.h>
#define COSMPM_PRAGMA(x) _Pragma(#x)
// Loops over fewer than cosmpm::parallel_threshold items run on one thread: a team's
// start-up and barrier cost more than they save, and far more on a loaded machine.
// Iterations are split in equal contiguous parts, thread t always taking the t-th (OpenMP
// `schedule(static)`), so a thread touches the same particles and nodes in every pass of a
// step and of the next one: on this VM a cache line written on one vCPU and read on the other
// costs about twice a line read where it was written, and handing out chunks as threads come
// free (`schedule(dynamic)`, used up to 2026-12-03) moved most of the step's data between them
// every pass, so that two threads ran the step slower than one (docs/performance.md, "Two
// threads and the host"). Every loop these macros serve has independent iterations, so
// results do not depend on which thread ran which part.
#define COSMPM_OMP_PARALLEL_FOR(threads, work)                                       \
  COSMPM_PRAGMA(omp parallel for schedule(static) num_threads(threads) if ((work) >= \
                                                                         cosmpm::parallel_threshold))
// The same loop with thread-private copies of the listed Index variables, combined by min at
// the end: each thread records the first particle that failed a check in a register, with
// no lock and no call inside the loop (a call there makes the compiler reload every array
// pointer per particle).
#define COSMPM_OMP_PARALLEL_FOR_MIN(threads, work, ...)                              \
  COSMPM_PRAGMA(omp parallel for schedule(static) num_threads(threads) if ((work) >= \
                                                                         cosmpm::parallel_threshold) reduction(min : __VA_ARGS__))
// A team for a region that splits its work itself (static_share below).
#define COSMPM_OMP_PARALLEL(threads, work) \
  COSMPM_PRAGMA(omp parallel num_threads(threads) if ((work) >= cosmpm::parallel_threshold))
#else
#define COSMPM_OMP_PARALLEL_FOR(threads, work)
#define COSMPM_OMP_PARALLEL_FOR_MIN(threads, work, ...)
#define COSMPM_OMP_PARALLEL(threads, work)
#endif

namespace cosmpm {

inline constexpr long parallel_threshold = 4096;

// Threads the engine uses when the user asks for `requested` (0: OpenMP's default).
inline int resolve_thread_count(int requested) {
#if defined(_OPENMP)
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

// Threads of the team running the calling code (1 outside a parallel region or without OpenMP).
inline int current_team_size() {
#if defined(_OPENMP)
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// The calling thread's number in its team (0 outside a parallel region or without OpenMP).
inline int current_thread() {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// The iterations [first, last) of `count` that `schedule(static)` gives the calling thread:
// a region doing several loops over the same share runs them without a barrier between.
struct Share {
  Index first;
  Index last;
};
inline Share static_share(Index count) {
  const Index team = current_team_size();
  const Index thread = current_thread();
  const Index base = count / team;
  const Index extra = count % team;  // the first `extra` threads take one more
  const Index first = thread * base + std::min(thread, extra);
  return {first, first + base + (thread < extra ? 1 : 0)};
}

}  // namespace cosmpm
