#include <doctest/doctest.h>

#include <vector>

#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"

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
#if defined(_OPENMP)
#pragma omp parallel num_threads(team)
#endif
      {
        const cosmpm::Share share = cosmpm::static_share(count);
        const int thread = cosmpm::current_thread();
        for (Index i = share.first; i < share.last; ++i) {
          const auto k = static_cast<std::size_t>(i);
          if (by_share[k] != -1) ++overlaps[static_cast<std::size_t>(thread)];
          by_share[k] = thread;
        }
      }
#if defined(_OPENMP)
#pragma omp parallel for schedule(static) num_threads(team)
#endif
      for (Index i = 0; i < count; ++i) {
        by_loop[static_cast<std::size_t>(i)] = cosmpm::current_thread();
      }
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
