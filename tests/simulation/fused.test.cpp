// The fused schemes (integrator/fused.hpp) against the unfused ones they shorten: the same
// particles, the same steps, compared field by field.
// The fused pass sums each node's terms in particle-index order, in two halves, where the
// unfused scatter sums them block by block in colour order, so the fields differ by rounding
// only. The bound, 1e-11 of each field's largest magnitude, is about 1e3 times the differences
// measured when it was written (2026-12-03: 1.7e-14 for the elastic bar after 300 steps,
// 1.4e-14 for the Mohr-Coulomb block after 200); a particle's terms missing from or doubled in a
// nodal sum, or records left from before a particle was changed, move the fields by far more. One
// and two threads give the same bits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/transfer/apic.hpp"
#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using Soil = material::MohrCoulomb<>;

// A block of 2 x 2 particles per cell on the floor under gravity, sliding sideways at `speed`
// (the floor a roller), so that after a few dozen steps particles cross block boundaries
// (blocks span 16 x 4 cells); the Mohr-Coulomb runs have a fixed floor, which shears the
// block's base into plastic flow. `wide`: 5,300 particles, above cosmpm::parallel_threshold.
template <class Sim>
Sim thrown_block(const typename Sim::continuum_type& continuum, int threads, double speed,
                 bool wide = false) {
  const double length = wide ? 2.0 : 0.4;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(length, 0.12), {wide ? 200 : 40, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = threads;
  Sim sim(grid, continuum, parameters);
  const auto seeding =
      particles::seed_box(grid, Vec<2>(0.05, 0.0), Vec<2>(wide ? 1.6 : 0.25, 0.07), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  for (auto& velocity : v) velocity = Vec<2>(speed, 0.0);
  constexpr bool plastic = std::is_same_v<typename Sim::model_type, Soil>;
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                plastic ? grid::BoundaryKind::fixed : grid::BoundaryKind::roller);
  return sim;
}

// An elastic bar filling the grid between roller walls on a roller floor, 5,600 particles,
// released with the velocity of its first axial mode, v_x = v sin(pi x / L): particles
// inside travel up to two cells and cross block boundaries, while none enters an empty cell
// (where USL's small nodal masses would make the run unstable whatever the scheme).
template <class Sim>
Sim vibrating_bar(const typename Sim::continuum_type& continuum, int threads) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(2.0, 0.12), {200, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, 0.0);
  parameters.threads = threads;
  Sim sim(grid, continuum, parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(2.0, 0.07), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  for (std::size_t p = 0; p < v.size(); ++p) {
    v[p] = Vec<2>(0.5 * std::sin(std::numbers::pi * x[p][0] / 2.0), 0.0);
  }
  using BC = grid::BoundaryConditions<2>;
  for (const auto face : {BC::face(1, false), BC::face(0, false), BC::face(0, true)}) {
    sim.boundary_conditions().set(face, grid::BoundaryKind::roller);
  }
  return sim;
}

// The elastic Cosserat continuum of the polar checks.
using Polar = continuum::Cosserat<material::CosseratElastic<double>>;
const Polar& polar_bar() {
  static const Polar polar(material::CosseratElastic<double>(2e5, 0.25, 8e4, 0.01),
                           {.micro_inertia = 1.25e-5});
  return polar;
}

const Soil& corn() {
  static const Soil soil({.youngs_modulus = 2e5,
                          .poisson_ratio = 0.25,
                          .friction_angle_deg = 26.0,
                          .dilatancy_angle_deg = 2.0});
  return soil;
}

// The largest difference between two runs' particle fields, over each field's largest
// magnitude (positions, velocities, stresses, deformation gradients).
template <class A, class B>
double largest_relative_difference(const A& a, const B& b) {
  namespace field = particles::field;
  using Model = typename A::model_type;
  double worst = 0.0;
  const auto compare = [&](const auto& x, const auto& y) {
    REQUIRE(x.size() == y.size());
    double scale = 0.0, difference = 0.0;
    for (std::size_t p = 0; p < x.size(); ++p) {
      scale = std::max(scale, x[p].cwiseAbs().maxCoeff());
      difference = std::max(difference, (x[p] - y[p]).cwiseAbs().maxCoeff());
    }
    worst = std::max(worst, scale > 0.0 ? difference / scale : difference);
  };
  compare(a.particles().template get<field::Position<2>>(),
          b.particles().template get<field::Position<2>>());
  compare(a.particles().template get<field::Velocity<2>>(),
          b.particles().template get<field::Velocity<2>>());
  compare(a.particles().template get<field::Stress<Model>>(),
          b.particles().template get<field::Stress<Model>>());
  compare(a.particles().template get<field::DeformationGradient<2>>(),
          b.particles().template get<field::DeformationGradient<2>>());
  return worst;
}

template <class Plain, class Fused>
void run_side_by_side(Plain& plain, Fused& fused, int steps) {
  const double dt = plain.time_step();
  REQUIRE(dt == fused.time_step());
  for (int i = 0; i < steps; ++i) {
    plain.step(dt);
    fused.step(dt);
  }
}

// Runs `steps` steps of each, then checks the fused run against the unfused one within the
// bound above and the fused runs on one and two threads against each other, bit for bit.
template <class Plain, class Fused>
void check_fused(Plain& plain, Fused& fused, Fused& fused_two, int steps,
                 const std::string& label) {
  run_side_by_side(plain, fused, steps);
  for (int i = 0; i < steps; ++i) fused_two.step(plain.time_step());
  const double difference = largest_relative_difference(plain, fused);
  MESSAGE(label << " after " << steps << " steps: " << difference);
  CHECK(difference <= 1e-11);
#if defined(_OPENMP)
  CHECK(std::as_const(fused_two).engine().fused_team == 2);  // the parallel path ran
#endif
  CHECK(largest_relative_difference(fused, fused_two) == 0.0);
}

}  // namespace

TEST_CASE(
    "fused MUSL: within rounding of MUSL, with plastic returns; the same on 1 and 2 threads") {
  using Plain = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::MUSL>;
  using Fused = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::FusedMUSL>;
  Plain plain = thrown_block<Plain>(continuum::Classical<Soil>(corn()), 1, 0.5, true);
  Fused fused = thrown_block<Fused>(continuum::Classical<Soil>(corn()), 1, 0.5, true);
  Fused fused_two = thrown_block<Fused>(continuum::Classical<Soil>(corn()), 2, 0.5, true);
  check_fused(plain, fused, fused_two, 200, "fused MUSL against MUSL");
  const auto& state = fused.particles().get<particles::field::MaterialState<Soil>>();
  CHECK(std::count_if(state.begin(), state.end(), [](const auto& s) { return s.plastic; }) > 100);
}

TEST_CASE("fused USL: within rounding of USL, the same on 1 and 2 threads") {
  using Plain =
      Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::USL>;
  using Fused = Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField,
                           integrator::FusedUSL>;
  const test::ElasticContinuum elastic(test::Elastic(2e5, 0.25));
  Plain plain = vibrating_bar<Plain>(elastic, 1);
  Fused fused = vibrating_bar<Fused>(elastic, 1);
  Fused fused_two = vibrating_bar<Fused>(elastic, 2);
  check_fused(plain, fused, fused_two, 300, "fused USL against USL");
}

TEST_CASE("fused schemes: particles written between steps are mapped as written") {
  using Plain = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::MUSL>;
  using Fused = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::FusedMUSL>;
  Plain plain = thrown_block<Plain>(continuum::Classical<Soil>(corn()), 1, 0.0);
  Fused fused = thrown_block<Fused>(continuum::Classical<Soil>(corn()), 1, 0.0);
  run_side_by_side(plain, fused, 20);
  // A kick to every particle after the fused pass scattered the old velocities.
  const auto kick = [](auto& sim) {
    for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
      v += Vec<2>(0.0, 0.3);
    }
  };
  kick(plain);
  kick(fused);
  run_side_by_side(plain, fused, 20);
  CHECK(largest_relative_difference(plain, fused) <= 1e-11);
  // Reading through a const reference keeps the records: the run stays the same.
  double total_mass = 0.0;
  for (const double m : std::as_const(fused).particles().get<particles::field::Mass>()) {
    total_mass += m;
  }
  CHECK(total_mass > 0.0);
  run_side_by_side(plain, fused, 5);
  CHECK(largest_relative_difference(plain, fused) <= 1e-11);
}

TEST_CASE(
    "fused schemes: records dropped between steps (a restart, a user's write) change no bit") {
  using Fused = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::FusedMUSL>;
  Fused straight = thrown_block<Fused>(continuum::Classical<Soil>(corn()), 1, 0.5, true);
  Fused dropped = thrown_block<Fused>(continuum::Classical<Soil>(corn()), 2, 0.5, true);
  const double dt = straight.time_step();
  for (int i = 0; i < 60; ++i) {
    straight.step(dt);
    dropped.step(dt);
    if (i % 7 == 3) dropped.particles();  // taken for writing: the fused records are dropped
  }
  CHECK(largest_relative_difference(straight, dropped) == 0.0);
  for (Index n = 0; n < straight.grid().node_count(); ++n) {
    REQUIRE(straight.nodes().mass[n] == dropped.nodes().mass[n]);
    REQUIRE(straight.nodes().velocity[n] == dropped.nodes().velocity[n]);
  }
}

TEST_CASE("fused schemes: a particle leaving the grid is removed as in the unfused scheme") {
  using Plain =
      Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, integrator::USL>;
  using Fused = Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField,
                           integrator::FusedUSL>;
  const test::ElasticContinuum elastic(test::Elastic(2e5, 0.25));
  const auto make = [&](auto tag) {
    using Sim = typename decltype(tag)::type;
    const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.12), {40, 12});
    SimulationParameters<2> parameters;
    parameters.threads = 1;
    parameters.stray_particles = StrayParticles::remove;
    Sim sim(grid, elastic, parameters);
    const auto seeding = particles::seed_box(grid, Vec<2>(0.3, 0.05), Vec<2>(0.39, 0.07), 2);
    sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
    for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
      v = Vec<2>(3.0, 0.0);
    }
    return sim;
  };
  Plain plain = make(std::type_identity<Plain>{});
  Fused fused = make(std::type_identity<Fused>{});
  run_side_by_side(plain, fused, 60);
  REQUIRE(plain.stray_particles().count > 0);
  CHECK(fused.stray_particles().count == plain.stray_particles().count);
  CHECK(fused.particles().size() == plain.particles().size());
}

namespace {
// A fused scheme against its unfused one with rotational degrees of freedom (the micro-spins
// compared too) and with APIC's affine terms, and on one thread against two.
template <class PlainScheme, class FusedScheme>
void check_polar_and_apic(const std::string& label) {
  SUBCASE("Cosserat continuum") {
    using Plain = Simulation<2, shape::Linear, Polar, contact::SingleField, PlainScheme>;
    using Fused = Simulation<2, shape::Linear, Polar, contact::SingleField, FusedScheme>;
    const Polar& polar = polar_bar();
    Plain plain = vibrating_bar<Plain>(polar, 1);
    Fused fused = vibrating_bar<Fused>(polar, 1);
    Fused fused_two = vibrating_bar<Fused>(polar, 2);
    check_fused(plain, fused, fused_two, 300, label + ", Cosserat");
    const auto& a = plain.particles().template get<particles::field::MicroSpin>();
    const auto& b = fused.particles().template get<particles::field::MicroSpin>();
    double scale = 0.0, worst = 0.0;
    for (std::size_t p = 0; p < a.size(); ++p) {
      scale = std::max(scale, std::abs(a[p]));
      worst = std::max(worst, std::abs(a[p] - b[p]));
    }
    CHECK(scale > 0.0);
    CHECK(worst <= 1e-11 * scale);
  }
  SUBCASE("APIC, quadratic B-splines") {
    using Plain = Simulation<2, shape::QuadraticBSpline, test::ElasticContinuum,
                             contact::SingleField, PlainScheme, transfer::APIC>;
    using Fused = Simulation<2, shape::QuadraticBSpline, test::ElasticContinuum,
                             contact::SingleField, FusedScheme, transfer::APIC>;
    const test::ElasticContinuum elastic(test::Elastic(2e5, 0.25));
    Plain plain = vibrating_bar<Plain>(elastic, 1);
    Fused fused = vibrating_bar<Fused>(elastic, 1);
    Fused fused_two = vibrating_bar<Fused>(elastic, 2);
    check_fused(plain, fused, fused_two, 300, label + ", APIC");
  }
}
}  // namespace

TEST_CASE("fused USL: within rounding of USL with rotational degrees of freedom and with APIC") {
  check_polar_and_apic<integrator::USL, integrator::FusedUSL>("fused USL against USL");
}

TEST_CASE("fused MUSL: within rounding of MUSL with rotational degrees of freedom and with APIC") {
  check_polar_and_apic<integrator::MUSL, integrator::FusedMUSL>("fused MUSL against MUSL");
}

namespace {
// The two-stage remap (map_to_particles, remap_momentum) and the one-pass stage of fused MUSL
// (map_to_particles_and_remap) on two copies of one run after `steps` MUSL steps: the particles
// move by the same arithmetic, so bit for bit; each remapped node velocity (and spin) is the
// same terms summed in another order, so within 1e-13 of the field's largest magnitude
// (measured 2026-12-03: 1.9e-16 Mohr-Coulomb, 4.5e-16 Cosserat, 1.7e-15 APIC; one particle's
// terms left out moved a node by 7-18 % of it). The fused copy runs on two threads.
template <class Sim>
void check_one_pass_remap(Sim& two_stage, Sim& one_pass, int steps, const std::string& label) {
  const double dt = two_stage.time_step();
  run_side_by_side(two_stage, one_pass, steps);
  for (Sim* sim : {&two_stage, &one_pass}) {
    sim->map_to_grid(true);
    sim->update_grid(dt);
  }
  two_stage.map_to_particles(dt);
  two_stage.remap_momentum(dt);
  one_pass.map_to_particles_and_remap(dt);
  CHECK(largest_relative_difference(two_stage, one_pass) == 0.0);
  const auto& a = two_stage.nodes();
  const auto& b = one_pass.nodes();
  double scale = 0.0, worst = 0.0, spin_scale = 0.0, spin_worst = 0.0;
  for (Index n = 0; n < two_stage.grid().node_count(); ++n) {
    scale = std::max(scale, a.velocity[n].cwiseAbs().maxCoeff());
    worst = std::max(worst, (a.velocity[n] - b.velocity[n]).cwiseAbs().maxCoeff());
  }
  for (std::size_t k = 0; k < a.spin.size(); ++k) {
    spin_scale = std::max(spin_scale, std::abs(a.spin[k]));
    spin_worst = std::max(spin_worst, std::abs(a.spin[k] - b.spin[k]));
  }
  MESSAGE(label << ": node velocity " << worst / scale << ", spin "
                << (spin_scale > 0.0 ? spin_worst / spin_scale : 0.0));
  CHECK(scale > 0.0);
  CHECK(worst <= 1e-13 * scale);
  CHECK(spin_worst <= 1e-13 * spin_scale);
#if defined(_OPENMP)
  CHECK(std::as_const(one_pass).engine().fused_team == 2);
#endif
}
}  // namespace

TEST_CASE("map_to_particles_and_remap: as map_to_particles then remap_momentum, within rounding") {
  SUBCASE("Mohr-Coulomb, linear") {
    using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::MUSL>;
    Sim two_stage = thrown_block<Sim>(continuum::Classical<Soil>(corn()), 1, 0.5, true);
    Sim one_pass = thrown_block<Sim>(continuum::Classical<Soil>(corn()), 2, 0.5, true);
    check_one_pass_remap(two_stage, one_pass, 40, "Mohr-Coulomb");
  }
  SUBCASE("Cosserat continuum (spin remapped)") {
    using Sim = Simulation<2, shape::Linear, Polar, contact::SingleField, integrator::MUSL>;
    const Polar& polar = polar_bar();
    Sim two_stage = vibrating_bar<Sim>(polar, 1);
    Sim one_pass = vibrating_bar<Sim>(polar, 2);
    check_one_pass_remap(two_stage, one_pass, 40, "Cosserat");
    double spin = 0.0;
    for (const double w : two_stage.nodes().spin) spin = std::max(spin, std::abs(w));
    CHECK(spin > 0.0);
  }
  SUBCASE("APIC, quadratic B-splines (affine terms remapped)") {
    using Sim = Simulation<2, shape::QuadraticBSpline, test::ElasticContinuum, contact::SingleField,
                           integrator::MUSL, transfer::APIC>;
    const test::ElasticContinuum elastic(test::Elastic(2e5, 0.25));
    Sim two_stage = vibrating_bar<Sim>(elastic, 1);
    Sim one_pass = vibrating_bar<Sim>(elastic, 2);
    check_one_pass_remap(two_stage, one_pass, 40, "APIC");
  }
}

namespace {
// Stage 4a apart (velocity_gradient_from_grid, then update_stress_and_map_to_grid) and inside
// the pass (update_stress_and_map_to_grid with the nodal fields, what FusedMUSL calls) on two
// copies of one run: each particle's rates, stress and scatter are the same arithmetic, so the
// particles, their velocity gradients and the next step's node fields agree bit for bit (the
// rates gathered after each run's stress update instead of before failed 5 of the checks). The
// one-pass copy runs on two threads.
template <class Sim>
void check_one_pass_rates(Sim& apart, Sim& one_pass, int steps, const std::string& label) {
  const double dt = apart.time_step();
  run_side_by_side(apart, one_pass, steps);
  for (Sim* sim : {&apart, &one_pass}) {
    sim->map_to_grid_or_reuse();
    sim->update_grid(dt);
    sim->map_to_particles_and_remap(dt);
  }
  apart.velocity_gradient_from_grid(apart.nodes().velocity, apart.nodes().spin);
  apart.update_stress_and_map_to_grid(dt);
  one_pass.update_stress_and_map_to_grid(dt, one_pass.nodes().velocity, one_pass.nodes().spin);
  CHECK(largest_relative_difference(apart, one_pass) == 0.0);
  const auto& L_apart =
      std::as_const(apart).particles().template get<particles::field::VelocityGradient<2>>();
  const auto& L_one =
      std::as_const(one_pass).particles().template get<particles::field::VelocityGradient<2>>();
  double gradient = 0.0;
  for (std::size_t p = 0; p < L_apart.size(); ++p) {
    CHECK_MESSAGE(L_apart[p] == L_one[p], label << ": particle " << p);
    gradient = std::max(gradient, L_apart[p].cwiseAbs().maxCoeff());
  }
  CHECK(gradient > 0.0);
  // The records the pass scattered, taken as the next step's node fields.
  for (Sim* sim : {&apart, &one_pass}) sim->map_to_grid_or_reuse();
  const auto& a = apart.nodes();
  const auto& b = one_pass.nodes();
  CHECK(a.mass == b.mass);
  CHECK(a.momentum == b.momentum);
  CHECK(a.force == b.force);
  CHECK(a.spin_momentum == b.spin_momentum);
  CHECK(a.moment == b.moment);
#if defined(_OPENMP)
  CHECK(std::as_const(one_pass).engine().fused_team == 2);
#endif
}
}  // namespace

TEST_CASE(
    "update_stress_and_map_to_grid with the nodal fields: as stage 4a before it, bit for bit") {
  SUBCASE("Mohr-Coulomb, linear") {
    using Sim = Simulation<2, shape::Linear, continuum::Classical<Soil>, contact::SingleField,
                           integrator::FusedMUSL>;
    Sim apart = thrown_block<Sim>(continuum::Classical<Soil>(corn()), 1, 0.5, true);
    Sim one_pass = thrown_block<Sim>(continuum::Classical<Soil>(corn()), 2, 0.5, true);
    check_one_pass_rates(apart, one_pass, 40, "Mohr-Coulomb");
    const auto& state = one_pass.particles().get<particles::field::MaterialState<Soil>>();
    CHECK(std::count_if(state.begin(), state.end(), [](const auto& s) { return s.plastic; }) > 0);
  }
  SUBCASE("Cosserat continuum (spin and its gradient)") {
    using Sim = Simulation<2, shape::Linear, Polar, contact::SingleField, integrator::FusedMUSL>;
    const Polar& polar = polar_bar();
    Sim apart = vibrating_bar<Sim>(polar, 1);
    Sim one_pass = vibrating_bar<Sim>(polar, 2);
    check_one_pass_rates(apart, one_pass, 40, "Cosserat");
  }
  SUBCASE("F-bar (the stages apart: the average needs every rate first)") {
    using Averaged = continuum::Classical<Soil, antilocking::FBar>;
    using Sim = Simulation<2, shape::Linear, Averaged, contact::SingleField, integrator::FusedMUSL>;
    Sim apart = thrown_block<Sim>(Averaged(corn()), 1, 0.5, true);
    Sim one_pass = thrown_block<Sim>(Averaged(corn()), 2, 0.5, true);
    check_one_pass_rates(apart, one_pass, 40, "F-bar");
  }
}
