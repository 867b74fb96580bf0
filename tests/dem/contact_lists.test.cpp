// The cell-list Verlet lists against brute force, and the skin's invisibility: a run gives
// bit-identical results whatever the skin (lists rebuilt every few steps or rarely), which
// holds only if no contact is ever missed and shear histories survive every rebuild.
#include <doctest/doctest.h>

#include <cstring>
#include <set>
#include <utility>
#include <vector>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

dem::Assembly random_assembly(int count, std::uint64_t seed) {
  dem::Assembly a;
  dem::Random random(seed);
  const dem::ClumpShape grain = dem::ClumpShape::two_disks(0.010, 0.006);
  for (int k = 0; k < count; ++k) {
    const Vec<2> x(random.uniform(0.0, 0.3), random.uniform(0.0, 0.3));
    if (k % 3 == 0) {
      a.add_clump(grain, 1.0, x, random.uniform(0, 2 * pi), 855.0);
    } else {
      a.add_disk(x, random.uniform(0.002, 0.007), 855.0);
    }
  }
  return a;
}

}  // namespace

TEST_CASE("contact lists: the candidates are exactly the pairs within the skin") {
  const dem::Assembly a = random_assembly(600, 11);
  const double skin = 0.001;
  dem::ContactLists lists;
  lists.build(
      a.elements(), skin, 1, 0, [](Index, const Vec<2>&) { return 0.0; },
      [](Index) { return false; }, false);
  const auto& x = a.elements().get<particles::field::Position<2>>();
  const auto& r = a.elements().get<dem::field::Radius>();
  const auto& body = a.elements().get<particles::field::Body>();
  std::set<std::pair<int, int>> brute;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      if (body[i] == body[j]) continue;
      const double reach = r[i] + r[j] + skin;
      if ((x[i] - x[j]).squaredNorm() < reach * reach) brute.insert({int(i), int(j)});
    }
  }
  std::set<std::pair<int, int>> listed;
  for (Index p = 0; p < lists.pair_count(); ++p) {
    listed.insert({lists.first[p], lists.second[p]});
    if (p > 0 && lists.first[p] == lists.first[p - 1]) CHECK(lists.second[p] > lists.second[p - 1]);
  }
  CHECK(listed == brute);
  CHECK(brute.size() > 500);
  // Every pair is reachable from its second element too.
  for (Index e = 0; e < a.element_count(); ++e) {
    for (Index q = lists.second_offsets[e]; q < lists.second_offsets[e + 1]; ++q) {
      CHECK(lists.second[lists.second_pairs[q]] == e);
    }
  }
}

TEST_CASE("contact lists: results do not depend on the skin") {
  auto run = [](double skin) {
    dem::Assembly a;
    dem::Grains grains;
    grains.shape = dem::ClumpShape::two_disks(1.0, 0.6);
    grains.min_size = 0.008;
    grains.max_size = 0.012;
    dem::rain(a, grains, 300, {0.0, 0.15, 0.02, 1.0}, 5);
    dem::Parameters p;
    p.skin = skin;
    dem::Simulation<> sim(std::move(a), dem::LinearSpring(), dem::LocalDamping(0.7), p);
    sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {.friction = 0.25});
    sim.add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), {});
    sim.add_plane_wall("right", Vec<2>(0.15, 0), Vec<2>(-1, 0), {});
    const double dt = 0.8 * sim.critical_time_step();
    for (int k = 0; k < 3000; ++k) sim.step(dt);
    return std::make_pair(sim.assembly().elements().get<particles::field::Position<2>>(),
                          sim.contact_lists().builds);
  };
  const auto [thin, thin_builds] = run(0.0002);
  const auto [thick, thick_builds] = run(0.004);
  MESSAGE("list builds: " << thin_builds << " with a 0.2 mm skin, " << thick_builds
                          << " with 4 mm");
  CHECK(thin_builds > 5 * thick_builds);
  REQUIRE(thin.size() == thick.size());
  CHECK(std::memcmp(thin.data(), thick.data(), thin.size() * sizeof(Vec<2>)) == 0);
}
