// 1D properties of every shape kernel, at many points including the grid edges and the nodes.
// Tolerances: 1e-12 for identities that hold exactly in exact arithmetic (a few dozen
// roundings of O(1) numbers, i.e. ~1e-15, with three orders of margin); -1e-15 for
// non-negativity (a folded weight that is exactly zero can round to -1 ulp of its terms).
#include <doctest/doctest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/shape.hpp"
#include "shape_test_support.hpp"

using cosmpm::Index;
using namespace cosmpm::shape;
using namespace shape_test;

namespace {

constexpr double identity_tol = 1e-12;

template <class K>
struct Evaluation {
  Index first;
  std::array<double, K::support> w;
  std::array<double, K::support> g;
};

template <class K>
Evaluation<K> evaluate(double xi, double half_width, Index n) {
  Evaluation<K> e{};
  e.first = K::evaluate(xi, half_width, n, e.w, e.g);
  return e;
}

// Weight (or gradient) of global node k, zero for nodes outside the stencil.
template <class K>
double global_weight(const Evaluation<K>& e, Index k, bool gradient = false) {
  const Index slot = k - e.first;
  if (slot < 0 || slot >= K::support) return 0.0;
  return gradient ? e.g[slot] : e.w[slot];
}

template <class K>
void check_properties(double xi, double half_width, Index n) {
  CAPTURE(xi);
  CAPTURE(n);
  const auto e = evaluate<K>(xi, half_width, n);
  // The stencil lies inside the grid.
  REQUIRE(e.first >= 0);
  REQUIRE(e.first <= n - K::support);
  double sum_w = 0.0, sum_g = 0.0, sum_wx = 0.0, sum_gx = 0.0;
  const double radius = support_radius<K>(half_width);
  for (int k = 0; k < K::support; ++k) {
    const double node = static_cast<double>(e.first + k);
    sum_w += e.w[k];
    sum_g += e.g[k];
    sum_wx += e.w[k] * node;
    sum_gx += e.g[k] * node;
    CHECK(e.w[k] >= -1e-15);
    // Nonzero weight only within the support radius of the node.
    if (e.w[k] != 0.0) CHECK(std::abs(node - xi) < radius + 1e-12);
  }
  CHECK(std::abs(sum_w - 1.0) < identity_tol);   // partition of unity
  CHECK(std::abs(sum_g) < identity_tol);         // zero gradient sum
  CHECK(std::abs(sum_wx - xi) < identity_tol);   // sum N_i x_i = x
  CHECK(std::abs(sum_gx - 1.0) < identity_tol);  // sum dN_i/dx x_i = 1
  // Every grid node agrees with the independent reference basis, so no node of the support
  // is dropped and none outside it is touched.
  for (Index k = 0; k < n; ++k) {
    CAPTURE(k);
    CHECK(std::abs(global_weight(e, k) - reference_basis<K>(k, xi, half_width, n)) < 1e-13);
  }
}

// Central differences of the weight of every node against the analytic gradient. Step 1e-7:
// the truncation error of a C1 piecewise polynomial is <= M * step with M = max |N''| <= 2
// (GIMP with lp = 1/4: 1/(2 lp)), the rounding error ~1e-16 / step = 1e-9; tolerance 1e-6.
template <class K>
void check_gradient_by_differences(double xi, double half_width, Index n) {
  constexpr double step = 1e-7;
  const double last = static_cast<double>(n - 1);
  const double lo = std::max(0.0, xi - step);
  const double hi = std::min(last, xi + step);
  const auto e = evaluate<K>(xi, half_width, n);
  const auto e_lo = evaluate<K>(lo, half_width, n);
  const auto e_hi = evaluate<K>(hi, half_width, n);
  for (Index k = 0; k < n; ++k) {
    CAPTURE(xi);
    CAPTURE(k);
    const double difference = (global_weight(e_hi, k) - global_weight(e_lo, k)) / (hi - lo);
    CHECK(std::abs(difference - global_weight(e, k, true)) < 1e-6);
  }
}

// Linear's gradient jumps at the nodes: differences there are not its derivative.
template <class K>
bool differentiable_at(double xi) {
  if constexpr (std::is_same_v<K, Linear>) {
    return std::abs(xi - std::round(xi)) > 1e-6;
  }
  return true;
}

}  // namespace

TEST_CASE_TEMPLATE("shape kernels: partition of unity, linear reproduction, support, sign", K,
                   Linear, GIMP, QuadraticBSpline, CubicBSpline) {
  const double half_width = Case<K>::half_width;
  // A 9-node axis, and the smallest axis the kernel fits on (node_count == support).
  for (Index n : {Index{9}, Index{K::support}}) {
    for (double xi : sample_points(n, 20261123u)) check_properties<K>(xi, half_width, n);
  }
}

TEST_CASE_TEMPLATE("shape kernels: gradients match central differences of the weights", K, Linear,
                   GIMP, QuadraticBSpline, CubicBSpline) {
  const double half_width = Case<K>::half_width;
  for (Index n : {Index{9}, Index{K::support}}) {
    for (double xi : sample_points(n, 7u, 500)) {
      if (differentiable_at<K>(xi)) check_gradient_by_differences<K>(xi, half_width, n);
    }
  }
}

TEST_CASE("GIMP properties hold for every admissible half-width") {
  // lp = 1/2 is one particle per cell, 1/6 three per cell, 1/8 four per cell.
  for (double lp : {0.5, 1.0 / 6.0, 0.125, 0.01}) {
    CAPTURE(lp);
    for (double xi : sample_points(9, 99u, 500)) check_properties<GIMP>(xi, lp, 9);
  }
}

TEST_CASE("shape kernels: hand-calculated interior values") {
  std::array<double, 2> w2{}, g2{};
  // Linear at xi = 3.3: nodes 3 and 4 with 1 - 0.3 and 0.3, gradients -1 and +1.
  CHECK(Linear::evaluate(3.3, 0.0, Index{9}, w2, g2) == 3);
  CHECK(w2[0] == doctest::Approx(0.7).epsilon(1e-14));
  CHECK(w2[1] == doctest::Approx(0.3).epsilon(1e-14));
  CHECK(g2[0] == -1.0);
  CHECK(g2[1] == 1.0);

  std::array<double, 3> w3{}, g3{};
  // Quadratic B-spline on node 4: N(0) = 3/4, N(1) = (3/2 - 1)^2 / 2 = 1/8.
  CHECK(QuadraticBSpline::evaluate(4.0, 0.0, Index{9}, w3, g3) == 3);
  CHECK(w3[0] == doctest::Approx(0.125).epsilon(1e-14));
  CHECK(w3[1] == doctest::Approx(0.75).epsilon(1e-14));
  CHECK(w3[2] == doctest::Approx(0.125).epsilon(1e-14));
  // N'(1) = -(3/2 - 1) = -1/2 for the node behind, +1/2 ahead.
  CHECK(g3[0] == doctest::Approx(-0.5).epsilon(1e-14));
  CHECK(g3[2] == doctest::Approx(0.5).epsilon(1e-14));

  // GIMP with lp = 1/4 on node 4: centre 1 - lp/2 = 7/8, neighbours (1 + lp - 1)^2/(4 lp) =
  // lp/4 = 1/16.
  CHECK(GIMP::evaluate(4.0, 0.25, Index{9}, w3, g3) == 3);
  CHECK(w3[0] == doctest::Approx(1.0 / 16.0).epsilon(1e-14));
  CHECK(w3[1] == doctest::Approx(7.0 / 8.0).epsilon(1e-14));
  CHECK(w3[2] == doctest::Approx(1.0 / 16.0).epsilon(1e-14));
  // GIMP with lp = 1/4 at xi = 4.5: nodes 4 and 5 at a = 1/2, in the 1 - a branch (lp <= a <
  // 1 - lp), 1/2 each; node 6 at a = 3/2 >= 1 + lp gets 0. Gradients -1 and +1 as for Linear.
  CHECK(GIMP::evaluate(4.5, 0.25, Index{9}, w3, g3) == 4);
  CHECK(w3[0] == doctest::Approx(0.5).epsilon(1e-14));
  CHECK(w3[1] == doctest::Approx(0.5).epsilon(1e-14));
  CHECK(w3[2] == 0.0);
  CHECK(g3[0] == -1.0);
  CHECK(g3[1] == 1.0);

  std::array<double, 4> w4{}, g4{};
  // Cubic B-spline on node 4: N(0) = 2/3, N(1) = 1/6, N(2) = 0.
  CHECK(CubicBSpline::evaluate(4.0, 0.0, Index{9}, w4, g4) == 3);
  CHECK(w4[0] == doctest::Approx(1.0 / 6.0).epsilon(1e-14));
  CHECK(w4[1] == doctest::Approx(2.0 / 3.0).epsilon(1e-14));
  CHECK(w4[2] == doctest::Approx(1.0 / 6.0).epsilon(1e-14));
  CHECK(w4[3] == 0.0);
  // dN/dxi of the node behind (r = +1): -(2 - 1)^2 / 2 = -1/2; ahead +1/2; 0 on the node.
  CHECK(g4[0] == doctest::Approx(-0.5).epsilon(1e-14));
  CHECK(std::abs(g4[1]) < 1e-14);
  CHECK(g4[2] == doctest::Approx(0.5).epsilon(1e-14));
}

TEST_CASE("shape kernels: hand-calculated values at the grid edges") {
  std::array<double, 3> w3{}, g3{};
  // Quadratic at xi = 0.25: unmodified N_-1 = (1/2 - 1/4)^2/2 = 1/32, N_0 = 3/4 - 1/16 = 11/16,
  // N_1 = (1/2 + 1/4)^2/2 = 9/32; folded N_0 + 2 N_-1 = 3/4 and N_1 - N_-1 = 1/4 (linear).
  CHECK(QuadraticBSpline::evaluate(0.25, 0.0, Index{9}, w3, g3) == 0);
  CHECK(w3[0] == doctest::Approx(0.75).epsilon(1e-14));
  CHECK(w3[1] == doctest::Approx(0.25).epsilon(1e-14));
  CHECK(w3[2] == 0.0);
  CHECK(g3[0] == doctest::Approx(-1.0).epsilon(1e-14));
  CHECK(g3[1] == doctest::Approx(1.0).epsilon(1e-14));
  // The same at the upper edge of a 9-node axis, xi = 7.75 (mirror image).
  CHECK(QuadraticBSpline::evaluate(7.75, 0.0, Index{9}, w3, g3) == 6);
  CHECK(w3[0] == 0.0);
  CHECK(w3[1] == doctest::Approx(0.25).epsilon(1e-14));
  CHECK(w3[2] == doctest::Approx(0.75).epsilon(1e-14));

  // GIMP, lp = 1/4, xi = 0.1: the particle domain [-0.15, 0.35] sticks out of the grid; the
  // folded basis is the hat extended linearly, whose average over the domain is its value at
  // the centre: 0.9 and 0.1.
  CHECK(GIMP::evaluate(0.1, 0.25, Index{9}, w3, g3) == 0);
  CHECK(w3[0] == doctest::Approx(0.9).epsilon(1e-14));
  CHECK(w3[1] == doctest::Approx(0.1).epsilon(1e-14));
  CHECK(std::abs(w3[2]) < 1e-15);

  std::array<double, 4> w4{}, g4{};
  // Cubic on the edge node 0: N_0 + 2 N_-1 = 2/3 + 2/6 = 1, N_1 - N_-1 = 1/6 - 1/6 = 0.
  CHECK(CubicBSpline::evaluate(0.0, 0.0, Index{9}, w4, g4) == 0);
  CHECK(w4[0] == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(std::abs(w4[1]) < 1e-15);
  CHECK(w4[2] == 0.0);
  // Cubic on the last node of a 9-node axis: all weight on node 8.
  CHECK(CubicBSpline::evaluate(8.0, 0.0, Index{9}, w4, g4) == 5);
  CHECK(w4[3] == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(std::abs(w4[2]) < 1e-15);
}

TEST_CASE("GIMP tends to Linear as the half-width goes to zero") {
  // |S - hat| <= lp everywhere: in the centre branch the difference is (|r| - lp)^2/(2 lp) <=
  // lp/2, in the outer branch both functions lie in [0, lp]. Away from the nodes (more than lp
  // from every node) both are 1 - |r| exactly, with gradient -sign(r).
  for (double lp : {1e-2, 1e-4, 1e-6}) {
    CAPTURE(lp);
    double max_difference = 0.0;
    for (double xi : sample_points(9, 5u, 1000)) {
      const auto linear = evaluate<Linear>(xi, 0.0, 9);
      const auto gimp = evaluate<GIMP>(xi, lp, 9);
      const bool near_node = std::abs(xi - std::round(xi)) <= lp;
      for (Index k = 0; k < 9; ++k) {
        const double difference = std::abs(global_weight(gimp, k) - global_weight(linear, k));
        max_difference = std::max(max_difference, difference);
        if (!near_node) {
          CHECK(difference < 1e-13);
          CHECK(std::abs(global_weight(gimp, k, true) - global_weight(linear, k, true)) < 1e-12);
        }
      }
    }
    CHECK(max_difference <= lp * (1.0 + 1e-9));
  }
}

TEST_CASE_TEMPLATE("shape kernels: the float instantiation keeps the identities", K, Linear, GIMP,
                   QuadraticBSpline, CubicBSpline) {
  // float round-off: eps = 6e-8 on terms up to |x_i| = 8, a few dozen operations: 1e-5.
  const Index n = 9;
  for (double point : sample_points(n, 13u, 300)) {
    const float xi = static_cast<float>(point);
    std::array<float, K::support> w{}, g{};
    const Index first = K::evaluate(xi, static_cast<float>(Case<K>::half_width), n, w, g);
    REQUIRE(first >= 0);
    REQUIRE(first <= n - K::support);
    float sum_w = 0.0f, sum_g = 0.0f, sum_wx = 0.0f, sum_gx = 0.0f;
    for (int k = 0; k < K::support; ++k) {
      const auto node = static_cast<float>(first + k);
      sum_w += w[k];
      sum_g += g[k];
      sum_wx += w[k] * node;
      sum_gx += g[k] * node;
    }
    CAPTURE(point);
    CHECK(std::abs(sum_w - 1.0f) < 1e-5f);
    CHECK(std::abs(sum_g) < 1e-5f);
    CHECK(std::abs(sum_wx - xi) < 1e-5f);
    CHECK(std::abs(sum_gx - 1.0f) < 1e-5f);
  }
}

TEST_CASE_TEMPLATE("shape kernels: evaluate_lanes gives each lane evaluate's bits", K, Linear,
                   QuadraticBSpline, CubicBSpline) {
  // Each lane does evaluate's arithmetic in the same order (the B-splines' ghosts folded
  // lane by lane), so without fused multiply-adds (the tests' target) the bits agree. Axes of
  // as many nodes as the support (the B-splines fold both ghosts within one or two cells), one
  // more, and 9; the sample points include both edges, the first and last cells and the
  // quadratic's switch points at the cell midpoints.
  // Two lanes whatever pack_width the build chose (SSE2 holds them; a pack_width 1 build
  // never calls evaluate_lanes but users may).
  constexpr int W = 2;
  using P = cosmpm::Pack<W>;
  for (const Index n : {Index{K::support}, Index{K::support + 1}, Index{9}}) {
    const auto points = sample_points(n, 29u, 400);
    for (std::size_t p = 0; p + W <= points.size(); p += W) {
      const P xi =
          cosmpm::make_pack<W>([&](int l) { return points[p + static_cast<std::size_t>(l)]; });
      std::array<P, K::support> w, g;
      K::evaluate_lanes(xi, n, w, g);
      for (int l = 0; l < W; ++l) {
        std::array<double, K::support> w1{}, g1{};
        const double x = cosmpm::lane<W>(xi, l);
        K::evaluate(x, 0.0, n, w1, g1);
        CAPTURE(n);
        CAPTURE(x);
        for (int i = 0; i < K::support; ++i) {
          CHECK(std::bit_cast<std::uint64_t>(cosmpm::lane<W>(w[i], l)) ==
                std::bit_cast<std::uint64_t>(w1[i]));
          CHECK(std::bit_cast<std::uint64_t>(cosmpm::lane<W>(g[i], l)) ==
                std::bit_cast<std::uint64_t>(g1[i]));
        }
      }
    }
  }
}
