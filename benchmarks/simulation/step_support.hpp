#pragma once
// What the step benchmarks of step.bench.cpp (2D) and step_3d.bench.cpp (3D) share: the
// paper's corn as each model and continuum, the soil block (a box of particles on a fixed floor
// between roller walls, gravity along the last axis) and the timed loop of full steps with its
// counters. items_per_second is particle-steps per second.
#include <benchmark/benchmark.h>

#include <atomic>
#include <optional>
#include <type_traits>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/simulation/parameters.hpp"

namespace cosmpm::benchmarks {

inline constexpr double corn_density = 778.0;  // kg/m^3

// The soil models of the flat blade, with the paper's corn (Table 1), in plane strain or 3D.
template <int Dim>
material::LinearElastic<double, Dim> make_model(
    std::type_identity<material::LinearElastic<double, Dim>>) {
  return material::LinearElastic<double, Dim>(2.76e6, 0.2);
}
template <int Dim>
material::MohrCoulomb<double, Dim> make_model(
    std::type_identity<material::MohrCoulomb<double, Dim>>) {
  return material::MohrCoulomb<double, Dim>(2.76e6, 0.2, 26.0, 2.0);
}
inline material::CosseratElastic<> make_model(std::type_identity<material::CosseratElastic<>>) {
  return material::CosseratElastic<>(2.76e6, 0.2, 2.3e6, 0.01);
}
inline material::CosseratDruckerPrager<> make_model(
    std::type_identity<material::CosseratDruckerPrager<>>) {
  return material::CosseratDruckerPrager<>(2.76e6, 0.2, 2.3e6, 0.01, 26.0, 2.0);
}

// The continuum of those models (Cosserat: the paper's micro-inertia, times
// micro_inertia_scale; a classical continuum ignores the scale).
template <class Continuum>
Continuum make_continuum(double micro_inertia_scale = 1.0) {
  using Model = typename Continuum::model_type;
  if constexpr (Continuum::is_cosserat) {
    return Continuum(make_model(std::type_identity<Model>{}),
                     {.micro_inertia = 12.5e-6, .micro_inertia_scale = micro_inertia_scale});
  } else {
    (void)micro_inertia_scale;
    return Continuum(make_model(std::type_identity<Model>{}));
  }
}

// Corn filling the box [0, fill] of `grid` (2 particles per cell and axis), gravity along the
// last axis, the floor (lower face of the last axis) fixed, every side face a roller wall.
template <class Sim>
Sim soil_block(const grid::Grid<Sim::dim>& grid, const Vec<Sim::dim>& fill, int threads,
               std::optional<double> flip_fraction = std::nullopt,
               double micro_inertia_scale = 1.0) {
  constexpr int dim = Sim::dim;
  SimulationParameters<dim> parameters;
  parameters.gravity = Vec<dim>::Zero();
  parameters.gravity[dim - 1] = -9.81;
  parameters.threads = threads;
  parameters.flip_fraction = flip_fraction;
  Sim sim(grid, make_continuum<typename Sim::continuum_type>(micro_inertia_scale), parameters);
  const Vec<dim> origin = Vec<dim>::Zero();
  const auto seeding = particles::seed_box(grid, origin, fill, 2);
  sim.add_particles(seeding.positions, seeding.volume, corn_density, seeding.half_width);
  using Faces = grid::BoundaryConditions<dim>;
  sim.boundary_conditions().set(Faces::face(dim - 1, false), grid::BoundaryKind::fixed);
  for (int axis = 0; axis < dim - 1; ++axis) {
    sim.boundary_conditions().set(Faces::face(axis, false), grid::BoundaryKind::roller);
    sim.boundary_conditions().set(Faces::face(axis, true), grid::BoundaryKind::roller);
  }
  return sim;
}

// Whether a model's points can return plastically (its state is a PlasticState).
template <class Model>
inline constexpr bool has_plastic_state =
    std::is_same_v<typename Model::state_type, material::PlasticState>;

// The fraction of the particles whose last update was plastic. Counted in the particle
// passes' static shares: one thread reading every state after each step pulled the other
// thread's half of the states into its cache, and moving them back cost the timed two-thread
// step about 10 % (docs/performance.md, "The benchmark's own count").
template <class Sim>
double plastic_fraction(const Sim& sim) {
  using Model = typename Sim::model_type;
  if constexpr (has_plastic_state<Model>) {
    const auto& states = sim.particles().template get<particles::field::MaterialState<Model>>();
    const Index count = static_cast<Index>(states.size());
    // On the engine's team, not an OpenMP one: OpenMP's threads would spin on after the count
    // and take the core from the team's helper in the next timed step.
    std::atomic<Index> plastic{0};
    parallel_region(sim.threads(), count, [&] {
      const Share share = static_share(count);
      Index mine = 0;
      for (Index i = share.first; i < share.last; ++i) {
        mine += states[static_cast<std::size_t>(i)].plastic ? 1 : 0;
      }
      plastic.fetch_add(mine, std::memory_order_relaxed);
    });
    return static_cast<double>(plastic.load()) / static_cast<double>(count);
  } else {
    return 0.0;
  }
}

// items_per_second (particle-steps per second, from the timed loop's iterations) and the
// counters: the particles, the threads and the fraction of plastic points (`plastic`; 0 for
// an elastic model). Every benchmark sets the same counters: Google Benchmark's CSV output,
// which scripts/bench_interleaved.sh reads, aborts when a run has a counter that the first run
// reported lacked, and random interleaving puts any one first.
template <class Sim>
void report_counters(benchmark::State& state, const Sim& sim, double plastic) {
  const Index count = sim.particles().size();
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["particles"] = static_cast<double>(count);
  state.counters["threads"] = static_cast<double>(sim.threads());
  state.counters["plastic_fraction"] = plastic;
}
// The same with the last step's plastic fraction.
template <class Sim>
void report_counters(benchmark::State& state, const Sim& sim) {
  report_counters(state, sim, plastic_fraction(sim));
}

// How many steps a plastic model's step benchmark times, all from the soil block's start.
// Why a fixed number: a plastic step costs more the more of its points return, and in the
// block that fraction swings between 0 and 1 from step to step as stress waves cross it
// (layer by layer: the block is uniform along x). Its mean over the first n steps falls with
// n: Mohr-Coulomb 0.97 over 100 steps, 0.25 over 1000, 0.10 over 3000; Cosserat
// Drucker-Prager 0.96, 0.47, 0.27 (2D, linear, MUSL). A benchmark that ran as many steps as
// fit into its minimum time timed a mix that depended on its own speed: a faster build ran
// more steps, fewer of them plastic, and looked faster still. Registered with
// ->Iterations(plastic_steps), every build times the same steps, and plastic_fraction is the
// mean over them.
inline constexpr int plastic_steps = 1000;

// Full steps of the stable size, timed, and their counters. A plastic model's benchmark must
// be registered with ->Iterations(plastic_steps) (see there); the count of plastic points after
// each step is taken with the timer paused (about a microsecond against a step of 0.5 ms or
// more).
template <class Sim>
void time_full_steps(benchmark::State& state, Sim& sim) {
  const double dt = sim.time_step();
  if constexpr (has_plastic_state<typename Sim::model_type>) {
    if (state.max_iterations != plastic_steps) {
      state.SkipWithError(
          "a plastic model's step benchmark times a fixed sequence: register it "
          "with ->Iterations(benchmarks::plastic_steps)");
      return;
    }
    double plastic = 0.0;
    for (auto _ : state) {
      sim.step(dt);
      state.PauseTiming();
      plastic += plastic_fraction(sim);
      state.ResumeTiming();
    }
    report_counters(state, sim, plastic / static_cast<double>(state.iterations()));
  } else {
    for (auto _ : state) sim.step(dt);
    report_counters(state, sim);
  }
}

}  // namespace cosmpm::benchmarks
