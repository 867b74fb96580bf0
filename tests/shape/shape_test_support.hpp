#pragma once
// Shared pieces of the shape tests: the kernels under test with the half-width each is run
// with, an independent reference basis (Cox-de Boor recursion and the exact GIMP integral,
// not the closed forms the kernels use), and the sample points.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape.hpp"

namespace shape_test {

using cosmpm::Index;

// A kernel with the half-width (cell units) it is tested with and its support radius in cells:
// a node farther than `radius` from the particle must get exactly zero weight.
template <class K>
struct Case {
  using Kernel = K;
  static constexpr double half_width = 0.0;  // ignored by the splines
};
template <>
struct Case<cosmpm::shape::GIMP> {
  using Kernel = cosmpm::shape::GIMP;
  static constexpr double half_width = 0.25;  // 2 x 2 particles per cell
};

template <class K>
constexpr int spline_degree() {
  if constexpr (std::is_same_v<K, cosmpm::shape::Linear>) return 1;
  if constexpr (std::is_same_v<K, cosmpm::shape::QuadraticBSpline>) return 2;
  if constexpr (std::is_same_v<K, cosmpm::shape::CubicBSpline>) return 3;
  return -1;  // GIMP
}

// Support radius in cells: half the B-spline's knot span (p + 1) / 2, or 1 + lp for GIMP.
template <class K>
double support_radius(double half_width) {
  constexpr int p = spline_degree<K>();
  if constexpr (p < 0) return 1.0 + half_width;
  return 0.5 * (p + 1);
}

// Cox-de Boor recursion for the uniform B-spline of degree p with knots t0, t0 + 1, ...,
// t0 + p + 1 (half-open knot intervals).
inline double cox_de_boor(double x, int p, double t0) {
  if (p == 0) return (t0 <= x && x < t0 + 1.0) ? 1.0 : 0.0;
  return (x - t0) / p * cox_de_boor(x, p - 1, t0) +
         (t0 + p + 1.0 - x) / p * cox_de_boor(x, p - 1, t0 + 1.0);
}

// Antiderivative of the hat function 1 - |r| (zero left of -1, one right of +1).
inline double hat_integral(double r) {
  if (r <= -1.0) return 0.0;
  if (r <= 0.0) return 0.5 * (1.0 + r) * (1.0 + r);
  if (r <= 1.0) return 1.0 - 0.5 * (1.0 - r) * (1.0 - r);
  return 1.0;
}

// The unmodified basis function of node k (k may be a ghost node outside the grid).
template <class K>
double unmodified_basis(Index k, double xi, double half_width) {
  const double r = xi - static_cast<double>(k);
  constexpr int p = spline_degree<K>();
  if constexpr (p < 0) {
    // uGIMP: the hat averaged over the particle domain [r - lp, r + lp].
    return (hat_integral(r + half_width) - hat_integral(r - half_width)) / (2.0 * half_width);
  } else {
    // Centred on the node: the knots span [k - (p+1)/2, k + (p+1)/2].
    return cox_de_boor(xi, p, static_cast<double>(k) - 0.5 * (p + 1));
  }
}

// The boundary-modified basis of node k in [0, n): the ghost nodes -1 and n are folded by
// linear extrapolation, v_-1 = 2 v_0 - v_1 and v_n = 2 v_{n-1} - v_{n-2}.
template <class K>
double reference_basis(Index k, double xi, double half_width, Index n) {
  const double lower_ghost = unmodified_basis<K>(-1, xi, half_width);
  const double upper_ghost = unmodified_basis<K>(n, xi, half_width);
  double value = unmodified_basis<K>(k, xi, half_width);
  if (k == 0) value += 2.0 * lower_ghost;
  if (k == 1) value -= lower_ghost;
  if (k == n - 1) value += 2.0 * upper_ghost;
  if (k == n - 2) value -= upper_ghost;
  return value;
}

// Sample points in cell units on an axis with n nodes: random points (fixed seed) over the
// axis, random points within one cell of either edge, every node exactly, and points a few
// ulps inside the edges.
inline std::vector<double> sample_points(Index n, unsigned seed, int random_count = 2000) {
  const double last = static_cast<double>(n - 1);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> anywhere(0.0, last);
  std::uniform_real_distribution<double> first_cell(0.0, 1.0);
  std::vector<double> points;
  for (int i = 0; i < random_count; ++i) points.push_back(anywhere(rng));
  for (int i = 0; i < random_count / 4; ++i) {
    points.push_back(first_cell(rng));
    points.push_back(last - first_cell(rng));
  }
  for (Index k = 0; k < n; ++k) points.push_back(static_cast<double>(k));
  for (double tiny : {1e-15, 1e-12, 1e-9}) {
    points.push_back(tiny);
    points.push_back(last - tiny);
  }
  // Cell midpoints and the quadratic/GIMP switch points, where the stencil moves.
  for (Index k = 0; k + 1 < n; ++k) points.push_back(static_cast<double>(k) + 0.5);
  return points;
}

// The grids of the stencil tests: anisotropic cells with an offset origin, so positions and
// cell units differ (2D: 15 mm x 14 mm cells as in the paper's 80 x 50 mesh).
template <int Dim>
cosmpm::grid::Grid<Dim> test_grid();

template <>
inline cosmpm::grid::Grid<2> test_grid<2>() {
  // 8 x 5 cells of 15 mm x 14 mm, origin off zero so positions and cell units differ.
  return {cosmpm::Vec<2>(-0.05, 0.02), cosmpm::Vec<2>(0.12, 0.07), {8, 5}};
}

template <>
inline cosmpm::grid::Grid<3> test_grid<3>() {
  return {cosmpm::Vec<3>(0.1, -0.2, 0.3), cosmpm::Vec<3>(0.04, 0.06, 0.05), {4, 5, 4}};
}

// Random points in the grid box, points within one cell of every face, every node (corners
// included) and the box corners; fixed seed.
template <int Dim>
std::vector<cosmpm::Vec<Dim>> sample_positions(const cosmpm::grid::Grid<Dim>& grid, unsigned seed,
                                               int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<cosmpm::Vec<Dim>> points;
  const cosmpm::Vec<Dim> extent = grid.extent();
  for (int i = 0; i < count; ++i) {
    cosmpm::Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = grid.origin()[d] + unit(rng) * extent[d];
    points.push_back(x);
    // The same point pushed into the first or last cell of one axis.
    const int axis = i % Dim;
    cosmpm::Vec<Dim> near_face = x;
    const double offset = unit(rng) * grid.cell_size()[axis];
    near_face[axis] =
        (i % 2 == 0) ? grid.origin()[axis] + offset : grid.origin()[axis] + extent[axis] - offset;
    points.push_back(near_face);
  }
  for (Index k = 0; k < grid.node_count(); ++k) points.push_back(grid.node_position(k));
  return points;
}

}  // namespace shape_test
