#pragma once
// OpenMP without warnings when it is off: loops compile serially and stay correct.
#if defined(_OPENMP)
#include <omp.h>
#define COSMPM_PRAGMA(x) _Pragma(#x)
// Loops over fewer than cosmpm::parallel_threshold items run on one thread: a team's
// start-up and barrier cost more than they save, and far more on a loaded machine.
#define COSMPM_OMP_PARALLEL_FOR(threads, work) \
  COSMPM_PRAGMA(omp parallel for schedule(static) num_threads(threads) if ((work) >= cosmpm::parallel_threshold))
#else
#define COSMPM_OMP_PARALLEL_FOR(threads, work)
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

}  // namespace cosmpm
