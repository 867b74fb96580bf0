// The engine's transfers (shape/separable.hpp, shape/transfer.hpp) against the plain sum over the
// full tensor-product stencil (shape::Stencil, tested on its own in stencil.test.cpp), for every
// kernel in 2D and 3D, at random points and next to every face. The contraction changes only
// the order of the additions: tolerance 1e-12 relative to the sum of the magnitudes of the
// terms (a few dozen roundings of ~1e-16 each, with margin).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "scatter_paths.hpp"
#include "shape_test_support.hpp"

using cosmpm::Index;
using cosmpm::Vec;
using namespace cosmpm::shape;
using namespace shape_test;

namespace {

constexpr double order_tol = 1e-12;

template <int Dim>
Vec<Dim> half_width_for(double value) {
  return Vec<Dim>::Constant(value);
}

// C random values per node, stored as the transfers store them (records of C doubles).
template <int C>
std::vector<double> random_records(Index nodes, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> value(-2.0, 3.0);
  std::vector<double> records(static_cast<std::size_t>(C * nodes));
  for (double& r : records) r = value(rng);
  return records;
}

template <int Dim, class K>
void check_gather_and_scatter() {
  const auto grid = test_grid<Dim>();
  const Vec<Dim> half = half_width_for<Dim>(Case<K>::half_width);
  constexpr int C = 3;
  constexpr int G = 2;  // the first two fields also with gradients
  const auto records = random_records<C>(grid.node_count(), 11);
  for (const Vec<Dim>& x : sample_positions(grid, 5u, 200)) {
    CAPTURE(x.transpose());
    Stencil<Dim, K> full;
    full.compute(grid, x, half);
    SeparableStencil<Dim, K> separable;
    separable.compute(grid, x, half);

    // Gather: value and gradient of each field, against the full sum.
    const auto gathered = gather<C, G>(separable, records.data());
    for (int c = 0; c < C; ++c) {
      double value = 0.0, magnitude = 0.0;
      Vec<Dim> gradient = Vec<Dim>::Zero(), gradient_magnitude = Vec<Dim>::Zero();
      for (int k = 0; k < Stencil<Dim, K>::size; ++k) {
        const double f = records[static_cast<std::size_t>(full.node[k] * C + c)];
        value += full.weight[k] * f;
        magnitude += std::abs(full.weight[k] * f);
        gradient += f * full.gradient[k];
        gradient_magnitude += (f * full.gradient[k]).cwiseAbs();
      }
      CHECK(std::abs(gathered.value[c] - value) <= order_tol * magnitude);
      if (c < G) {
        for (int d = 0; d < Dim; ++d) {
          CHECK(std::abs(gathered.gradient[c][d] - gradient[d]) <=
                order_tol * gradient_magnitude[d]);
        }
      }
    }

    // Scatter: one weighted-only field and two with gradient terms, into zeroed records.
    constexpr int Weighted = 1;
    const std::array<double, C> weighted{0.7, -1.3, 2.1};
    std::array<std::array<double, Dim>, C - Weighted> by_gradient;
    for (int f = 0; f < C - Weighted; ++f) {
      for (int d = 0; d < Dim; ++d) by_gradient[f][d] = 0.3 * (f + 1) - 0.2 * d;
    }
    std::vector<double> scattered(static_cast<std::size_t>(C * grid.node_count()), 0.0);
    scatter<Weighted>(separable, scattered.data(), weighted, by_gradient);
    std::vector<double> expected(scattered.size(), 0.0);
    std::vector<double> magnitude(scattered.size(), 0.0);
    for (int k = 0; k < Stencil<Dim, K>::size; ++k) {
      for (int c = 0; c < C; ++c) {
        const auto slot = static_cast<std::size_t>(full.node[k] * C + c);
        double add = full.weight[k] * weighted[c];
        double size = std::abs(add);
        if (c >= Weighted) {
          for (int d = 0; d < Dim; ++d) {
            add += full.gradient[k][d] * by_gradient[c - Weighted][d];
            size += std::abs(full.gradient[k][d] * by_gradient[c - Weighted][d]);
          }
        }
        expected[slot] += add;
        magnitude[slot] += size;
      }
    }
    for (std::size_t i = 0; i < scattered.size(); ++i) {
      CHECK(std::abs(scattered[i] - expected[i]) <= order_tol * magnitude[i]);
    }
  }
}

}  // namespace

TEST_CASE_TEMPLATE("SeparableStencil: gather and scatter equal the sums over the full stencil (2D)",
                   K, Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  check_gather_and_scatter<2, K>();
}

TEST_CASE_TEMPLATE("SeparableStencil: gather and scatter equal the sums over the full stencil (3D)",
                   K, Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  check_gather_and_scatter<3, K>();
}

TEST_CASE_TEMPLATE("SeparableStencil: the cached cell-unit position reproduces the stencil", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  const auto grid = test_grid<2>();
  const Vec<2> half = half_width_for<2>(Case<K>::half_width);
  for (const Vec<2>& x : sample_positions(grid, 9u, 200)) {
    CAPTURE(x.transpose());
    SeparableStencil<2, K> checked;
    checked.compute(grid, x, half);
    // The cell holds the particle (the last cell for a particle on the far face).
    for (int d = 0; d < 2; ++d) {
      const double xi = (x[d] - grid.origin()[d]) * grid.inverse_cell_size()[d];
      CHECK(checked.cell[d] >= 0);
      CHECK(checked.cell[d] <= grid.cells(d) - 1);
      CHECK(static_cast<double>(checked.cell[d]) <= xi + 1e-9);
      CHECK(xi < static_cast<double>(checked.cell[d] + 1) + 1e-9);
    }
    // The later maps of a step rebuild the stencil from the cached position: bit for bit.
    SeparableStencil<2, K> cached;
    cached.compute_from_cell_units(StencilGrid<2>(grid), checked.position_in_cells, half);
    CHECK(cached.first_node == checked.first_node);
    for (int d = 0; d < 2; ++d) {
      for (int i = 0; i < K::support; ++i) {
        CHECK(cached.w[d][i] == checked.w[d][i]);
        CHECK(cached.dw[d][i] == checked.dw[d][i]);
      }
    }
  }
}

TEST_CASE_TEMPLATE("PackedStencil: each lane gathers what one particle's stencil gathers", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  // The lanes do the arithmetic of the scalar path in the same order; without fused
  // multiply-adds (the default x86-64 target) the results agree bit for bit, with them to
  // a few ulps.
#if defined(__FMA__)
  constexpr double lane_tol = 1e-14;
#else
  constexpr double lane_tol = 0.0;
#endif
  constexpr int W = 2;
  const auto grid = test_grid<2>();
  const StencilGrid<2> stencil_grid(grid);
  const Vec<2> half = half_width_for<2>(Case<K>::half_width);
  constexpr int C = 4;
  const auto records = random_records<C>(grid.node_count(), 3);
  const auto points = sample_positions(grid, 13u, 200);
  for (std::size_t p = 0; p + 1 < points.size(); p += 2) {
    std::array<Vec<2>, W> xi;
    std::array<SeparableStencil<2, K>, W> one;
    for (int l = 0; l < W; ++l) {
      one[l].compute(grid, points[p + l], half);
      xi[l] = one[l].position_in_cells;
    }
    PackedStencil<2, K, W> packed;
    packed.compute_from_cell_units(
        stencil_grid, [&](int l) -> const Vec<2>& { return xi[l]; },
        [&](int) -> const Vec<2>& { return half; });
    const auto lanes = gather<C, 2>(packed, records.data());
    for (int l = 0; l < W; ++l) {
      const auto single = gather<C, 2>(one[l], records.data());
      for (int c = 0; c < C; ++c) {
        CHECK(std::abs(cosmpm::lane<W>(lanes.value[c], l) - single.value[c]) <=
              lane_tol * (1.0 + std::abs(single.value[c])));
      }
      for (int c = 0; c < 2; ++c) {
        for (int d = 0; d < 2; ++d) {
          CHECK(std::abs(cosmpm::lane<W>(lanes.gradient[c][d], l) - single.gradient[c][d]) <=
                lane_tol * (1.0 + std::abs(single.gradient[c][d])));
        }
      }
    }
  }
}

// Records of whole packs (the Cosserat records: 8 doubles in 2D, 16 in 3D; 4 with one
// weighted-only component) take the scatter by node packs: the row arrays' sums bit for bit.
TEST_CASE_TEMPLATE("shape::scatter by node packs equals the row arrays' scatter bit for bit", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  constexpr int P = cosmpm::pack_width;
  if constexpr (P > 1) {
    CHECK(scatter_paths::differing_doubles<2, K, 5, 8>(3) == 0);
    CHECK(scatter_paths::differing_doubles<2, K, 1, 4>(4) == 0);
    CHECK(scatter_paths::differing_doubles<2, K, 4, 4>(5) == 0);
    CHECK(scatter_paths::differing_doubles<3, K, 10, 16>(6) == 0);
    CHECK(scatter_paths::differing_doubles<2, K, P, P>(7) == 0);   // 2D MUSL's remap at P = 2
    CHECK(scatter_paths::differing_doubles<2, K, 9, 12>(8) == 0);  // 2D Cosserat with APIC
  }
}
