#pragma once
// How the engine runs work on several threads.
//
// Regions and loops run on a team only when one pays: more than one thread asked for and at
// least cosmpm::parallel_threshold items (a team's start-up and barrier cost more than they
// save on less, and far more on a loaded machine). Otherwise they run on the calling thread
// alone. The team is the engine's own (core/thread_team.hpp), not OpenMP's: libgomp makes a
// futex system call at a region's start, at each barrier and at its end, even for a team of
// one, and a system call costs about 1 us on this VM (docs/performance.md, "What a parallel
// region costs", "A team of our own"). OpenMP still decides how many threads there are
// (OMP_NUM_THREADS), and a build without it runs on one.
//
// Iterations are split in equal contiguous parts, thread t always taking the t-th (OpenMP
// `schedule(static)`, static_share below), so a thread touches the same particles and nodes in
// every pass of a step and of the next one: on this VM a cache line written on one vCPU and
// read on the other costs about twice a line read where it was written, and handing out
// chunks as threads come free (`schedule(dynamic)`, used up to 2026-12-03) moved most of the
// step's data between them every pass, so that two threads ran the step slower than one
// (docs/performance.md, "Two threads and the host"). Every loop run so has independent
// iterations, so results do not depend on which thread ran which part.
#include <algorithm>
#include <atomic>
#include <type_traits>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/thread_team.hpp"
#include "cosmpm/core/types.hpp"

#if defined(_OPENMP)
#include <omp.h>
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

// Threads of the engine's region running the calling code (1 outside one). An OpenMP region of
// the caller's own does not count: a simulation stepped on one thread inside it runs whole.
inline int current_team_size() {
  return detail::team_place.size;
}

// The calling thread's number in the engine's region running it (0 outside one).
inline int current_thread() {
  return detail::team_place.thread;
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

// Whether work of `work` items runs on a team of `threads` (see the top of this header).
inline bool runs_on_team(int threads, long work) {
  return threads > 1 && work >= parallel_threshold;
}

namespace detail {
// The body of a region as one function, called by every member of a team or by the calling
// thread alone: the same machine code either way. Inlined into each path, the two copies could
// contract multiply-adds differently (GCC 12, -march=native, as map_to_particles' lambda did);
// results would then depend on the threads.
template <class Body>
[[gnu::noinline]] void run_region_body(Body& body) {
  body();
}
template <class Body>
void call_region_body(void* body) {
  run_region_body(*static_cast<Body*>(body));
}
}  // namespace detail

// body() once by every member of a team of `threads` when runs_on_team, each splitting the
// work itself (static_share); else once on the calling thread.
template <class Body>
COSMPM_ALWAYS_INLINE void parallel_region([[maybe_unused]] int threads, [[maybe_unused]] long work,
                                          Body&& body) {
#if defined(_OPENMP)
  if (runs_on_team(threads, work)) {
    using Plain = std::remove_reference_t<Body>;
    detail::run_on_team(threads, &detail::call_region_body<Plain>, body);
    return;
  }
#endif
  detail::run_region_body(body);
}

// Inside parallel_region's body: waits until every member of the region has come (nothing on a
// team of one).
inline void team_barrier() {
  detail::team_barrier();
}

// body(i) for i in [0, count), split as schedule(static) where parallel_region runs a team.
template <class Body>
COSMPM_ALWAYS_INLINE void parallel_for(int threads, Index count, Body&& body) {
  parallel_region(threads, count, [&] {
    const Share share = static_share(count);
    for (Index i = share.first; i < share.last; ++i) body(i);
  });
}

// shared = min(shared, mine), from any thread of a team: how a region's threads combine the
// first particle each found failing a check (exact, and independent of the order).
inline void combine_min(Index& shared, Index mine) {
  std::atomic_ref<Index> ref(shared);
  Index seen = ref.load(std::memory_order_relaxed);
  while (mine < seen && !ref.compare_exchange_weak(seen, mine, std::memory_order_relaxed)) {
  }
}

}  // namespace cosmpm
