// update_stress_from_grid (stages/stress_update.hpp): stages 4a and 4b in one pass, run by run,
// which MUSL and USF call. Each particle's arithmetic is the separate stages' in the same packs,
// so a run through it and a run through velocity_gradient_from_grid then update_stress agree bit
// for bit, every particle field and every node field, step after step.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using Soil = material::MohrCoulomb<>;
using PolarSoil = material::CosseratDruckerPrager<>;
using Polar = continuum::Cosserat<PolarSoil>;

// MUSL and USF with stages 4a and 4b called apart, as before update_stress_from_grid.
struct MUSLApart {
  static constexpr const char* name() { return "MUSL, stages 4a and 4b apart"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/true);
    sim.update_grid(dt);
    sim.map_to_particles(dt);
    sim.remap_momentum(dt);
    sim.velocity_gradient_from_grid(sim.nodes().velocity, sim.nodes().spin);
    sim.update_stress(dt);
  }
};
struct USFApart {
  static constexpr const char* name() { return "USF, stages 4a and 4b apart"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/false);
    sim.grid_velocity_from_momentum(dt);
    sim.velocity_gradient_from_grid(sim.nodes().momentum, sim.nodes().spin_momentum);
    sim.update_stress(dt);
    sim.map_forces_to_grid();
    sim.update_grid(dt);
    sim.map_to_particles(dt);
  }
};

template <class Continuum>
Continuum make_continuum() {
  // The benchmark's soils (benchmarks/simulation/step_support.hpp): corn, and the paper's
  // Cosserat parameters (Gc, l = 10 mm, micro-inertia 12.5e-6 m^2).
  if constexpr (std::is_same_v<Continuum, Polar>) {
    return Polar(PolarSoil(2.76e6, 0.2, 2.3e6, 0.01, 26.0, 2.0), {.micro_inertia = 12.5e-6});
  } else {
    return Continuum(Soil({.youngs_modulus = 2.76e6,
                           .poisson_ratio = 0.2,
                           .friction_angle_deg = 26.0,
                           .dilatancy_angle_deg = 2.0}));
  }
}

// A block of 2 x 2 particles per cell sliding at 0.5 m/s over a fixed floor, which shears its
// base into plastic flow. `wide`: 6,200 particles, above cosmpm::parallel_threshold, so the
// pass runs on two threads.
template <class Sim>
Sim sliding_block(int threads, bool wide) {
  const double length = wide ? 2.0 : 0.4;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(length, 0.12), {wide ? 200 : 40, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = threads;
  Sim sim(grid, make_continuum<typename Sim::continuum_type>(), parameters);
  const auto seeding =
      particles::seed_box(grid, Vec<2>(0.05, 0.0), Vec<2>(wide ? 1.6 : 0.25, wide ? 0.1 : 0.06), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
    v = Vec<2>(0.5, 0.0);
  }
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  // memcmp takes no null pointer, which an empty vector may hold.
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <class A, class B>
void check_same(const A& a, const B& b) {
  namespace field = particles::field;
  using Model = typename A::model_type;
  const auto& p = a.particles();
  const auto& q = b.particles();
  CHECK(same_bits(p.template get<field::Position<2>>(), q.template get<field::Position<2>>()));
  CHECK(same_bits(p.template get<field::Velocity<2>>(), q.template get<field::Velocity<2>>()));
  CHECK(same_bits(p.template get<field::Stress<Model>>(), q.template get<field::Stress<Model>>()));
  CHECK(same_bits(p.template get<field::Strain<Model>>(), q.template get<field::Strain<Model>>()));
  CHECK(same_bits(p.template get<field::MaterialState<Model>>(),
                  q.template get<field::MaterialState<Model>>()));
  CHECK(same_bits(p.template get<field::VelocityGradient<2>>(),
                  q.template get<field::VelocityGradient<2>>()));
  CHECK(same_bits(p.template get<field::DeformationGradient<2>>(),
                  q.template get<field::DeformationGradient<2>>()));
  CHECK(same_bits(p.template get<field::Volume>(), q.template get<field::Volume>()));
  if constexpr (A::continuum_type::rotational_dofs > 0) {
    CHECK(same_bits(p.template get<field::MicroSpin>(), q.template get<field::MicroSpin>()));
    CHECK(
        same_bits(p.template get<field::MicroRotation>(), q.template get<field::MicroRotation>()));
  }
  CHECK(same_bits(a.nodes().velocity, b.nodes().velocity));
  CHECK(same_bits(a.nodes().force, b.nodes().force));
  CHECK(same_bits(a.nodes().moment, b.nodes().moment));
}

// Steps a run of `Scheme` and one of `Apart` side by side and compares them every 20 steps;
// the block must have gone plastic, so the model's return is in the comparison.
template <class Continuum, class Scheme, class Apart>
void check_one_pass(int threads, bool wide, const std::string& label) {
  using Sim = Simulation<2, shape::Linear, Continuum, contact::SingleField, Scheme>;
  using SimApart = Simulation<2, shape::Linear, Continuum, contact::SingleField, Apart>;
  INFO(label);
  Sim one_pass = sliding_block<Sim>(threads, wide);
  SimApart apart = sliding_block<SimApart>(threads, wide);
  const double dt = one_pass.time_step();
  for (int i = 1; i <= 100; ++i) {
    one_pass.step(dt);
    apart.step(dt);
    if (i % 20 == 0) check_same(one_pass, apart);
  }
  using Model = typename Sim::model_type;
  const auto& state =
      std::as_const(one_pass).particles().template get<particles::field::MaterialState<Model>>();
  Index plastic = 0;
  for (const auto& s : state) plastic += s.plastic != 0;
  CHECK(plastic > 0);
}
}  // namespace

TEST_CASE(
    "update_stress_from_grid: as velocity_gradient_from_grid then update_stress, bit for "
    "bit") {
  SUBCASE("MUSL, Mohr-Coulomb") {
    check_one_pass<continuum::Classical<Soil>, integrator::MUSL, MUSLApart>(1, false, "MUSL MC");
  }
  SUBCASE("MUSL, Cosserat Drucker-Prager") {
    check_one_pass<Polar, integrator::MUSL, MUSLApart>(1, false, "MUSL Cosserat");
  }
  SUBCASE("USF, Mohr-Coulomb and Cosserat Drucker-Prager") {
    check_one_pass<continuum::Classical<Soil>, integrator::USF, USFApart>(1, false, "USF MC");
    check_one_pass<Polar, integrator::USF, USFApart>(1, false, "USF Cosserat");
  }
  SUBCASE("F-bar: the stages apart (the average needs every rate first)") {
    using Averaged = continuum::Classical<Soil, antilocking::FBar>;
    check_one_pass<Averaged, integrator::MUSL, MUSLApart>(1, false, "MUSL F-bar");
  }
  SUBCASE("two threads over 6,200 particles") {
    check_one_pass<continuum::Classical<Soil>, integrator::MUSL, MUSLApart>(2, true,
                                                                            "2 threads MC");
    check_one_pass<Polar, integrator::MUSL, MUSLApart>(2, true, "2 threads Cosserat");
  }
}

TEST_CASE("update_stress_from_grid: a nodal field of the wrong size is named") {
  using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                         integrator::MUSL>;
  Sim sim = sliding_block<Sim>(1, false);
  const double dt = sim.time_step();
  sim.step(dt);
  const std::vector<Vec<2>> too_short(3, Vec<2>::Zero());
  CHECK_THROWS_WITH_AS(sim.update_stress_from_grid(dt, too_short),
                       doctest::Contains("update_stress_from_grid"), Error);
}

TEST_CASE("update_stress_from_grid: its rates are not left for a later update_stress") {
  // The whole packs' rates go from stage 4a to 4b without EngineState::particle_rates; a later
  // update_stress would find other rates there, so it asks for stage 4a first.
  using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                         integrator::MUSL>;
  Sim sim = sliding_block<Sim>(1, false);
  const double dt = sim.time_step();
  sim.step(dt);
  CHECK_THROWS_WITH_AS(sim.update_stress(dt),
                       doctest::Contains("call velocity_gradient_from_grid first"), Error);
  sim.velocity_gradient_from_grid(sim.nodes().velocity);
  CHECK_NOTHROW(sim.update_stress(dt));
}
