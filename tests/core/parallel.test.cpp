#include <doctest/doctest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

using cosmpm::Index;

// static_share must give each thread the iterations `omp for schedule(static)` gives it: the
// node passes that split their work themselves (stages/particle_to_grid.hpp, remap.hpp) then
// touch the same nodes on the same thread as the other node loops of the step.
TEST_CASE("static_share: the iterations schedule(static) gives the calling thread") {
  for (const int team : {1, 2, 3, 4}) {
    for (const Index count : {Index{0}, Index{1}, Index{5}, Index{4097}, Index{6171}}) {
      CAPTURE(team);
      CAPTURE(count);
      std::vector<int> by_share(static_cast<std::size_t>(count), -1);
      std::vector<int> by_loop(static_cast<std::size_t>(count), -1);
      std::vector<int> overlaps(static_cast<std::size_t>(team), 0);
      // A region of the engine's team, whatever the count (work = the threshold).
      cosmpm::parallel_region(team, cosmpm::parallel_threshold, [&] {
        const cosmpm::Share share = cosmpm::static_share(count);
        const int thread = cosmpm::current_thread();
        for (Index i = share.first; i < share.last; ++i) {
          const auto k = static_cast<std::size_t>(i);
          if (by_share[k] != -1) ++overlaps[static_cast<std::size_t>(thread)];
          by_share[k] = thread;
        }
      });
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team)
      for (Index i = 0; i < count; ++i) by_loop[static_cast<std::size_t>(i)] = omp_get_thread_num();
#else
      std::fill(by_loop.begin(), by_loop.end(), 0);
#endif
      for (const int o : overlaps) CHECK(o == 0);
      CHECK(by_share == by_loop);  // every iteration once, on the same thread
    }
  }
}

TEST_CASE("static_share outside a parallel region: everything") {
  const cosmpm::Share share = cosmpm::static_share(6171);
  CHECK(share.first == 0);
  CHECK(share.last == 6171);
}

namespace {
// Nesting depth of OpenMP regions, inactive ones (a team of one) included: 0 when the calling
// code runs outside the runtime.
int region_level() {
#if defined(_OPENMP)
  return omp_get_level();
#else
  return 0;
#endif
}
}  // namespace

// One thread or too little work: the body runs once on the calling thread without entering the
// OpenMP runtime (libgomp makes a system call at the end of every region, even a team of one).
TEST_CASE("parallel_region: one thread or little work stays outside the runtime") {
  for (const auto& [threads, work] :
       {std::pair{1, 1000000L}, std::pair{2, 10L}, std::pair{4, cosmpm::parallel_threshold - 1}}) {
    CAPTURE(threads);
    CAPTURE(work);
    CHECK_FALSE(cosmpm::runs_on_team(threads, work));
    int calls = 0;
    int level = -1;
    cosmpm::parallel_region(threads, work, [&] {
      ++calls;
      level = region_level();
    });
    CHECK(calls == 1);
    CHECK(level == 0);
  }
}

#if defined(_OPENMP)
TEST_CASE("parallel_region: a team where it pays, every member calling the body once") {
  REQUIRE(cosmpm::runs_on_team(2, cosmpm::parallel_threshold));
  std::vector<int> calls(2, 0);
  int team = 0;
  int level = -1;
  cosmpm::parallel_region(2, cosmpm::parallel_threshold, [&] {
    ++calls[static_cast<std::size_t>(cosmpm::current_thread())];  // each its own slot
    if (cosmpm::current_thread() == 0) {
      team = cosmpm::current_team_size();
      level = region_level();
    }
  });
  CHECK(level == 0);  // the engine's own team, not OpenMP's
  CHECK(team == 2);
  CHECK(calls == std::vector<int>{1, 1});
}
#endif

TEST_CASE("parallel_for: every iteration once, on the thread schedule(static) gives it") {
  for (const int threads : {1, 2, 3}) {
    for (const Index count : {Index{0}, Index{7}, Index{4096}, Index{6171}}) {
      CAPTURE(threads);
      CAPTURE(count);
      std::vector<int> ran(static_cast<std::size_t>(count), 0);
      std::vector<int> by(static_cast<std::size_t>(count), -1);
      cosmpm::parallel_for(threads, count, [&](Index i) {
        ++ran[static_cast<std::size_t>(i)];
        by[static_cast<std::size_t>(i)] = cosmpm::current_thread();
      });
      CHECK(std::count(ran.begin(), ran.end(), 1) == count);
      // schedule(static) over the team that ran: thread t has the t-th contiguous part. Without
      // OpenMP there is no team.
#if defined(_OPENMP)
      const int team = cosmpm::runs_on_team(threads, count) ? threads : 1;
#else
      const int team = 1;
#endif
      std::vector<int> expected(static_cast<std::size_t>(count), 0);
      for (int t = 0; t < team; ++t) {
        const Index base = count / team, extra = count % team;
        const Index first = t * base + std::min<Index>(t, extra);
        const Index last = first + base + (t < extra ? 1 : 0);
        for (Index i = first; i < last; ++i) expected[static_cast<std::size_t>(i)] = t;
      }
      CHECK(by == expected);
    }
  }
}

// How a region's threads combine the first particle each found failing a check.
TEST_CASE("combine_min: the smallest of every thread's value, whatever the order") {
  Index first = 5000;
  cosmpm::parallel_for(2, 8192, [&](Index i) {
    if (i % 1000 == 777) cosmpm::combine_min(first, 8191 - i);  // 414 from i = 7777
  });
  CHECK(first == 414);
  cosmpm::combine_min(first, 9000);  // a larger value changes nothing
  CHECK(first == 414);
}
