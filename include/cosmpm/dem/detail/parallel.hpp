#pragma once
// Parallel loops of the DEM engine. Each returns the size of the team that ran it, so a test
// can assert that the parallel path really ran. Iterations are independent and every result
// lands in a slot of its own, so results never depend on the thread count. Loops below
// cosmpm::parallel_threshold run on one thread (core/parallel.hpp explains why).
#include <algorithm>
#include <limits>

#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::dem::detail {

template <class Body>
int parallel_for(int threads, Index count, Body&& body) {
  int team = 1;
#if defined(_OPENMP)
  if (!cosmpm::runs_on_team(threads, count)) {  // outside the runtime (core/parallel.hpp)
    for (Index i = 0; i < count; ++i) body(i);
    return team;
  }
#pragma omp parallel num_threads(threads)
  {
#pragma omp master
    team = omp_get_num_threads();
#pragma omp for schedule(dynamic, 256)
    for (Index i = 0; i < count; ++i) body(i);
  }
#else
  (void)threads;
  for (Index i = 0; i < count; ++i) body(i);
#endif
  return team;
}

// What the integration loop reports: the first element that moved more than its radius (or
// became non-finite) and the largest squared displacement since the contact lists were built.
struct MotionReport {
  Index first_unstable = std::numeric_limits<Index>::max();
  double max_drift_squared = 0.0;
  void merge(const MotionReport& other) {
    first_unstable = std::min(first_unstable, other.first_unstable);
    max_drift_squared = std::max(max_drift_squared, other.max_drift_squared);
  }
};

// body(i, report) for every i; the reports of all threads merged (min and max: exact and
// independent of the order).
template <class Body>
int parallel_for_motion(int threads, Index count, MotionReport& report, Body&& body) {
  int team = 1;
#if defined(_OPENMP)
  if (!cosmpm::runs_on_team(threads, count)) {  // outside the runtime (core/parallel.hpp)
    for (Index i = 0; i < count; ++i) body(i, report);
    return team;
  }
#pragma omp parallel num_threads(threads)
  {
#pragma omp master
    team = omp_get_num_threads();
    MotionReport local;
#pragma omp for schedule(dynamic, 256) nowait
    for (Index i = 0; i < count; ++i) body(i, local);
#pragma omp critical(cosmpm_dem_motion)
    report.merge(local);
  }
#else
  (void)threads;
  for (Index i = 0; i < count; ++i) body(i, report);
#endif
  return team;
}

}  // namespace cosmpm::dem::detail
