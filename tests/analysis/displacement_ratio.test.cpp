// The particle displacement ratio (Coetzee 2014, Sect. 3.3) on known motions.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "analysis_test_support.hpp"
#include "cosmpm/analysis/displacement_ratio.hpp"
#include "cosmpm/core/error.hpp"

namespace {
using namespace cosmpm;
namespace field = particles::field;

TEST_CASE("PDR of a translation and of a rotation") {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {20, 20});
  auto store = test::seeded(particles::seed_box(grid, Vec<2>(0.2, 0.2), Vec<2>(0.6, 0.6), 2));
  const std::vector<Vec<2>> start = store.get<field::Position<2>>();
  const Vec<2> blade(0.02, 0.0);  // 20 mm of blade travel
  // Every particle moved 3 mm, 4 mm: |u| = 5 mm, a quarter of the blade's travel.
  for (auto& x : store.get<field::Position<2>>()) x += Vec<2>(0.003, 0.004);
  for (double ratio : analysis::displacement_ratio(store, std::span<const Vec<2>>(start), blade)) {
    CHECK(ratio == doctest::Approx(0.25));
  }
  // A rigid rotation by theta about c moves a particle at distance r by 2 r sin(theta / 2).
  const Vec<2> c(0.4, 0.4);
  const double theta = 0.3;
  Mat<2> rotation;
  rotation << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  auto& x = store.get<field::Position<2>>();
  for (std::size_t p = 0; p < x.size(); ++p) x[p] = c + rotation * (start[p] - c);
  const auto ratio = analysis::displacement_ratio(store, std::span<const Vec<2>>(start), blade);
  for (std::size_t p = 0; p < x.size(); ++p) {
    const double r = (start[p] - c).norm();
    CHECK(ratio[p] == doctest::Approx(2.0 * r * std::sin(theta / 2) / 0.02).epsilon(1e-12));
  }
  // The paper's map: PDR >= 0.15 beyond r = 0.15 x 0.02 / (2 sin 0.15) = 10.0 mm of c.
  const auto dark = analysis::at_least(ratio, 0.15);
  for (std::size_t p = 0; p < x.size(); ++p) {
    CHECK(dark[p] == ((start[p] - c).norm() * 2.0 * std::sin(theta / 2) >= 0.003 ? 1 : 0));
  }
}

TEST_CASE("PDR needs a tool displacement and one reference per particle") {
  const std::vector<Vec<2>> x{Vec<2>(0, 0), Vec<2>(1, 1)};
  const std::vector<Vec<2>> one{Vec<2>(0, 0)};
  CHECK_THROWS_WITH_AS(analysis::displacement_ratio<2>(x, x, Vec<2>::Zero()),
                       doctest::Contains("|tool_displacement| (m) = 0"), Error);
  CHECK_THROWS_WITH_AS(analysis::displacement_ratio<2>(x, one, Vec<2>(1, 0)),
                       doctest::Contains("positions has 2 entries but reference_positions has 1"),
                       Error);
}

}  // namespace
