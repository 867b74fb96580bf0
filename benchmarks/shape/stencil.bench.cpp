// Cost of one 2D stencil evaluation (node indices, weights, physical gradients) per kernel,
// over the reference particle set: 120 x 35 cells of 10 mm, 2 x 2 particles per cell
// (16,800 particles), visited in seeding order as the transfers do. time_per_stencil is the
// figure to quote; items_per_second counts stencils.
#include <benchmark/benchmark.h>

#include <vector>

#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape.hpp"

namespace {
using namespace cosmpm;

struct ParticleSet {
  grid::Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(1.2, 0.35), {120, 35}};
  std::vector<Vec<2>> position;
  Vec<2> half_width = Vec<2>::Constant(0.25);  // cell units, 2 x 2 per cell

  ParticleSet() {
    const Vec<2> h = grid.cell_size();
    for (Index j = 0; j < grid.cells(1); ++j) {
      for (Index i = 0; i < grid.cells(0); ++i) {
        for (int b = 0; b < 2; ++b) {
          for (int a = 0; a < 2; ++a) {
            position.emplace_back((static_cast<double>(i) + 0.25 + 0.5 * a) * h[0],
                                  (static_cast<double>(j) + 0.25 + 0.5 * b) * h[1]);
          }
        }
      }
    }
  }
};

template <class K>
void stencil_2d(benchmark::State& state) {
  const ParticleSet set;
  shape::Stencil<2, K> s;
  for (auto _ : state) {
    for (const auto& x : set.position) {
      s.compute(set.grid, x, set.half_width);
      benchmark::DoNotOptimize(s);
    }
  }
  const auto count = static_cast<double>(set.position.size());
  state.counters["items_per_second"] =
      benchmark::Counter(count, benchmark::Counter::kIsIterationInvariantRate);
  // The inverted rate: seconds per stencil (the console shows it as e.g. "5.1ns").
  state.counters["time_per_stencil"] = benchmark::Counter(
      count, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

BENCHMARK(stencil_2d<shape::Linear>)->Name("stencil_2d/Linear");
BENCHMARK(stencil_2d<shape::GIMP>)->Name("stencil_2d/GIMP");
BENCHMARK(stencil_2d<shape::QuadraticBSpline>)->Name("stencil_2d/QuadraticBSpline");
BENCHMARK(stencil_2d<shape::CubicBSpline>)->Name("stencil_2d/CubicBSpline");

}  // namespace
