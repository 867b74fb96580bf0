// The engine's bookkeeping around its transfers: particles sorted into coloured blocks (kept
// up to date by the engine as particles move, and re-sorted when a user moves them), the
// stencils of a step computed once in map_to_grid, and the grid-to-particle map that runs
// particles in pairs with a scalar remainder. References are sums over shape::Stencil, the
// independently tested full tensor-product stencil; tolerance 1e-12 relative (summation order).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using Sim =
    Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::USL>;

// 40 x 12 cells (3 x 3 particle blocks of 16 x 4 cells), an odd number of particles so the
// paired grid-to-particle loop has a remainder, moving under gravity. `wide` stretches it to
// 200 cells and 5,321 particles, above cosmpm::parallel_threshold, for two-thread runs.
Sim make_block(int threads, bool wide = false) {
  const double length = wide ? 2.0 : 0.4;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(length, 0.12), {wide ? 200 : 40, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.3, -9.81);
  parameters.threads = threads;
  Sim sim(grid, test::Elastic(2e5, 0.25), parameters);
  const auto seeding =
      particles::seed_box(grid, Vec<2>(0.05, 0.0), Vec<2>(wide ? 1.95 : 0.3, 0.07), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  sim.add_particles({Vec<2>(0.2001, 0.0613)}, seeding.volume, 1500.0, seeding.half_width);
  REQUIRE(sim.particles().size() % 2 == 1);
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

// Node masses sum_p m_p N_n(x_p) with the full stencil.
std::vector<double> expected_node_mass(const Sim& sim) {
  std::vector<double> mass(static_cast<std::size_t>(sim.grid().node_count()), 0.0);
  const auto& x = sim.particles().get<particles::field::Position<2>>();
  const auto& m = sim.particles().get<particles::field::Mass>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    shape::Stencil<2, shape::Linear> s;
    s.compute(sim.grid(), x[p]);
    for (int k = 0; k < s.size; ++k)
      mass[static_cast<std::size_t>(s.node[k])] += s.weight[k] * m[p];
  }
  return mass;
}

void check_node_mass(const Sim& sim) {
  const auto expected = expected_node_mass(sim);
  for (Index n = 0; n < sim.grid().node_count(); ++n) {
    CAPTURE(n);
    CHECK(std::abs(sim.nodes().mass[n] - expected[static_cast<std::size_t>(n)]) <=
          1e-12 * std::abs(expected[static_cast<std::size_t>(n)]));
  }
}

// Moves particles by hand across block boundaries: one to the far corner block, every third
// by 1.7 cells along x and 1.2 cells up.
void move_by_hand(Sim& sim) {
  auto& x = sim.particles().get<particles::field::Position<2>>();
  x[0] = Vec<2>(sim.grid().extent()[0] - 0.015, 0.105);
  for (Index p = 1; p < sim.particles().size(); p += 3) x[p] += Vec<2>(0.017, 0.012);
}

}  // namespace

TEST_CASE("blocks: particles moved by the engine or by hand are scattered where they are") {
  Sim sim = make_block(0);
  const double dt = sim.time_step();
  for (int i = 0; i < 200; ++i) sim.step(dt);
  sim.map_to_grid(true);
  check_node_mass(sim);  // after 200 steps of the engine moving the particles
  move_by_hand(sim);
  sim.map_to_grid(true);
  check_node_mass(sim);
  sim.step(dt);  // the step runs on with the re-sorted blocks
}

TEST_CASE("blocks: a re-sort after moves by hand does not depend on the thread count") {
  Sim one = make_block(1, true);
  Sim two = make_block(2, true);
  REQUIRE(one.particles().size() >= cosmpm::parallel_threshold);
  const double dt = one.time_step();
  for (int i = 0; i < 50; ++i) {
    one.step(dt);
    two.step(dt);
    if (i == 20) {
      move_by_hand(one);
      move_by_hand(two);
    }
  }
  // The two-thread run ran its coloured scatter on two threads (OpenMP builds).
  CHECK(one.last_team_size() == 1);
#if defined(_OPENMP)
  CHECK(two.last_team_size() == 2);
#endif
  const auto& x1 = one.particles().get<particles::field::Position<2>>();
  const auto& x2 = two.particles().get<particles::field::Position<2>>();
  const auto& s1 = one.particles().get<particles::field::Stress<test::Elastic>>();
  const auto& s2 = two.particles().get<particles::field::Stress<test::Elastic>>();
  bool identical = true;
  for (Index p = 0; p < one.particles().size(); ++p) {
    identical = identical && x1[p] == x2[p] && s1[p] == s2[p];
  }
  CHECK(identical);
}

TEST_CASE("blocks: every particle, paired or not, moves with the grid velocity at its stencil") {
  Sim sim = make_block(0);
  const double dt = sim.time_step();
  for (int i = 0; i < 20; ++i) sim.step(dt);
  const auto start = sim.particles().get<particles::field::Position<2>>();
  sim.map_to_grid(true);
  sim.update_grid(dt);
  sim.map_to_particles(dt, true);
  const auto& x = sim.particles().get<particles::field::Position<2>>();
  const auto& L = sim.particles().get<particles::field::VelocityGradient<2>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    CAPTURE(p);
    shape::Stencil<2, shape::Linear> s;
    s.compute(sim.grid(), start[p]);
    Vec<2> v_grid = Vec<2>::Zero(), v_size = Vec<2>::Zero();
    Mat<2> gradient = Mat<2>::Zero(), gradient_size = Mat<2>::Zero();
    for (int k = 0; k < s.size; ++k) {
      const Vec<2>& v_node = sim.nodes().velocity[s.node[k]];
      v_grid += s.weight[k] * v_node;
      v_size += (s.weight[k] * v_node).cwiseAbs();
      gradient += v_node * s.gradient[k].transpose();
      gradient_size += (v_node * s.gradient[k].transpose()).cwiseAbs();
    }
    // x_new - x_start = dt v_grid; the difference carries the round-off of x itself.
    const Vec<2> moved = x[p] - start[p];
    for (int d = 0; d < 2; ++d) {
      CHECK(std::abs(moved[d] - dt * v_grid[d]) <= 1e-12 * dt * v_size[d] + 1e-15 * 0.4);
    }
    CHECK(((L[p] - gradient).array().abs() <= 1e-12 * gradient_size.array()).all());
  }
}

TEST_CASE("blocks: the later maps of a step need map_to_grid first") {
  Sim sim = make_block(1);
  const double dt = sim.time_step();
  CHECK_THROWS_AS(sim.map_to_particles(dt), Error);
  CHECK_THROWS_WITH_AS(sim.velocity_gradient_from_grid(sim.nodes().velocity),
                       doctest::Contains("call map_to_grid first"), Error);
}

TEST_CASE("blocks: a particle moved outside the grid by hand is an error, also on two threads") {
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    Sim sim = make_block(threads);
    const double dt = sim.time_step();
    sim.step(dt);
    sim.particles().get<particles::field::Position<2>>()[7] = Vec<2>(0.1, -0.01);
    // Thrown after the parallel scatter, not from inside it (which would end the program).
    CHECK_THROWS_WITH_AS(sim.step(dt), doctest::Contains("outside the valid range"), Error);
  }
}

TEST_CASE("blocks: two threads share every colour's particles equally, each in whole blocks") {
  // 200 x 12 cells: 13 x 3 blocks of 16 x 4 cells. Particles dense on the left (a 6 x 6
  // lattice per cell over the first 40 cells) and sparse beyond (one per cell), so equal runs
  // of blocks would hold very different numbers of particles.
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(2.0, 0.12), {200, 12});
  std::vector<Vec<2>> x;
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 12; ++j) {
      const int per_axis = i < 40 ? 6 : 1;
      for (int a = 0; a < per_axis; ++a) {
        for (int b = 0; b < per_axis; ++b) {
          x.emplace_back(0.01 * (i + (a + 0.5) / per_axis), 0.01 * (j + (b + 0.5) / per_axis));
        }
      }
    }
  }
  const auto count = static_cast<Index>(x.size());
  REQUIRE(count >= cosmpm::parallel_threshold);
  BlockScheduler<2, shape::Linear> blocks(grid);
  blocks.bucket(x, count, shape::StencilGrid<2>(grid));
  std::vector<int> visits(x.size(), 0), thread(x.size(), -1);
  blocks.for_each_coloured(2, count, [&](Index p) {
    ++visits[static_cast<std::size_t>(p)];
    thread[static_cast<std::size_t>(p)] = cosmpm::current_thread();
  });
  for (const int v : visits) REQUIRE(v == 1);
  // Per colour (block parities) and thread: particles, and the blocks each thread ran.
  const auto block_of = [](const Vec<2>& p) {
    return std::array<int, 2>{static_cast<int>(p[0] / 0.16), static_cast<int>(p[1] / 0.04)};
  };
  std::array<std::array<Index, 2>, 4> particles{};
  std::array<std::array<std::vector<int>, 2>, 4> block_index;  // the blocks a thread ran
  std::array<Index, 4> largest{};                              // the largest block of each colour
  std::vector<Index> block_count(13 * 3, 0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    const auto [bx, by] = block_of(x[p]);
    ++block_count[static_cast<std::size_t>(by * 13 + bx)];
  }
  for (std::size_t p = 0; p < x.size(); ++p) {
    const auto [bx, by] = block_of(x[p]);
    const int colour = (bx & 1) | ((by & 1) << 1);
    const auto c = static_cast<std::size_t>(colour);
    const auto t = static_cast<std::size_t>(thread[p] < 0 ? 0 : thread[p]);
    ++particles[c][t];
    block_index[c][t].push_back(by * 13 + bx);
    largest[c] = std::max(largest[c], block_count[static_cast<std::size_t>(by * 13 + bx)]);
  }
#if defined(_OPENMP)
  CHECK(blocks.last_team_size() == 2);
  for (std::size_t c = 0; c < 4; ++c) {
    CAPTURE(c);
    // The cut falls at a block boundary: the shares differ by at most one block.
    CHECK(std::abs(particles[c][0] - particles[c][1]) <= largest[c]);
    // Thread 0 runs the colour's first blocks (in block order), thread 1 the rest.
    const auto [low0, high0] =
        std::minmax_element(block_index[c][0].begin(), block_index[c][0].end());
    const auto [low1, high1] =
        std::minmax_element(block_index[c][1].begin(), block_index[c][1].end());
    REQUIRE(!block_index[c][0].empty());
    REQUIRE(!block_index[c][1].empty());
    CHECK(*high0 < *low1);
    (void)low0;
    (void)high1;
  }
#endif
}
