// The fused MUSL step of step.bench.cpp's block, its three calls timed apart: where a step's
// time goes, on one thread and on two. The scheme is integrator::FusedMUSL's, written here as a
// user's integrator policy with a clock around each call; Simulation::step runs the rest of the
// step as for any scheme. The figures are counters, in microseconds per step:
//   grid_us          map_or_reuse_and_update_grid (the records taken, the grid update)
//   map_remap_us     map_to_particles_and_remap (the particle pass and the remap's node pass)
//   stress_scatter_us update_stress_and_map_to_grid (stages 4a and 4b, the next step's scatter)
// A separate binary: Google Benchmark's CSV output needs every benchmark of a run to report the
// same counters (benchmarks/simulation/step_support.hpp), and the step benchmarks report others.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>

#include "../simulation/step_support.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;

// Seconds spent in each of the scheme's calls since the last reset.
std::array<double, 3> stage_seconds{};

struct TimedFusedMUSL {
  static constexpr const char* name() { return "fused MUSL, each call timed"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    sim.map_or_reuse_and_update_grid(dt);
    const auto grid = Clock::now();
    sim.map_to_particles_and_remap(dt);
    const auto remap = Clock::now();
    sim.update_stress_and_map_to_grid(dt, sim.nodes().velocity, sim.nodes().spin);
    const auto end = Clock::now();
    const auto seconds = [](auto from, auto to) {
      return std::chrono::duration<double>(to - from).count();
    };
    stage_seconds[0] += seconds(start, grid);
    stage_seconds[1] += seconds(grid, remap);
    stage_seconds[2] += seconds(remap, end);
  }
};

// The block of step.bench.cpp (120 x 50 cells, corn 0.35 m deep, 16,800 particles), the same
// fixed sequence of plastic steps (benchmarks::plastic_steps) as its fused MUSL benchmarks.
template <class Continuum>
void fused_musl_stages(benchmark::State& state) {
  using Sim = Simulation<2, shape::Linear, Continuum, contact::SingleField, TimedFusedMUSL>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.2, 0.5), {120, 50});
  auto sim = benchmarks::soil_block<Sim>(grid, Vec<2>(1.2, 0.35), static_cast<int>(state.range(0)));
  stage_seconds = {};
  benchmarks::time_full_steps(state, sim);
  const double steps = static_cast<double>(state.iterations());
  state.counters["grid_us"] = 1e6 * stage_seconds[0] / steps;
  state.counters["map_remap_us"] = 1e6 * stage_seconds[1] / steps;
  state.counters["stress_scatter_us"] = 1e6 * stage_seconds[2] / steps;
}
}  // namespace

BENCHMARK(fused_musl_stages<continuum::Classical<material::MohrCoulomb<>>>)
    ->Name("stages/linear/FusedMUSL/mohr_coulomb")
    ->Arg(1)
    ->Arg(2)
    ->Iterations(benchmarks::plastic_steps)
    ->UseRealTime();
BENCHMARK(fused_musl_stages<continuum::Cosserat<material::CosseratDruckerPrager<>>>)
    ->Name("stages/linear/FusedMUSL/cosserat_drucker_prager")
    ->Arg(1)
    ->Arg(2)
    ->Iterations(benchmarks::plastic_steps)
    ->UseRealTime();
