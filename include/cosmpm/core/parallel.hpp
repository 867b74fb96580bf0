#pragma once
// OpenMP without warnings when it is off: loops compile serially and stay correct.
#if defined(_OPENMP)
#include <omp.h>
#define COSMPM_PRAGMA(x) _Pragma(#x)
// Loops over fewer than cosmpm::parallel_threshold items run on one thread: a team's
// start-up and barrier cost more than they save, and far more on a loaded machine.
// Iterations are handed out in chunks as threads come free (dynamic), not split in equal
// halves up front: on a shared machine one core can run at half the speed of the other,
// and with equal halves the slow one sets the time. On this VM that made two threads no
// faster than one (measured on a plain parallel loop). Every loop this macro serves has
// independent iterations, so results do not depend on which thread ran which chunk.
#define COSMPM_OMP_PARALLEL_FOR(threads, work, chunk)                                        \
  COSMPM_PRAGMA(omp parallel for schedule(dynamic, chunk) num_threads(threads) if ((work) >= \
                                                                               cosmpm::parallel_threshold))
// The same loop with thread-private copies of the listed Index variables, combined by min at
// the end: each thread records the first particle that failed a check in a register, with
// no lock and no call inside the loop (a call there makes the compiler reload every array
// pointer per particle).
#define COSMPM_OMP_PARALLEL_FOR_MIN(threads, work, chunk, ...)                               \
  COSMPM_PRAGMA(omp parallel for schedule(dynamic, chunk) num_threads(threads) if ((work) >= \
                                                                               cosmpm::parallel_threshold) reduction(min : __VA_ARGS__))
// The same loop with the reduction clauses given, e.g. reduction(min : a) reduction(max : b).
#define COSMPM_OMP_PARALLEL_FOR_REDUCE(threads, work, chunk, ...)                            \
  COSMPM_PRAGMA(omp parallel for schedule(dynamic, chunk) num_threads(threads) if ((work) >= \
                                                                               cosmpm::parallel_threshold) __VA_ARGS__)
#else
#define COSMPM_OMP_PARALLEL_FOR(threads, work, chunk)
#define COSMPM_OMP_PARALLEL_FOR_MIN(threads, work, chunk, ...)
#define COSMPM_OMP_PARALLEL_FOR_REDUCE(threads, work, chunk, ...)
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

}  // namespace cosmpm
