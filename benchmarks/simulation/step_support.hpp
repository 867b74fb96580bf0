#pragma once
// What the step benchmarks of step.bench.cpp (2D) and step_3d.bench.cpp (3D) share: the
// paper's corn as each model and continuum, the soil block (a box of particles on a fixed floor
// between roller walls, gravity along the last axis) and the timed loop of full steps with its
// counters. items_per_second is particle-steps per second.
#include <benchmark/benchmark.h>

#include <optional>
#include <type_traits>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/continuum/cosserat.hpp"
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

// The continuum of those models (Cosserat: the paper's micro-inertia).
template <class Continuum>
Continuum make_continuum() {
  using Model = typename Continuum::model_type;
  if constexpr (Continuum::is_cosserat) {
    return Continuum(make_model(std::type_identity<Model>{}), {.micro_inertia = 12.5e-6});
  } else {
    return Continuum(make_model(std::type_identity<Model>{}));
  }
}

// Corn filling the box [0, fill] of `grid` (2 particles per cell and axis), gravity along the
// last axis, the floor (lower face of the last axis) fixed, every side face a roller wall.
template <class Sim>
Sim soil_block(const grid::Grid<Sim::dim>& grid, const Vec<Sim::dim>& fill, int threads,
               std::optional<double> flip_fraction = std::nullopt) {
  constexpr int dim = Sim::dim;
  SimulationParameters<dim> parameters;
  parameters.gravity = Vec<dim>::Zero();
  parameters.gravity[dim - 1] = -9.81;
  parameters.threads = threads;
  parameters.flip_fraction = flip_fraction;
  Sim sim(grid, make_continuum<typename Sim::continuum_type>(), parameters);
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

// items_per_second (particle-steps per second, from the timed loop's iterations) and the
// counters: the particles, the threads and the fraction of particles whose last update was
// plastic (the cost of a Mohr-Coulomb step depends on it, in 3D by the eigenproblem of each
// plastic point; 0 for an elastic model). Every benchmark sets the same counters: Google
// Benchmark's CSV output, which scripts/bench_interleaved.sh reads, aborts when a run has a
// counter that the first run reported lacked, and random interleaving puts any one first.
template <class Sim>
void report_counters(benchmark::State& state, const Sim& sim) {
  const Index count = sim.particles().size();
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["particles"] = static_cast<double>(count);
  state.counters["threads"] = static_cast<double>(sim.threads());
  using Model = typename Sim::model_type;
  double plastic = 0.0;
  if constexpr (std::is_same_v<typename Model::state_type, material::PlasticState>) {
    const auto& states = sim.particles().template get<particles::field::MaterialState<Model>>();
    for (Index p = 0; p < count; ++p) plastic += states[p].plastic;
  }
  state.counters["plastic_fraction"] = plastic / static_cast<double>(count);
}

// Full steps of the stable size, timed, and their counters.
template <class Sim>
void time_full_steps(benchmark::State& state, Sim& sim) {
  const double dt = sim.time_step();
  for (auto _ : state) sim.step(dt);
  report_counters(state, sim);
}

}  // namespace cosmpm::benchmarks
