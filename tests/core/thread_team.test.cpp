// The engine's own team of threads (core/thread_team.hpp): who runs a region, its barrier, and
// regions asked for where another team already runs.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <set>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

using cosmpm::Index;

namespace {
constexpr long on_team = cosmpm::parallel_threshold;  // work that takes a team
}  // namespace

#if defined(_OPENMP)
TEST_CASE("team: every member once, each on a thread of its own, the caller member 0") {
  for (const int threads : {2, 3, 4, 2}) {  // 2 after 4: a smaller region on a larger team
    CAPTURE(threads);
    std::vector<int> calls(static_cast<std::size_t>(threads), 0);
    std::vector<std::thread::id> who(static_cast<std::size_t>(threads));
    std::vector<int> sizes(static_cast<std::size_t>(threads), 0);
    cosmpm::parallel_region(threads, on_team, [&] {
      const auto t = static_cast<std::size_t>(cosmpm::current_thread());
      ++calls[t];
      who[t] = std::this_thread::get_id();
      sizes[t] = cosmpm::current_team_size();
    });
    CHECK(std::count(calls.begin(), calls.end(), 1) == threads);
    CHECK(std::count(sizes.begin(), sizes.end(), threads) == threads);
    CHECK(std::set<std::thread::id>(who.begin(), who.end()).size() ==
          static_cast<std::size_t>(threads));
    CHECK(who[0] == std::this_thread::get_id());
    CHECK(cosmpm::current_team_size() == 1);  // back outside
    CHECK(cosmpm::current_thread() == 0);
  }
}

// Each member writes its slot of round k, waits, then reads every slot of round k: a barrier
// that let a member through early would show an old round's value.
TEST_CASE("team_barrier: no member passes before all have come") {
  for (const int threads : {2, 3}) {
    CAPTURE(threads);
    constexpr int rounds = 2000;
    std::vector<std::atomic<int>> slots(static_cast<std::size_t>(threads));
    for (auto& slot : slots) slot.store(-1);
    std::atomic<int> early{0};
    cosmpm::parallel_region(threads, on_team, [&] {
      const auto t = static_cast<std::size_t>(cosmpm::current_thread());
      for (int k = 0; k < rounds; ++k) {
        slots[t].store(k, std::memory_order_relaxed);
        cosmpm::team_barrier();
        for (const auto& slot : slots) {
          if (slot.load(std::memory_order_relaxed) < k) early.fetch_add(1);
        }
        cosmpm::team_barrier();  // nobody writes round k + 1 while another still reads k
      }
    });
    CHECK(early.load() == 0);
    for (const auto& slot : slots) CHECK(slot.load() == rounds - 1);
  }
}

TEST_CASE("team: a region asked for inside a region runs whole on the calling member") {
  constexpr Index count = 10000;
  std::vector<int> inner_ran(2, 0);
  std::vector<int> inner_sizes(2, 0);
  cosmpm::parallel_region(2, on_team, [&] {
    const auto outer = static_cast<std::size_t>(cosmpm::current_thread());
    cosmpm::parallel_region(2, on_team, [&] {
      const cosmpm::Share share = cosmpm::static_share(count);
      inner_ran[outer] += static_cast<int>(share.last - share.first);
      inner_sizes[outer] = cosmpm::current_team_size();
    });
    CHECK(cosmpm::current_team_size() == 2);  // the outer place is back
  });
  CHECK(inner_ran == std::vector<int>{count, count});
  CHECK(inner_sizes == std::vector<int>{1, 1});
}

// A user's own OpenMP region is not the engine's: a simulation stepped on one thread inside it
// must do all of its work, not one OpenMP thread's share (as it did when static_share asked
// OpenMP for the team).
TEST_CASE("team: regions inside a user's OpenMP region run whole, or on teams of their own") {
  constexpr Index count = 10000;
  std::vector<Index> alone(2, 0), teamed(2, 0);
#pragma omp parallel num_threads(2)
  {
    const auto user = static_cast<std::size_t>(omp_get_thread_num());
    cosmpm::parallel_region(1, on_team, [&] {
      const cosmpm::Share share = cosmpm::static_share(count);
      alone[user] = share.last - share.first;
    });
    std::atomic<Index> sum{0};
    cosmpm::parallel_region(2, on_team, [&] {
      const cosmpm::Share share = cosmpm::static_share(count);
      sum.fetch_add(share.last - share.first);
      cosmpm::team_barrier();
    });
    teamed[user] = sum.load();
  }
  const int users =
      static_cast<int>(std::count_if(alone.begin(), alone.end(), [](Index n) { return n != 0; }));
  CHECK(users >= 1);  // OpenMP may give the region fewer threads than asked
  for (int u = 0; u < users; ++u) {
    CHECK(alone[static_cast<std::size_t>(u)] == count);
    CHECK(teamed[static_cast<std::size_t>(u)] == count);
  }
}

TEST_CASE("team: two user threads, each with a team of its own, at the same time") {
  constexpr int regions = 500;
  constexpr Index count = 6000;
  std::vector<long> totals(2, 0);
  std::vector<std::thread> users;
  for (std::size_t u = 0; u < 2; ++u) {
    users.emplace_back([&totals, u] {
      long total = 0;
      for (int r = 0; r < regions; ++r) {
        std::atomic<long> sum{0};
        cosmpm::parallel_region(2, on_team, [&] {
          const cosmpm::Share share = cosmpm::static_share(count);
          long mine = 0;
          for (Index i = share.first; i < share.last; ++i) mine += i;
          sum.fetch_add(mine);
          cosmpm::team_barrier();
        });
        total += sum.load();
      }
      totals[u] = total;
    });
  }
  for (auto& user : users) user.join();
  const long expected = regions * (count * (count - 1) / 2);
  CHECK(totals == std::vector<long>{expected, expected});
}

// A child of fork() has only the forking thread: the team made before has no helpers there, and
// a region that waited for them would never end. The child makes a team of its own.
TEST_CASE("team: a forked child runs regions on a team of its own") {
  constexpr Index count = 6000;
  const auto sum_on_team = [] {
    std::atomic<long> sum{0};
    cosmpm::parallel_region(2, on_team, [&] {
      const cosmpm::Share share = cosmpm::static_share(count);
      sum.fetch_add(share.last - share.first);
      cosmpm::team_barrier();
    });
    return sum.load();
  };
  REQUIRE(sum_on_team() == count);  // the parent's team exists before the fork
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) _exit(sum_on_team() == count && sum_on_team() == count ? 0 : 1);
  int status = 0;
  pid_t done = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((done = waitpid(child, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (done == 0) kill(child, SIGKILL), waitpid(child, &status, 0);
  CHECK(done == child);  // it did not hang
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(sum_on_team() == count);  // the parent's team still works
}
#endif

TEST_CASE("team_barrier outside a region, or on one thread: returns at once") {
  cosmpm::team_barrier();
  int calls = 0;
  cosmpm::parallel_region(1, on_team, [&] {
    cosmpm::team_barrier();
    ++calls;
  });
  CHECK(calls == 1);
}
