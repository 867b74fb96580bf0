// update_stress_from_grid (stages/stress_update.hpp): stages 4a and 4b in one pass, run by run,
// which MUSL and USF call. Each particle's arithmetic is the separate stages' in the same packs,
// so a run through it and a run through velocity_gradient_from_grid then update_stress agree bit
// for bit, every particle field and every node field, step after step.
#include <doctest/doctest.h>

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "sliding_block.hpp"

namespace {
using namespace cosmpm;
using test::sliding_block;
using test::Soil;
using Polar = test::PolarContinuum;

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
    if (i % 20 == 0) test::check_same_fields(one_pass, apart);
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
