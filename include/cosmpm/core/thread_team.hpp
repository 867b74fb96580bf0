#pragma once
// The engine's own team of threads: helpers kept for the thread that asks for them, handed each
// region's work through shared words they watch, and joined when that thread ends.
//
// Why not OpenMP's team: libgomp makes a futex system call when it starts a region's team, at
// every barrier and at the region's end, whatever the wait policy, and a system call costs
// about 1 us on this VM (page-table isolation). An empty two-thread region cost 3.1 us, a
// fused MUSL step made 12 system calls and a plain MUSL one 24. Handed over by spinning, a
// region costs about 0.5 us and a barrier less (docs/performance.md, "A team of our own").
//
// A waiting member spins for up to team_spin_budget(), then sleeps in the kernel until woken
// (std::atomic wait and notify: no system call when nobody sleeps). OMP_WAIT_POLICY=passive
// makes it sleep at once, as libgomp's threads do under that setting. A child of fork() makes a
// team of its own: the parent's helpers are not there.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <string_view>
#include <thread>
#include <vector>

#if __has_include(<pthread.h>)
#include <pthread.h>
#endif

namespace cosmpm::detail {

class ThreadTeam;

// Where the calling thread stands: member `thread` of a region of `size` on `team`; thread 0 of
// 1, on no team, outside the engine's regions.
struct TeamPlace {
  int thread = 0;
  int size = 1;
  ThreadTeam* team = nullptr;
};
inline thread_local TeamPlace team_place{};

// How long a waiting member spins before it sleeps: 200 us covers the serial gaps between a
// step's regions and between steps; OMP_WAIT_POLICY=passive (set where test processes share the
// cores) sleeps at once.
inline std::chrono::nanoseconds team_spin_budget() {
  static const std::chrono::nanoseconds budget = [] {
    const char* policy = std::getenv("OMP_WAIT_POLICY");
    const std::string_view value = policy != nullptr ? policy : "";
    const bool passive = value == "passive" || value == "PASSIVE" || value == "Passive";
    return passive ? std::chrono::nanoseconds{0} : std::chrono::nanoseconds{200'000};
  }();
  return budget;
}

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// The value of `word` once it differs from `seen` (acquire): spins, then sleeps.
inline unsigned wait_for_change(const std::atomic<unsigned>& word, unsigned seen) {
  unsigned now = word.load(std::memory_order_acquire);
  if (now != seen) return now;
  const auto budget = team_spin_budget();
  if (budget.count() > 0) {
    const auto start = std::chrono::steady_clock::now();
    do {
      for (int i = 0; i < 64; ++i) {
        cpu_relax();
        now = word.load(std::memory_order_acquire);
        if (now != seen) return now;
      }
    } while (std::chrono::steady_clock::now() - start < budget);
  }
  for (;;) {
    word.wait(seen, std::memory_order_acquire);
    now = word.load(std::memory_order_acquire);
    if (now != seen) return now;
  }
}

// Forks this process has seen itself born from: a child of fork() has only the forking thread,
// so a team made before has no helpers there (counted by a pthread_atfork handler in the child,
// registered at the first call).
inline std::atomic<unsigned> forks_seen{0};
inline unsigned fork_count() {
#if __has_include(<pthread.h>)
  static const int registered =
      pthread_atfork(nullptr, nullptr, [] { forks_seen.fetch_add(1, std::memory_order_relaxed); });
  (void)registered;
#endif
  return forks_seen.load(std::memory_order_relaxed);
}

class ThreadTeam {
 public:
  // A team of `size` members: the constructing thread (member 0) and size - 1 helpers.
  explicit ThreadTeam(int size) : made_after_forks_(fork_count()) {
    helpers_.reserve(static_cast<std::size_t>(size - 1));
    for (int member = 1; member < size; ++member) {
      helpers_.emplace_back([this, member] { serve(member); });
    }
  }
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  ~ThreadTeam() {
    stop_ = true;
    start_.fetch_add(1, std::memory_order_release);
    start_.notify_all();
    for (auto& helper : helpers_) helper.join();
  }

  int size() const { return static_cast<int>(helpers_.size()) + 1; }
  // Whether its helpers run in this process (not made before a fork() that led here).
  bool helpers_here() const { return made_after_forks_ == fork_count(); }

  // call(body) on members 0..size-1 (size <= this->size()), the calling thread as member 0;
  // returns when all have returned. noexcept: a throwing body ends the program, as it does in
  // an OpenMP region (the helpers would otherwise run on with the body's frame gone).
  void run(int size, void (*call)(void*), void* body) noexcept {
    call_ = call;
    body_ = body;
    active_ = size;
    arrived_.store(0, std::memory_order_relaxed);
    start_.fetch_add(1, std::memory_order_release);  // publishes the three above
    start_.notify_all();
    const TeamPlace outside = team_place;
    team_place = {0, size, this};
    call(body);
    team_place = outside;
    const auto helpers = static_cast<unsigned>(helpers_.size());
    for (unsigned seen = arrived_.load(std::memory_order_acquire); seen != helpers;) {
      seen = wait_for_change(arrived_, seen);
    }
  }

  // Every member of the running region waits here until all have come.
  void barrier() noexcept {
    const unsigned generation = barrier_generation_.load(std::memory_order_acquire);
    if (barrier_count_.fetch_add(1, std::memory_order_acq_rel) + 1 ==
        static_cast<unsigned>(active_)) {
      barrier_count_.store(0, std::memory_order_relaxed);
      barrier_generation_.store(generation + 1, std::memory_order_release);
      barrier_generation_.notify_all();
    } else {
      wait_for_change(barrier_generation_, generation);
    }
  }

 private:
  void serve(int member) {
    unsigned seen = 0;
    for (;;) {
      seen = wait_for_change(start_, seen);
      if (stop_) return;
      if (member < active_) {
        team_place = {member, active_, this};
        call_(body_);
        team_place = {};
      }
      arrived_.fetch_add(1, std::memory_order_release);
      arrived_.notify_all();
    }
  }

  // Each word the members spin on in a cache line of its own, away from the region's data.
  alignas(64) std::atomic<unsigned> start_{0};    // bumped to start a region (or to stop)
  alignas(64) std::atomic<unsigned> arrived_{0};  // helpers done with the region
  alignas(64) std::atomic<unsigned> barrier_count_{0};
  alignas(64) std::atomic<unsigned> barrier_generation_{0};
  // Written by member 0 before start_ is bumped, read by helpers after they see it.
  alignas(64) void (*call_)(void*) = nullptr;
  void* body_ = nullptr;
  int active_ = 1;
  bool stop_ = false;
  unsigned made_after_forks_;
  std::vector<std::thread> helpers_;
};

// The calling thread's team, of at least `size` members: made at its first use, larger when a
// region asks for more, joined when the thread ends. Each calling thread has its own, so
// simulations stepped side by side on user threads do not share one.
inline ThreadTeam& team_of_calling_thread(int size) {
  thread_local std::unique_ptr<ThreadTeam> team;
  if (team && !team->helpers_here()) {
    (void)team.release();  // made in the parent: its helpers cannot be joined or woken here
  }
  if (!team || team->size() < size) {
    team.reset();  // its helpers joined before more are made
    team = std::make_unique<ThreadTeam>(size);
  }
  return *team;
}

// body() on a team of `size`, member 0 the calling thread. A region asked for inside one of the
// engine's regions runs on the calling member alone, as its own team of one.
template <class Body>
void run_on_team(int size, void (*call)(void*), Body& body) {
  if (team_place.team != nullptr) {
    const TeamPlace outer = team_place;
    team_place = {};
    call(&body);
    team_place = outer;
    return;
  }
  team_of_calling_thread(size).run(size, call, &body);
}

// Inside a region: waits for the region's other members (nothing outside one).
inline void team_barrier() {
  if (team_place.size > 1) team_place.team->barrier();
}

}  // namespace cosmpm::detail
