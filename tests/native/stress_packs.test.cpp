// Stage 4b with a model that has update_packs (material::HasPacksUpdate): the rotated stresses
// and increments stay in packs, the model updates them there and the strains accumulate on them.
// A model without the hook gets update_batch on stored increments and the strains accumulated
// particle by particle. The hook's contract is update_batch's values, so the two paths must
// leave every particle field equal bit for bit: here the same model with its update_packs
// hidden runs beside it, under MUSL and fused MUSL. Built for the host (tests/native), where the
// packs hold 4 doubles and both Mohr-Coulomb and Cosserat Drucker-Prager have the hook.
#include <doctest/doctest.h>

#include <string>
#include <type_traits>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"

namespace {
using namespace cosmpm;

// The model with update_packs hidden: stage 4b takes its update_batch path.
template <class Model>
struct WithoutPacks : Model {
  using Model::Model;
  template <int W, class... Arguments>
  void update_packs(Arguments&&...) const = delete;
};

// A block on a fixed floor under gravity, thrown sideways, so its base shears into plastic
// flow (the block of tests/simulation/fused.test.cpp): 2 x 2 particles per cell, 560 particles.
template <class Sim>
Sim thrown_block(const typename Sim::continuum_type& continuum) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.12), {40, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = 1;
  Sim sim(grid, continuum, parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.05, 0.0), Vec<2>(0.25, 0.07), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
    v = Vec<2>(0.5, 0.0);
  }
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

template <class A, class B, class Field>
bool same_field(const A& a, const B& b, Field) {
  const auto& x = a.particles().template get<Field>();
  const auto& y = b.particles().template get<Field>();
  if (x.size() != y.size()) return false;
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (!(x[p] == y[p])) return false;
  }
  return true;
}

// Runs `steps` MUSL steps of the continuum over the model with and without its update_packs and
// compares every field the update writes; returns the number of points plastic in the last step.
template <class Model, class Scheme, class Continuum, class Hidden>
int check_paths(const Continuum& with_packs, const Hidden& without_packs, int steps) {
  static_assert(material::HasPacksUpdate<Model, pack_width>);
  using HiddenModel = typename Hidden::model_type;
  static_assert(!material::HasPacksUpdate<HiddenModel, pack_width>);
  using SimA = Simulation<2, shape::Linear, Continuum, contact::SingleField, Scheme>;
  using SimB = Simulation<2, shape::Linear, Hidden, contact::SingleField, Scheme>;
  SimA a = thrown_block<SimA>(with_packs);
  SimB b = thrown_block<SimB>(without_packs);
  const double dt = a.time_step();
  REQUIRE(dt == b.time_step());
  for (int i = 0; i < steps; ++i) {
    a.step(dt);
    b.step(dt);
  }
  namespace field = particles::field;
  CHECK(same_field(a, b, field::Position<2>{}));
  CHECK(same_field(a, b, field::Velocity<2>{}));
  CHECK(same_field(a, b, field::DeformationGradient<2>{}));
  const auto& sa = a.particles().template get<field::Stress<Model>>();
  const auto& sb = b.particles().template get<field::Stress<HiddenModel>>();
  const auto& ea = a.particles().template get<field::Strain<Model>>();
  const auto& eb = b.particles().template get<field::Strain<HiddenModel>>();
  const auto& ma = a.particles().template get<field::MaterialState<Model>>();
  const auto& mb = b.particles().template get<field::MaterialState<HiddenModel>>();
  REQUIRE(sa.size() == sb.size());
  bool stress = true, strain = true, state = true;
  int plastic = 0;
  for (std::size_t p = 0; p < sa.size(); ++p) {
    stress = stress && sa[p] == sb[p];
    strain = strain && ea[p] == eb[p];
    state = state && ma[p].values() == mb[p].values();
    plastic += ma[p].plastic == 1.0 ? 1 : 0;
  }
  CHECK(stress);
  CHECK(strain);
  CHECK(state);
  return plastic;
}

}  // namespace

// With fused MUSL the scatter after stage 4b also takes the whole packs' stresses from the
// packs (stages/fused_pass.hpp), where without the hook it loads them from the particles.
TEST_CASE_TEMPLATE(
    "stage 4b: a model's update_packs leaves every field as update_batch does, bit for bit", Scheme,
    integrator::MUSL, integrator::FusedMUSL) {
  if constexpr (pack_width < 4) {
    MESSAGE("packs of " << pack_width << " doubles: Mohr-Coulomb has no update_packs here");
  } else {
    SUBCASE("Mohr-Coulomb") {
      using Model = material::MohrCoulomb<>;
      const material::MohrCoulombParameters corn{.youngs_modulus = 2e5,
                                                 .poisson_ratio = 0.25,
                                                 .friction_angle_deg = 26.0,
                                                 .dilatancy_angle_deg = 2.0};
      const continuum::Classical<Model> with_packs{Model(corn)};
      const continuum::Classical<WithoutPacks<Model>> without_packs{WithoutPacks<Model>(corn)};
      // After 200 steps the block flows: 533 of the 560 points plastic in the last step (560
      // in the Cosserat run); the first steps, from zero stress, are elastic.
      CHECK(check_paths<Model, Scheme>(with_packs, without_packs, 200) > 10);
    }
    SUBCASE("Cosserat Drucker-Prager") {
      using Model = material::CosseratDruckerPrager<double>;
      const material::CosseratDruckerPragerParameters corn{.youngs_modulus = 2e5,
                                                           .poisson_ratio = 0.25,
                                                           .cosserat_shear_modulus = 8e4,
                                                           .characteristic_length = 0.01,
                                                           .friction_angle_deg = 26.0,
                                                           .dilatancy_angle_deg = 2.0};
      const continuum::Cosserat<Model> with_packs(Model(corn), {.micro_inertia = 1.25e-5});
      const continuum::Cosserat<WithoutPacks<Model>> without_packs(WithoutPacks<Model>(corn),
                                                                   {.micro_inertia = 1.25e-5});
      CHECK(check_paths<Model, Scheme>(with_packs, without_packs, 200) > 10);
    }
  }
}
