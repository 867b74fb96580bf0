// The full explicit step at Dim = 3, beside step.bench.cpp's 2D figures: corn filling a
// 0.16 m x 0.16 m x 0.08 m block of 16 x 16 x 8 cells (10 mm, the 2D block's cells and so its
// time step) at 2 x 2 x 2 particles per cell, 16,384 particles against the 2D block's 16,800,
// on a fixed floor between four roller walls, gravity along z (step_support.hpp). The size is
// chosen for the scheduler's 16 x 4 x 4-cell blocks: the particles fill one block along x, four
// along y and two along z, so each of the four occupied colours holds two equal blocks and two
// threads share every colour evenly (2100 cells, 16,800 particles exactly, has no factor of 16
// and so no such split).
// items_per_second is particle-steps per second, as in 2D; divide the 2D figure of the same
// name (step/... for step_3d/...) by it for the cost per particle relative to 2D. A
// Mohr-Coulomb step costs more the more of its points are plastic (in 3D each pays the 3x3
// eigenproblem), and that changes as the block settles under its own weight, so its benchmarks
// time a fixed number of steps from the start and report the mean plastic fraction over them
// (step_support.hpp, plastic_steps).
//   build/release/benchmarks/cosmpm_bench_simulation
//       --benchmark_filter='^step(_3d)?/(linear|quadratic_bspline)/(USL|MUSL/mohr_coulomb)/'
#include <benchmark/benchmark.h>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"
#include "step_support.hpp"

namespace {
using namespace cosmpm;
using Elastic3 = material::LinearElastic<double, 3>;
using MohrCoulomb3 = material::MohrCoulomb<double, 3>;

template <class Kernel, class Scheme, class Model>
void full_step_3d(benchmark::State& state) {
  using Sim = Simulation<3, Kernel, continuum::Classical<Model>, contact::SingleField, Scheme>;
  const grid::Grid<3> grid(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.16, 0.16, 0.12), {16, 16, 12});
  auto sim =
      benchmarks::soil_block<Sim>(grid, Vec<3>(0.16, 0.16, 0.08), static_cast<int>(state.range(0)));
  benchmarks::time_full_steps(state, sim);
}
}  // namespace

BENCHMARK(full_step_3d<shape::Linear, integrator::USL, Elastic3>)
    ->Name("step_3d/linear/USL")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(full_step_3d<shape::QuadraticBSpline, integrator::USL, Elastic3>)
    ->Name("step_3d/quadratic_bspline/USL")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(full_step_3d<shape::Linear, integrator::MUSL, MohrCoulomb3>)
    ->Name("step_3d/linear/MUSL/mohr_coulomb")
    ->Iterations(benchmarks::plastic_steps)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(full_step_3d<shape::QuadraticBSpline, integrator::MUSL, MohrCoulomb3>)
    ->Name("step_3d/quadratic_bspline/MUSL/mohr_coulomb")
    ->Iterations(benchmarks::plastic_steps)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
// The fused schemes (integrator/fused.hpp) on the same block.
BENCHMARK(full_step_3d<shape::Linear, integrator::FusedUSL, Elastic3>)
    ->Name("step_3d/linear/FusedUSL")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
BENCHMARK(full_step_3d<shape::Linear, integrator::FusedMUSL, MohrCoulomb3>)
    ->Name("step_3d/linear/FusedMUSL/mohr_coulomb")
    ->Iterations(benchmarks::plastic_steps)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime();
