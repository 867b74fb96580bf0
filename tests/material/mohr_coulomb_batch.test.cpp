// MohrCoulomb::update_batch (detail/mohr_coulomb_batch.hpp) against the per-point update, bit
// for bit, for every variant of the model: every return region, separated points, the
// dilatancy cut-off, Tresca, a tension cut-off below the apex (the per-point path), increments
// that are not finite, and batch sizes that leave a remainder after the lanes.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "material/mohr_coulomb_points.hpp"

using cosmpm::material::MohrCoulomb;
using cosmpm::material::MohrCoulombParameters;
using cosmpm::material::MohrCoulombRegion;
using cosmpm::material::PlasticState;
using namespace mohr_coulomb_points;

namespace {

bool same_bits(const Stress& a, const Stress& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 4) == 0;
}
bool same_bits(const PlasticState& a, const PlasticState& b) {
  const auto x = a.values(), y = b.values();
  return std::memcmp(x.data(), y.data(), sizeof(double) * x.size()) == 0;
}

// Runs update point by point and the batched updates over [first, first + size) of copies of
// `points`; returns the number of points that differ in any bit (summed over the batched
// updates), and counts the regions update used.
// (A template, so that the discarded width-4 branch is not compiled for SSE2.)
template <class Model>
std::size_t differences(const Model& model, const Points& points, std::size_t first,
                        std::size_t size, std::map<MohrCoulombRegion, int>& regions) {
  auto one = points;
  for (std::size_t i = first; i < first + size; ++i)
    ++regions[model.update_region(one.stress[i], one.state[i], one.increment[i])];
  std::size_t differing = 0;
  // update_batch (lanes of the target's width with AVX, else one by one) and the lane code at
  // width 2 whatever the target (and 4 where the registers hold 4 doubles).
  const auto compare = [&](auto run_batch) {
    auto batch = points;
    run_batch(std::span(batch.stress.data() + first, size),
              std::span(batch.state.data() + first, size),
              std::span<const Strain>(batch.increment.data() + first, size));
    for (std::size_t i = 0; i < points.stress.size(); ++i) {
      if (!same_bits(one.stress[i], batch.stress[i]) || !same_bits(one.state[i], batch.state[i]))
        ++differing;
    }
  };
  compare([&](auto stress, auto state, auto increment) {
    model.update_batch(stress, state, increment);
  });
  compare([&](auto stress, auto state, auto increment) {
    model.template update_lanes<2>(stress, state, increment);
  });
  if constexpr (cosmpm::material::detail::register_bytes >= 4 * sizeof(double)) {
    compare([&](auto stress, auto state, auto increment) {
      model.template update_lanes<4>(stress, state, increment);
    });
  }
  return differing;
}

}  // namespace

TEST_CASE("MohrCoulomb::update_batch equals update bit for bit in every variant and region") {
  std::map<std::string, MohrCoulombParameters> variants;
  variants["corn"] = corn();
  variants["separation"] = corn();
  variants["separation"].separation = true;
  variants["dilatancy cut-off"] = corn();
  variants["dilatancy cut-off"].dilatancy_cutoff_strain = 0.05;
  variants["Tresca"] = {.youngs_modulus = 2.76e6,
                        .poisson_ratio = 0.2,
                        .friction_angle_deg = 0,
                        .dilatancy_angle_deg = 0,
                        .cohesion = 5e3};
  variants["cohesion, tension cut-off below the apex"] = {.youngs_modulus = 2.76e6,
                                                          .poisson_ratio = 0.2,
                                                          .friction_angle_deg = 26,
                                                          .dilatancy_angle_deg = 2,
                                                          .cohesion = 2e3,
                                                          .tension_cutoff = 1e3};
  const Points points = random_points(4001, 17);
  for (const auto& [name, parameters] : variants) {
    CAPTURE(name);
    const MohrCoulomb<double> model(parameters);
    std::map<MohrCoulombRegion, int> regions;
    CHECK(differences(model, points, 0, points.stress.size(), regions) == 0);
    // Each region the variant has is exercised, so an equality of untouched paths proves
    // nothing less: at least 50 points in each (of 4001).
    CHECK(regions[MohrCoulombRegion::elastic] >= 50);
    CHECK(regions[MohrCoulombRegion::plane] >= 50);
    if (parameters.friction_angle_deg > 0) {
      CHECK(regions[MohrCoulombRegion::compression_edge] >= 50);
      CHECK(regions[MohrCoulombRegion::extension_edge] >= 50);
    }
    if (parameters.tension_cutoff) {
      CHECK(regions[MohrCoulombRegion::tension] >= 50);
    } else if (parameters.friction_angle_deg > 0) {
      CHECK(regions[MohrCoulombRegion::apex] >= 50);
    }
    if (parameters.separation) CHECK(regions[MohrCoulombRegion::separated] >= 50);
  }
}

TEST_CASE(
    "MohrCoulomb::update_batch equals update bit for bit with the points in runs of one region") {
  // The engine's points come in space order, so whole packs are elastic, or plastic and on the
  // yield plane: the lanes then skip the plastic return, or the edges' returns, by one branch
  // for the pack. Random points (above) seldom fill a pack with one region; here they are
  // ordered by the region update() takes, so most packs have one, and the packs where two
  // regions meet mix them.
  for (const bool separation : {false, true}) {
    CAPTURE(separation);
    auto parameters = corn();
    parameters.separation = separation;
    parameters.dilatancy_cutoff_strain = 0.05;
    const MohrCoulomb<double> model(parameters);
    const Points random = random_points(4001, 23);
    std::vector<std::pair<MohrCoulombRegion, std::size_t>> order;
    for (std::size_t i = 0; i < random.stress.size(); ++i) {
      auto stress = random.stress[i];
      auto state = random.state[i];
      order.emplace_back(model.update_region(stress, state, random.increment[i]), i);
    }
    std::stable_sort(order.begin(), order.end());
    Points points;
    for (const auto& [region, i] : order) {
      points.stress.push_back(random.stress[i]);
      points.state.push_back(random.state[i]);
      points.increment.push_back(random.increment[i]);
    }
    std::map<MohrCoulombRegion, int> regions;
    CHECK(differences(model, points, 0, points.stress.size(), regions) == 0);
    // Enough of each for whole packs of it (at least 50 points, 12 packs of 4).
    for (const auto region :
         {MohrCoulombRegion::elastic, MohrCoulombRegion::plane, MohrCoulombRegion::compression_edge,
          MohrCoulombRegion::extension_edge, MohrCoulombRegion::apex}) {
      CAPTURE(static_cast<int>(region));
      CHECK(regions[region] >= 50);
    }
  }
}

TEST_CASE("MohrCoulomb::update_batch: batches of every small size and offset leave the rest") {
  // Sizes 0 to 9 cover a remainder after lanes of 2 and 4 and batches shorter than one pack;
  // points outside the batch must come out untouched (differences() compares all of them).
  auto parameters = corn();
  parameters.separation = true;
  const MohrCoulomb<double> model(parameters);
  const Points points = random_points(40, 5);
  std::map<MohrCoulombRegion, int> regions;
  for (std::size_t size = 0; size < 10; ++size) {
    for (std::size_t first = 0; first < 3; ++first) {
      CAPTURE(size);
      CAPTURE(first);
      CHECK(differences(model, points, first, size, regions) == 0);
    }
  }
}

TEST_CASE("MohrCoulomb::update_batch: spans of different sizes throw before writing") {
  const MohrCoulomb<double> model(corn());
  std::vector<Stress> stress(4, Stress(-1e4, -1e4, -1e4, 0.0));
  std::vector<PlasticState> state(3);
  const std::vector<Strain> increment(4, Strain(1e-3, 0.0, 0.0, 0.0));
  const auto message = doctest::Contains("MohrCoulomb::update_batch: stress has 4 points, state 3");
  CHECK_THROWS_WITH_AS(model.update_batch(stress, state, increment), message, cosmpm::Error);
  CHECK_THROWS_WITH_AS(model.update_lanes<2>(stress, state, increment), message, cosmpm::Error);
  CHECK(stress[0] == Stress(-1e4, -1e4, -1e4, 0.0));
}
