#pragma once
// The scatter of a pack of particles (shape::scatter_lanes) against the same particles
// scattered one after the other (shape::scatter at each lane's stencil), bit for bit: per lane
// the same operations, and every record takes the lanes' terms in lane order. The lanes lie in
// one or two neighbouring cells, so their stencils share nodes, as a pack of consecutive
// particles' do. Built at the including test's instruction set (portable in tests/shape, the
// host's in tests/native).
#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"

namespace scatter_lanes_paths {

// The number of record doubles, over all packs, where the two paths differ in any bit. Records
// start as random values with every third one +0 (as a zeroed record does); each lane's
// weighted values and gradient factors are random.
template <int Dim, class K, int Weighted, std::size_t C>
int differing_doubles(unsigned seed) {
  constexpr int W = cosmpm::pack_width;
  using P = cosmpm::Pack<W>;
  std::array<cosmpm::Index, Dim> cells;
  cells.fill(6);
  const cosmpm::grid::Grid<Dim> grid(cosmpm::Vec<Dim>::Zero(), cosmpm::Vec<Dim>::Constant(0.6),
                                     cells);
  const cosmpm::shape::StencilGrid<Dim> stencil_grid(grid);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> value(-2.0, 3.0), in_cell(0.0, 0.06), step(0.0, 0.04);
  int differing = 0;
  for (int pack = 0; pack < 200; ++pack) {
    // Lanes in cells 2 and 3 of each axis (cell size 0.1), each a short step on from the last.
    std::array<cosmpm::Vec<Dim>, W> x;
    for (int d = 0; d < Dim; ++d) x[0][d] = 0.22 + in_cell(rng);
    for (int l = 1; l < W; ++l) {
      for (int d = 0; d < Dim; ++d) x[l][d] = x[l - 1][d] + step(rng);
    }
    const cosmpm::Vec<Dim> half = cosmpm::Vec<Dim>::Zero();
    std::array<cosmpm::shape::SeparableStencil<Dim, K>, W> one;
    for (int l = 0; l < W; ++l) one[l].compute(stencil_grid, x[l], half);
    cosmpm::shape::PackedStencil<Dim, K, W> packed;
    packed.compute_from_cell_units(
        stencil_grid, [&](int l) -> const cosmpm::Vec<Dim>& { return one[l].position_in_cells; },
        [&](int) -> const cosmpm::Vec<Dim>& { return half; });

    std::array<std::array<double, C>, W> weighted;
    std::array<std::array<std::array<double, Dim>, C - Weighted>, W> by_gradient;
    std::array<P, C> weighted_packs;
    std::array<std::array<P, Dim>, C - Weighted> by_gradient_packs;
    for (int l = 0; l < W; ++l) {
      for (double& w : weighted[l]) w = value(rng);
      for (auto& factors : by_gradient[l]) {
        for (double& f : factors) f = value(rng);
      }
    }
    for (std::size_t c = 0; c < C; ++c) {
      cosmpm::gather_lanes(weighted_packs[c], [&](int l) { return weighted[l][c]; });
    }
    for (std::size_t f = 0; f < C - Weighted; ++f) {
      for (int d = 0; d < Dim; ++d) {
        cosmpm::gather_lanes(by_gradient_packs[f][d], [&](int l) { return by_gradient[l][f][d]; });
      }
    }

    std::vector<double> by_particle(C * static_cast<std::size_t>(grid.node_count()));
    for (std::size_t i = 0; i < by_particle.size(); ++i)
      by_particle[i] = i % 3 == 0 ? 0.0 : value(rng);
    std::vector<double> by_pack = by_particle;
    for (int l = 0; l < W; ++l) {
      cosmpm::shape::scatter<Weighted>(packed.lane(l), by_particle.data(), weighted[l],
                                       by_gradient[l]);
    }
    cosmpm::shape::scatter_lanes<Weighted>(packed, by_pack.data(), weighted_packs,
                                           by_gradient_packs);
    for (std::size_t i = 0; i < by_particle.size(); ++i)
      differing += std::memcmp(&by_particle[i], &by_pack[i], sizeof(double)) != 0;
  }
  return differing;
}

}  // namespace scatter_lanes_paths
