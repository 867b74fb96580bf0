// Results do not depend on the thread count: 10,000 disks (and 5,000 two-disk clumps) packed
// on a lattice with overlaps, so every loop has more than cosmpm::parallel_threshold items and
// runs on the parallel path, stepped with 1 and with 2 threads, compared bit for bit.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

struct State {
  std::vector<Vec<2>> x, v;
  std::vector<double> spin;
  Vec<2> floor_force = Vec<2>::Zero();
  int team = 0;
  Index contacts = 0;
};

State run(bool clumps, int threads) {
  dem::Assembly a;
  dem::Random random(3);
  // A jittered lattice whose spacing is below the mean size: the particles start overlapping.
  const dem::ClumpShape grain = dem::ClumpShape::two_disks(0.010, 0.006);
  const int columns = 100, rows = clumps ? 50 : 100;
  const double spacing = clumps ? 0.008 : 0.0095;  // grains 9-11 mm long, disks 9.6-11 mm
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const Vec<2> centre(spacing * (i + 0.5) + random.uniform(-3e-4, 3e-4),
                          spacing * (j + 0.5) + random.uniform(-3e-4, 3e-4));
      if (clumps) {
        a.add_clump(grain, random.uniform(0.9, 1.1), centre, random.uniform(0, 2 * pi), 855.0);
      } else {
        a.add_disk(centre, random.uniform(0.0048, 0.0055), 855.0);
      }
    }
  }
  dem::Parameters p;
  p.threads = threads;
  dem::Simulation<> sim(std::move(a), dem::LinearSpring(), dem::LocalDamping(0.7), p);
  const Index floor = sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {});
  sim.add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), {});
  sim.add_plane_wall("right", Vec<2>(100 * spacing, 0), Vec<2>(-1, 0), {});
  const double dt = 0.8 * sim.critical_time_step();
  State s;
  for (int k = 0; k < 40; ++k) {
    sim.step(dt);
    s.team = std::max(s.team, sim.last_team_size());
  }
  s.x = sim.assembly().elements().get<particles::field::Position<2>>();
  s.v = sim.assembly().bodies().get<particles::field::Velocity<2>>();
  s.spin = sim.assembly().bodies().get<dem::field::Spin>();
  s.floor_force = sim.wall_force(floor);
  s.contacts = sim.active_contacts();
  return s;
}

bool same_bits(const void* a, const void* b, std::size_t bytes) {
  return std::memcmp(a, b, bytes) == 0;
}

void compare(bool clumps) {
  const State one = run(clumps, 1);
  const State two = run(clumps, 2);
  CHECK(one.contacts > parallel_threshold);  // jammed: thousands of contacts to sum
  CHECK(one.team == 1);
#if defined(_OPENMP)
  CHECK(two.team == 2);  // the parallel path ran
#else
  MESSAGE("built without OpenMP: both runs are serial");
#endif
  REQUIRE(one.x.size() == two.x.size());
  CHECK(same_bits(one.x.data(), two.x.data(), one.x.size() * sizeof(Vec<2>)));
  CHECK(same_bits(one.v.data(), two.v.data(), one.v.size() * sizeof(Vec<2>)));
  CHECK(same_bits(one.spin.data(), two.spin.data(), one.spin.size() * sizeof(double)));
  CHECK(same_bits(one.floor_force.data(), two.floor_force.data(), sizeof(Vec<2>)));
}

}  // namespace

TEST_CASE("determinism: 10,000 disks step bit-identically on 1 and 2 threads") {
  compare(false);
}

TEST_CASE("determinism: 5,000 clumps step bit-identically on 1 and 2 threads") {
  compare(true);
}
