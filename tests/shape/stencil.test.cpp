// The tensor-product stencil in 2D (the engine's case) and 3D, on an anisotropic grid with an
// offset origin (cells 15 mm x 14 mm as in the paper's 80 x 50 mesh). Tolerances: 1e-12 on
// dimensionless identities (round-off ~1e-15 with margin); identities in physical units are
// scaled by their natural size (1/h for gradient sums, the grid extent for positions).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape.hpp"
#include "shape_test_support.hpp"

using cosmpm::Index;
using cosmpm::Vec;
using namespace cosmpm::shape;
using namespace shape_test;

namespace {

constexpr double identity_tol = 1e-12;

template <int Dim, class K>
void check_stencil(const cosmpm::grid::Grid<Dim>& grid, const Vec<Dim>& x,
                   const Vec<Dim>& half_width) {
  CAPTURE(x.transpose());
  Stencil<Dim, K> s;
  s.compute(grid, x, half_width);
  const Vec<Dim> h = grid.cell_size();
  const double radius = support_radius<K>(half_width[0]);

  double sum_w = 0.0;
  Vec<Dim> sum_g = Vec<Dim>::Zero();
  Vec<Dim> sum_wx = Vec<Dim>::Zero();
  cosmpm::Mat<Dim> sum_xg = cosmpm::Mat<Dim>::Zero();
  std::set<Index> nodes;
  int nonzero = 0;
  for (int k = 0; k < Stencil<Dim, K>::size; ++k) {
    REQUIRE(s.node[k] >= 0);
    REQUIRE(s.node[k] < grid.node_count());
    nodes.insert(s.node[k]);
    const Vec<Dim> xk = grid.node_position(s.node[k]);
    sum_w += s.weight[k];
    sum_g += s.gradient[k];
    sum_wx += s.weight[k] * xk;
    sum_xg += xk * s.gradient[k].transpose();
    CHECK(s.weight[k] >= -1e-15);
    if (s.weight[k] != 0.0) {
      ++nonzero;
      // Within the kernel's support radius along every axis.
      for (int d = 0; d < Dim; ++d) CHECK(std::abs(xk[d] - x[d]) / h[d] < radius + 1e-9);
    }
  }
  CHECK(nodes.size() == static_cast<std::size_t>(Stencil<Dim, K>::size));  // distinct nodes
  CHECK(nonzero <= Stencil<Dim, K>::size);
  CHECK(std::abs(sum_w - 1.0) < identity_tol);
  // Each gradient is O(1/h); the sum cancels to round-off of that size.
  for (int d = 0; d < Dim; ++d) CHECK(std::abs(sum_g[d]) * h[d] < identity_tol);
  // sum N_k x_k = x: round-off relative to the coordinates' size (~|origin| + extent).
  const double length = grid.origin().cwiseAbs().maxCoeff() + grid.extent().maxCoeff();
  CHECK((sum_wx - x).cwiseAbs().maxCoeff() < identity_tol * length);
  // sum x_k (grad N_k)^T = identity: terms of size length / h.
  const double term = length / h.minCoeff();
  CHECK((sum_xg - cosmpm::Mat<Dim>::Identity()).cwiseAbs().maxCoeff() < identity_tol * term);
}

template <class K>
Vec<2> half_width_2d() {
  return Vec<2>::Constant(Case<K>::half_width);
}

}  // namespace

TEST_CASE("Stencil<2>: bilinear Q4 weights by hand") {
  const auto grid = test_grid<2>();
  // Cell (2, 1), local coordinates (0.25, 0.6): the four Q4 weights are (1 - s)(1 - t),
  // s(1 - t), (1 - s)t, s t with s = 0.25, t = 0.6; gradients dN/dx = dN/ds / hx.
  const Vec<2> x(-0.05 + (2 + 0.25) * 0.015, 0.02 + (1 + 0.6) * 0.014);
  Stencil<2, Linear> s;
  s.compute(grid, x);  // the overload without a half-width, for kernels that ignore it
  const std::array<Index, 4> expected_node{2 + 1 * 9, 3 + 1 * 9, 2 + 2 * 9, 3 + 2 * 9};
  const std::array<double, 4> expected_weight{0.75 * 0.4, 0.25 * 0.4, 0.75 * 0.6, 0.25 * 0.6};
  const std::array<Vec<2>, 4> expected_gradient{
      Vec<2>(-0.4 / 0.015, -0.75 / 0.014), Vec<2>(0.4 / 0.015, -0.25 / 0.014),
      Vec<2>(-0.6 / 0.015, 0.75 / 0.014), Vec<2>(0.6 / 0.015, 0.25 / 0.014)};
  for (int k = 0; k < 4; ++k) {
    CAPTURE(k);
    CHECK(s.node[k] == expected_node[k]);
    CHECK(s.weight[k] == doctest::Approx(expected_weight[k]).epsilon(1e-12));
    CHECK(s.gradient[k][0] == doctest::Approx(expected_gradient[k][0]).epsilon(1e-12));
    CHECK(s.gradient[k][1] == doctest::Approx(expected_gradient[k][1]).epsilon(1e-12));
  }
}

TEST_CASE_TEMPLATE("Stencil<2>: partition of unity, linear reproduction, support, sign", K, Linear,
                   GIMP, QuadraticBSpline, CubicBSpline) {
  const auto grid = test_grid<2>();
  for (const auto& x : sample_positions(grid, 2026u, 1500)) {
    check_stencil<2, K>(grid, x, half_width_2d<K>());
  }
}

TEST_CASE_TEMPLATE("Stencil<2>: weights are the product of the 1D kernels", K, Linear, GIMP,
                   QuadraticBSpline, CubicBSpline) {
  const auto grid = test_grid<2>();
  constexpr int S = K::support;
  for (const auto& x : sample_positions(grid, 11u, 200)) {
    Stencil<2, K> s;
    s.compute(grid, x, half_width_2d<K>());
    const Vec<2> xi = grid.to_cell_units(x);
    std::array<double, S> wx{}, gx{}, wy{}, gy{};
    const Index fx = K::evaluate(xi[0], Case<K>::half_width, grid.nodes(0), wx, gx);
    const Index fy = K::evaluate(xi[1], Case<K>::half_width, grid.nodes(1), wy, gy);
    for (int j = 0; j < S; ++j) {
      for (int i = 0; i < S; ++i) {
        const int k = i + S * j;
        CHECK(s.node[k] == grid.node_index({fx + i, fy + j}));
        CHECK(s.weight[k] == doctest::Approx(wx[i] * wy[j]).epsilon(1e-14));
        CHECK(s.gradient[k][0] * grid.cell_size()[0] ==
              doctest::Approx(gx[i] * wy[j]).epsilon(1e-12).scale(1.0));
        CHECK(s.gradient[k][1] * grid.cell_size()[1] ==
              doctest::Approx(wx[i] * gy[j]).epsilon(1e-12).scale(1.0));
      }
    }
  }
}

TEST_CASE_TEMPLATE("Stencil<2>: physical gradients match central differences", K, Linear, GIMP,
                   QuadraticBSpline, CubicBSpline) {
  // Step 1e-7 cells; as in the 1D test the error is <= 1e-6 in cell units, i.e. 1e-6 / h here.
  const auto grid = test_grid<2>();
  const Vec<2> hw = half_width_2d<K>();
  const Vec<2> h = grid.cell_size();
  auto weight_of = [&](const Vec<2>& x, Index node) {
    Stencil<2, K> s;
    s.compute(grid, x, hw);
    for (int k = 0; k < Stencil<2, K>::size; ++k) {
      if (s.node[k] == node) return s.weight[k];
    }
    return 0.0;
  };
  const Vec<2> lo = grid.origin();
  const Vec<2> hi = grid.origin() + grid.extent();
  for (const auto& x : sample_positions(grid, 3u, 100)) {
    const Vec<2> xi = grid.to_cell_units(x);
    // Linear's gradient jumps across grid lines.
    if (std::is_same_v<K, Linear> && ((xi.array() - xi.array().round()).abs() < 1e-6).any()) {
      continue;
    }
    Stencil<2, K> s;
    s.compute(grid, x, hw);
    for (int k = 0; k < Stencil<2, K>::size; ++k) {
      for (int d = 0; d < 2; ++d) {
        Vec<2> minus = x, plus = x;
        minus[d] = std::max(lo[d], x[d] - 1e-7 * h[d]);
        plus[d] = std::min(hi[d], x[d] + 1e-7 * h[d]);
        // Guard the ulp by which x +- step can round past the faces.
        if (grid.to_cell_units(plus)[d] > static_cast<double>(grid.cells(d))) continue;
        const double difference =
            (weight_of(plus, s.node[k]) - weight_of(minus, s.node[k])) / (plus[d] - minus[d]);
        CAPTURE(x.transpose());
        CAPTURE(k);
        CAPTURE(d);
        CHECK(std::abs(difference - s.gradient[k][d]) * h[d] < 1e-6);
      }
    }
  }
}

TEST_CASE_TEMPLATE("Stencil<3>: compiles and keeps partition of unity and linear reproduction", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  const auto grid = test_grid<3>();
  static_assert(Stencil<3, K>::size == K::support * K::support * K::support);
  for (const auto& x : sample_positions(grid, 42u, 300)) {
    check_stencil<3, K>(grid, x, Vec<3>::Constant(Case<K>::half_width));
  }
}

// Next to the edges and corners of the 3D box: points within one cell of two or three faces
// (each axis independently in its first cell, its last cell or anywhere), where the folded
// ghost nodes of two or three axes meet. Same identities and tolerances as above.
TEST_CASE_TEMPLATE("Stencil<3>: partition of unity and reproduction next to edges and corners", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  const auto grid = test_grid<3>();
  std::mt19937_64 rng(2026u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int near_edge_or_corner = 0;
  for (int i = 0; i < 600; ++i) {
    Vec<3> x;
    int faces = 0;
    for (int d = 0; d < 3; ++d) {
      const int where = static_cast<int>(rng() % 3);  // 0: first cell, 1: last cell, 2: anywhere
      const double cells = static_cast<double>(grid.cells(d));
      const double xi = where == 0 ? unit(rng) : where == 1 ? cells - unit(rng) : unit(rng) * cells;
      faces += where < 2 ? 1 : 0;
      x[d] = grid.origin()[d] + xi * grid.cell_size()[d];
    }
    near_edge_or_corner += faces >= 2 ? 1 : 0;
    check_stencil<3, K>(grid, x, Vec<3>::Constant(Case<K>::half_width));
  }
  // Expected 20/27 of the points (444): 8/27 next to a corner, 12/27 next to an edge only.
  CHECK(near_edge_or_corner > 400);
}

// Only GIMP needs the particle size; the overload without it is not offered for GIMP.
template <class S>
concept ComputesWithoutHalfWidth = requires(S s, const cosmpm::grid::Grid<2>& g, const Vec<2>& x) {
  s.compute(g, x);
};
static_assert(ComputesWithoutHalfWidth<Stencil<2, QuadraticBSpline>>);
static_assert(!ComputesWithoutHalfWidth<Stencil<2, GIMP>>);

TEST_CASE("Stencil: bad input throws cosmpm::Error naming the value and the range") {
  const auto grid = test_grid<2>();
  Stencil<2, QuadraticBSpline> s;
  // Below the grid along y: origin 0.02.
  try {
    s.compute(grid, Vec<2>(0.0, 0.0), Vec<2>::Zero());
    FAIL("a particle below the grid was accepted");
  } catch (const cosmpm::Error& e) {
    const std::string message = e.what();
    CHECK(message.find("QuadraticBSpline") != std::string::npos);
    CHECK(message.find("axis 1") != std::string::npos);
    CHECK(message.find("[0, 5]") != std::string::npos);  // 5 cells: cell units 0 to 5
  }
  // Beyond the right face, and not a number.
  CHECK_THROWS_AS(s.compute(grid, Vec<2>(0.0701, 0.05), Vec<2>::Zero()), cosmpm::Error);
  CHECK_THROWS_AS(s.compute(grid, Vec<2>(std::nan(""), 0.05), Vec<2>::Zero()), cosmpm::Error);
  // The grid faces themselves are inside (origin exactly, and cell units exactly 8 along x).
  CHECK_NOTHROW(s.compute(grid, Vec<2>(-0.05, 0.02), Vec<2>::Zero()));
  CHECK_NOTHROW(s.compute(grid, grid.node_position(grid.node_count() - 1), Vec<2>::Zero()));

  // GIMP's half-width must lie in (0, 1/2] cell units.
  Stencil<2, GIMP> gimp;
  CHECK_NOTHROW(gimp.compute(grid, Vec<2>(0.0, 0.05), Vec<2>(0.5, 0.25)));
  CHECK_THROWS_AS(gimp.compute(grid, Vec<2>(0.0, 0.05), Vec<2>(0.0, 0.25)), cosmpm::Error);
  CHECK_THROWS_AS(gimp.compute(grid, Vec<2>(0.0, 0.05), Vec<2>(0.25, 0.6)), cosmpm::Error);

  // A grid with fewer nodes than the cubic support (2 cells, 3 nodes along y).
  const cosmpm::grid::Grid<2> thin(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.2), {10, 2});
  Stencil<2, CubicBSpline> cubic;
  CHECK_THROWS_AS(cubic.compute(thin, Vec<2>(0.5, 0.1), Vec<2>::Zero()), cosmpm::Error);
  Stencil<2, QuadraticBSpline> quadratic;  // 3 nodes are enough for support 3
  CHECK_NOTHROW(quadratic.compute(thin, Vec<2>(0.5, 0.1), Vec<2>::Zero()));
}
