#pragma once
// The scatter by node packs (shape::detail::scatter_node_packs, for records of whole packs)
// against the row arrays' scatter (shape::detail::scatter_rows), bit for bit: the same
// operations per lane, so the same sums, at the instruction set the including test is built
// for (portable in tests/shape, the host's in tests/native, where GCC fuses multiply-adds).
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/transfer.hpp"

namespace scatter_paths {

// The number of record doubles, over all points, where the two paths differ in any bit.
// Records start as random values with every third one +0 (as a zeroed record does); each
// point's weighted values and gradient factors are random.
template <int Dim, class K, int Weighted, std::size_t C>
int differing_doubles(unsigned seed) {
  std::array<cosmpm::Index, Dim> cells;
  cells.fill(6);
  const cosmpm::grid::Grid<Dim> grid(cosmpm::Vec<Dim>::Zero(), cosmpm::Vec<Dim>::Constant(0.6),
                                     cells);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> value(-2.0, 3.0), inside(0.22, 0.38);
  int differing = 0;
  for (int point = 0; point < 200; ++point) {
    cosmpm::Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = inside(rng);
    cosmpm::shape::SeparableStencil<Dim, K> stencil;
    stencil.compute(grid, x, cosmpm::Vec<Dim>::Constant(0.25));
    std::array<double, C> weighted;
    for (double& w : weighted) w = value(rng);
    std::array<std::array<double, Dim>, C - Weighted> by_gradient;
    for (auto& factors : by_gradient) {
      for (double& f : factors) f = value(rng);
    }
    std::vector<double> rows(C * static_cast<std::size_t>(grid.node_count()));
    for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i % 3 == 0 ? 0.0 : value(rng);
    std::vector<double> packs = rows;
    cosmpm::shape::detail::scatter_rows<Weighted>(stencil, rows.data(), weighted, by_gradient);
    cosmpm::shape::detail::scatter_node_packs<Weighted>(stencil, packs.data(), weighted,
                                                        by_gradient);
    for (std::size_t i = 0; i < rows.size(); ++i)
      differing += std::memcmp(&rows[i], &packs[i], sizeof(double)) != 0;
  }
  return differing;
}

}  // namespace scatter_paths
