// The Cosserat continuum's rotational step bound against the operator it bounds: the lumped
// operator on the nodal rotations (translations held), assembled here from the library's
// kernels, the continuum's deformation increment and moment terms and the elastic model, its
// largest eigenvalue found by power iteration (and checked by a dense solver); explicit steps
// just below the bound and just above the critical step, of the grid update and of the
// engine's USL and MUSL; and the micro-inertia scale (docs/theory/mpm.md, "Cosserat
// continuum").
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using Model = material::CosseratElastic<double>;
using Polar = continuum::Cosserat<Model>;

constexpr double density = 778.0;   // the paper's corn
constexpr double cell = 0.01;       // m
constexpr double corn_j = 12.5e-6;  // m^2, the paper's J

// Pseudo-random numbers in [-1/2, 1/2) (a linear congruential generator: fixed, portable).
double next_uniform(std::uint32_t& seed) {
  seed = seed * 1664525u + 1013904223u;
  return static_cast<double>(seed) / 4294967296.0 - 0.5;
}

// Corn (Table 1 of the paper): E = 2.76 MPa, nu = 0.2, Gc = 2 G, l = 10 mm. On 10 mm cells
// its two rotational stiffnesses are equal, 4 B / h^2 = 4 Gc = 9.2 MPa.
Model corn(double length_scale = 0.01, double gc_over_g = 2.0) {
  const double shear = 2.76e6 / 2.4;
  return Model(2.76e6, 0.2, gc_over_g * shear, length_scale);
}

// K and I of I d(spin)/dt = -K omega on the nodes the particles touch, and C = sum_p N_a N_b
// m J, whose I^-1 C is the grid-to-particle-to-grid map of the transfers.
struct RotationalOperator {
  Eigen::MatrixXd stiffness;
  Eigen::VectorXd inertia;
  Eigen::MatrixXd consistent;
};

// Assembles the operator of the particles of a regular seeding of `patch` (per_cell x per_cell
// per cell). Periodic: the grid has two cells of margin around the patch and nodes wrap modulo
// the patch (no kernel reaches an edge); otherwise the patch is the whole grid, edges folded as
// the kernels do there. `disorder` > 0 moves each particle by up to +-disorder / 2 of its
// spacing along each axis. A column of K is minus the nodal moments of a unit nodal rotation:
// its rates at each particle (spin N, spin gradient grad N), the continuum's increment, the
// model's stress, the continuum's moment terms.
template <class Kernel>
RotationalOperator rotational_operator(const Polar& polar, Index patch, int per_cell, bool periodic,
                                       double disorder = 0.0) {
  const Index margin = periodic ? 2 : 0;
  const Index span = patch + 2 * margin;
  const grid::Grid<2> grid(
      Vec<2>(0.0, 0.0), Vec<2>(Vec<2>::Constant(cell * static_cast<double>(span))), {span, span});
  const auto seeding = particles::seed_box(
      grid, Vec<2>(Vec<2>::Constant(cell * static_cast<double>(margin))),
      Vec<2>(Vec<2>::Constant(cell * static_cast<double>(margin + patch))), per_cell);
  const Index nodes = periodic ? patch : patch + 1;
  auto dof = [&](Index grid_node) {
    auto ijk = grid.node_ijk(grid_node);
    for (auto& k : ijk) k = periodic ? ((k - margin) % patch + patch) % patch : k;
    return ijk[0] + nodes * ijk[1];
  };
  RotationalOperator op{Eigen::MatrixXd::Zero(nodes * nodes, nodes * nodes),
                        Eigen::VectorXd::Zero(nodes * nodes),
                        Eigen::MatrixXd::Zero(nodes * nodes, nodes * nodes)};
  const double mass_j = density * seeding.volume * polar.effective_micro_inertia();
  shape::Stencil<2, Kernel> s;
  std::uint32_t seed = 777;
  for (Vec<2> x : seeding.positions) {
    if (disorder > 0.0) {
      for (int d = 0; d < 2; ++d) x[d] += disorder * next_uniform(seed) * cell / per_cell;
    }
    s.compute(grid, x, seeding.half_width);
    for (std::size_t b = 0; b < s.node.size(); ++b) {
      op.inertia[dof(s.node[b])] += s.weight[b] * mass_j;
      continuum::ParticleRates<2, 1> rates{};
      rates.velocity_gradient.setZero();
      rates.spin[0] = s.weight[b];
      rates.spin_gradient[0] = {s.gradient[b][0], s.gradient[b][1]};
      Model::stress_type stress = Model::stress_type::Zero();
      const auto increment = Polar::rotate_and_increment(rates, 1.0, stress);
      Model::state_type state{};
      polar.model().update(stress, state, increment);
      double weighted[1];
      std::array<double, 2> by_gradient[1];
      Polar::rotational_force_terms(stress, seeding.volume, weighted, by_gradient);
      for (std::size_t a = 0; a < s.node.size(); ++a) {
        const double moment = s.weight[a] * weighted[0] + s.gradient[a][0] * by_gradient[0][0] +
                              s.gradient[a][1] * by_gradient[0][1];
        op.stiffness(dof(s.node[a]), dof(s.node[b])) -= moment;
        op.consistent(dof(s.node[a]), dof(s.node[b])) += s.weight[a] * s.weight[b] * mass_j;
      }
    }
  }
  return op;
}

// The largest eigenvalue of I^-1 K (omega_max^2) by power iteration from a fixed pseudo-random
// start, as the Rayleigh quotient of the last iterate.
double power_iteration(const RotationalOperator& op, int iterations = 3000) {
  Eigen::VectorXd v(op.inertia.size());
  std::uint32_t seed = 12345;
  for (Index i = 0; i < v.size(); ++i) v[i] = next_uniform(seed);
  double estimate = 0.0;
  for (int k = 0; k < iterations; ++k) {
    const Eigen::VectorXd kv = op.stiffness * v;
    estimate = v.dot(kv) / v.dot(op.inertia.cwiseProduct(v));
    v = kv.cwiseQuotient(op.inertia);
    v /= v.norm();
  }
  return estimate;
}

// The same from a dense symmetric solver on I^-1/2 K I^-1/2, to show the iteration converged.
double dense_largest(const RotationalOperator& op) {
  const Eigen::VectorXd scale = op.inertia.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd a = scale.asDiagonal() * op.stiffness * scale.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

// omega_max^2 the continuum's bound implies: (2 / dt)^2.
double bound_of(const Polar& polar) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.1), {10, 10});
  const double dt = polar.stable_time_step(grid, density);
  return 4.0 / (dt * dt);
}

struct Mix {
  const char* name;
  Model model;
};
const Mix mixes[] = {{"corn: 4 B/h^2 = 4 Gc", corn()},
                     {"bending-dominated: l = 30 mm", corn(0.03)},
                     {"coupling-dominated: l = 2 mm", corn(0.002)},
                     {"no coupling: Gc = 0", corn(0.01, 0.0)}};

// Checks, for one kernel, that the bound is at least the operator's largest eigenvalue and at
// most `factor` times it, for each mix, 1 to 4 particles per cell and axis, periodic and
// bounded patches of 6 x 6 cells.
template <class Kernel>
void check_bound(double factor) {
  double worst = 0.0;
  for (const Mix& mix : mixes) {
    const Polar polar(mix.model, {.micro_inertia = corn_j});
    const double bound = bound_of(polar);
    for (int per_cell = 1; per_cell <= 4; ++per_cell) {
      for (bool periodic : {true, false}) {
        const auto op = rotational_operator<Kernel>(polar, 6, per_cell, periodic);
        const double largest = power_iteration(op);
        const std::string mix_name = mix.name;
        CAPTURE(mix_name);
        CAPTURE(per_cell);
        CAPTURE(periodic);
        // The Rayleigh quotient converges from below; next to the edges the top modes
        // cluster, and 3000 iterations get within 1e-5 of the dense solver's value.
        const double dense = dense_largest(op);
        CHECK(largest == doctest::Approx(dense).epsilon(1e-5));
        CHECK(bound >= std::max(largest, dense) * (1.0 - 1e-12));
        CHECK(bound <= factor * largest);
        worst = std::max(worst, bound / largest);
      }
    }
  }
  MESSAGE(std::string(Kernel::name()) << ": bound / largest eigenvalue at most " << worst);
}
}  // namespace

TEST_CASE("the rotational operator of a regular 2 x 2 patch has the derived eigenvalue") {
  // The derivation (docs/theory/mpm.md) for the linear kernel: the top mode alternates along
  // one axis and is constant along the other, omega_max^2 rho J = 4 B / h^2 + 4 Gc rho_q with
  // rho_q = mean (1 - 2 xi)^2 = 1/4 at xi = 1/4, 3/4. For corn 4 B / h^2 = 4 Gc, so the old
  // sum over both axes plus 4 Gc (12 Gc) was 2.4 times the true value (5 Gc).
  const Polar polar(corn(), {.micro_inertia = corn_j});
  const auto op = rotational_operator<shape::Linear>(polar, 6, 2, true);
  const double gc4 = 4.0 * polar.model().cosserat_shear_modulus();
  const double expected = (gc4 + 0.25 * gc4) / (density * corn_j);
  CHECK(power_iteration(op) == doctest::Approx(expected).epsilon(1e-9));
  // The operator is symmetric, and its smallest eigenvalue is the symbol's lowest corner,
  // alternating along both axes: 4 B rho_q 2 / h^2 + 4 Gc rho_q^2 = 4 Gc (1/2 + 1/16).
  CHECK((op.stiffness - op.stiffness.transpose()).norm() <= 1e-12 * op.stiffness.norm());
  const Eigen::VectorXd scale = op.inertia.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * op.stiffness * scale.asDiagonal();
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .minCoeff() == doctest::Approx(gc4 * (0.5 + 1.0 / 16.0) / (density * corn_j)));
  const double old_bound =
      (gc4 + 8.0 * polar.model().bending_modulus() / (cell * cell)) / (density * corn_j);
  CHECK(old_bound / expected == doctest::Approx(2.4).epsilon(1e-9));
  // The new bound: rho_q -> 1/3, 4/3 Gc instead of Gc.
  CHECK(bound_of(polar) / expected == doctest::Approx(16.0 / 15.0).epsilon(1e-9));
}

TEST_CASE("the rotational step bound holds for every kernel and is not wastefully small") {
  // Factors (omega^2; the step's factor is the square root): Linear and GIMP attain
  // max(4 Gc, 4 B / h^2 + 4 Gc rho_q), rho_q in [0, 1/3), so the bound's 1/3 costs at most
  // 4/3 (one particle per cell, 4 B / h^2 = 4 Gc). The B-splines' bending eigenvalues lie far
  // below 4 B / h^2 (measured 1.1 to 2.5 B / h^2, the most at folded edges), which the
  // bending-dominated mix shows: up to 3.05 and 3.81 there (1.33 for corn).
  check_bound<shape::Linear>(4.0 / 3.0 + 1e-9);
  check_bound<shape::GIMP>(4.0 / 3.0 + 1e-9);
  check_bound<shape::QuadraticBSpline>(3.1);
  check_bound<shape::CubicBSpline>(3.9);
}

TEST_CASE("particles out of their regular places stay within the margin of cfl = 0.5") {
  // The bound is exact for regular arrangements only; displaced particles make nodes of
  // unequal mass. The engine steps at cfl x the bound, which holds up to omega_max^2 =
  // bound / cfl^2 = 4 x bound at the default cfl = 0.5.
  double worst = 0.0;
  for (const Mix& mix : mixes) {
    const Polar polar(mix.model, {.micro_inertia = corn_j});
    for (int per_cell = 1; per_cell <= 3; ++per_cell) {
      const double largest =
          dense_largest(rotational_operator<shape::Linear>(polar, 6, per_cell, true, 0.8));
      worst = std::max(worst, largest / bound_of(polar));
    }
  }
  MESSAGE("displaced particles: largest eigenvalue / bound at most " << worst);
  CHECK(worst > 1.0);                // the regular arrangement's bound is not a bound here ...
  CHECK(worst < 1.0 / (0.5 * 0.5));  // ... but cfl = 0.5 covers it
}

namespace {
// The largest |theta| over `steps` steps of the grid update alone, I w' = -K theta by the
// engine's explicit scheme (w += dt I^-1 (-K theta), theta += dt w), from a pseudo-random
// theta of at most 1 and w = 0.
double grid_update_growth(const RotationalOperator& op, double dt, int steps) {
  Eigen::VectorXd theta(op.inertia.size());
  std::uint32_t seed = 99;
  for (Index i = 0; i < theta.size(); ++i) theta[i] = 2.0 * next_uniform(seed);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(theta.size());
  double largest = 0.0;
  for (int k = 0; k < steps; ++k) {
    w -= dt * (op.stiffness * theta).cwiseQuotient(op.inertia);
    theta += dt * w;
    largest = std::max(largest, theta.cwiseAbs().maxCoeff());
  }
  return largest;
}

// The critical steps of the particle schemes with FLIP (flip = 1), from the operator. With
// particle velocities N c, the start-of-step grid velocity is P c, P = I^-1 C, and per step
//   USL:  c' = c - dt A theta,  theta' = theta + dt (P c - dt A theta),       A = I^-1 K,
//   MUSL: c' = c - dt A theta,  theta' = theta + dt P c'   (the remapped velocity).
// MUSL's map has determinant 1 and is stable while dt^2 max eig(P A) <= 4; USL's loses energy
// (det = 1 - dt^2 (1 - P) A per mode) and is stable up to dt^2 lambda (2 - P) <= 4 per mode,
// between 1/sqrt(2) and 1 times the grid's critical step 2 / sqrt(max eig A).
double musl_critical_step(const RotationalOperator& op) {
  const Eigen::VectorXd inverse = op.inertia.cwiseInverse();
  const Eigen::MatrixXd product =
      inverse.asDiagonal() * op.consistent * inverse.asDiagonal() * op.stiffness;
  const double largest =
      Eigen::EigenSolver<Eigen::MatrixXd>(product, false).eigenvalues().real().maxCoeff();
  return 2.0 / std::sqrt(largest);
}

double usl_spectral_radius(const RotationalOperator& op, double dt) {
  const Index n = op.inertia.size();
  const Eigen::VectorXd inverse = op.inertia.cwiseInverse();
  const Eigen::MatrixXd a = inverse.asDiagonal() * op.stiffness;
  const Eigen::MatrixXd p = inverse.asDiagonal() * op.consistent;
  Eigen::MatrixXd step(2 * n, 2 * n);
  step << Eigen::MatrixXd::Identity(n, n), -dt * a, dt * p,
      Eigen::MatrixXd::Identity(n, n) - dt * dt * a;
  return Eigen::EigenSolver<Eigen::MatrixXd>(step, false).eigenvalues().cwiseAbs().maxCoeff();
}

// By bisection between 0.7 and 1.01 times the grid's critical step (USL's range, above), to
// 5e-6 of it.
double usl_critical_step(const RotationalOperator& op) {
  const double grid = 2.0 / std::sqrt(dense_largest(op));
  double stable = 0.7 * grid;
  double unstable = 1.01 * grid;
  for (int k = 0; k < 16; ++k) {
    const double dt = 0.5 * (stable + unstable);
    (usl_spectral_radius(op, dt) <= 1.0 + 1e-6 ? stable : unstable) = dt;
  }
  return stable;
}

// A Cosserat elastic block filling an 8 x 8-cell grid (2 x 2 particles per cell), translations
// held on every face, rotation free, at rest but for a pseudo-random micro-spin of at most
// 1 rad/s. J is a thousandth of corn's, so the rotational modes are 60 times faster than the
// translational ones and the coupling shifts omega_max^2 by less than 1e-3.
constexpr double block_j = 1e-3 * corn_j;

template <class Scheme>
double engine_growth(double dt, int steps) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(8 * cell, 8 * cell), {8, 8});
  SimulationParameters<2> parameters;
  parameters.time_step = dt;
  parameters.allow_unstable_time_step = true;
  parameters.flip_fraction = 1.0;
  parameters.threads = 1;
  Simulation<2, shape::Linear, Polar, contact::SingleField, Scheme> sim(
      grid, Polar(corn(), {.micro_inertia = block_j}), parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(8 * cell, 8 * cell), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  for (int face = 0; face < 4; ++face) {
    sim.boundary_conditions().set(face, grid::BoundaryKind::fixed);
  }
  auto& spin = sim.particles().template get<particles::field::MicroSpin>();
  std::uint32_t seed = 2024;
  for (auto& value : spin) value = 2.0 * next_uniform(seed);
  double largest = 0.0;
  for (int k = 0; k < steps; ++k) {
    try {
      sim.step(dt);
    } catch (const Error&) {  // the engine stops a run that turned non-finite
      return std::numeric_limits<double>::infinity();
    }
    for (double value : spin) {
      largest = std::max(largest, std::isfinite(value) ? std::abs(value) : HUGE_VAL);
    }
  }
  return largest;
}
}  // namespace

TEST_CASE("explicit steps: stable just below the bound, unstable just above the critical step") {
  const Polar polar(corn(), {.micro_inertia = block_j});
  const auto op = rotational_operator<shape::Linear>(polar, 8, 2, false);
  const double critical = 2.0 / std::sqrt(power_iteration(op));
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(8 * cell, 8 * cell), {8, 8});
  const double bound = stable_time_step(polar, grid, density);
  // The rotational bound limits this block, 16/15 of the true omega_max^2 (derived above).
  REQUIRE(bound == doctest::Approx(polar.stable_time_step(grid, density)));
  CHECK(bound / critical == doctest::Approx(std::sqrt(15.0 / 16.0)).epsilon(1e-3));

  // The grid update alone: bounded (started at 1, a stable oscillation stays within a few
  // times that), or growing by about 2.4 per step at 1.1 x critical.
  const double below = grid_update_growth(op, 0.99 * bound, 5000);
  const double above = grid_update_growth(op, 1.1 * critical, 200);
  MESSAGE("grid update: critical step " << critical << " s, bound " << bound
                                        << " s; largest |theta| " << below << " at 0.99 x bound, "
                                        << above << " at 1.1 x critical");
  CHECK(below < 10.0);
  CHECK(above > 1e6);

  // The engine with its transfers (flip = 1): the particle schemes' own critical steps follow
  // from the same operator, and the engine is stable 3 % below and unstable 3 % above each.
  // USL loses a quarter of the grid's step here (the top mode's P = 1/4: sqrt(4 / 7) of it),
  // MUSL gains (its remap filters the top mode); cfl = 0.5 covers USL's worst, 1/sqrt(2).
  const double usl = usl_critical_step(op);
  const double musl = musl_critical_step(op);
  MESSAGE("critical steps / grid's: USL " << usl / critical << ", MUSL " << musl / critical);
  CHECK(usl / critical == doctest::Approx(std::sqrt(4.0 / 7.0)).epsilon(0.02));
  CHECK(usl > 0.5 * bound);  // the default step, cfl = 0.5
  CHECK(musl > critical);
  const double usl_below = engine_growth<integrator::USL>(0.97 * usl, 1000);
  const double usl_above = engine_growth<integrator::USL>(1.03 * usl, 1000);
  const double musl_below = engine_growth<integrator::MUSL>(0.97 * musl, 1000);
  const double musl_above = engine_growth<integrator::MUSL>(1.03 * musl, 1000);
  MESSAGE("engine, largest micro-spin (from 1 rad/s): USL "
          << usl_below << " at 0.97 x, " << usl_above << " at 1.03 x; MUSL " << musl_below
          << " at 0.97 x, " << musl_above << " at 1.03 x");
  CHECK(usl_below < 10.0);
  CHECK(usl_above > 1e6);
  CHECK(musl_below < 10.0);
  CHECK(musl_above > 1e6);
}

TEST_CASE("micro_inertia_scale: checked, carried to the nodes, and the step grows with it") {
  const Model model = corn();
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(Polar(model, {.micro_inertia = corn_j, .micro_inertia_scale = bad}),
                         doctest::Contains("micro_inertia_scale = "), Error);
  }
  CHECK_THROWS_WITH_AS(Polar(model, {.micro_inertia = corn_j, .micro_inertia_scale = -2.0}),
                       "continuum::Cosserat: micro_inertia_scale = -2 must be positive and "
                       "finite (valid range (0, inf))",
                       Error);

  // The scaled inertia reaches the particles and the nodes: sum_i I_i = sum_p m_p J s.
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(12 * cell, 8 * cell), {12, 8});
  const auto seeding =
      particles::seed_box(grid, Vec<2>(2 * cell, 0.0), Vec<2>(10 * cell, 5 * cell), 2);
  auto inertia_at_nodes = [&](double scale) {
    Simulation<2, shape::Linear, Polar> sim(
        grid, Polar(model, {.micro_inertia = corn_j, .micro_inertia_scale = scale}));
    sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
    for (double j : sim.particles().get<particles::field::MicroInertia>()) {
      CHECK(j == doctest::Approx(corn_j * scale).epsilon(1e-15));
    }
    sim.map_to_grid(true);
    return sim.nodes().rotational_inertia;
  };
  const auto plain = inertia_at_nodes(1.0);
  const auto scaled = inertia_at_nodes(16.0);
  double total = 0.0;
  for (std::size_t n = 0; n < plain.size(); ++n) {
    CHECK(scaled[n] == doctest::Approx(16.0 * plain[n]).epsilon(1e-14));
    total += scaled[n];
  }
  const double mass = density * seeding.volume * static_cast<double>(seeding.positions.size());
  CHECK(total == doctest::Approx(mass * corn_j * 16.0).epsilon(1e-12));

  // The rotational bound grows as sqrt(scale); at 16 it no longer limits corn on 10 mm cells,
  // where the p-wave bound h / sqrt((G + Gc) / rho) = 1.50e-4 s takes over.
  const Polar one(model, {.micro_inertia = corn_j});
  const Polar sixteen(model, {.micro_inertia = corn_j, .micro_inertia_scale = 16.0});
  const grid::Grid<2> paper(Vec<2>(0.0, 0.0), Vec<2>(1.2, 0.7), {120, 70});
  const double rotational = one.stable_time_step(paper, density);
  CHECK(sixteen.stable_time_step(paper, density) == doctest::Approx(4.0 * rotational));
  const double p_wave = cell / std::sqrt(model.p_wave_modulus() / density);
  CHECK(p_wave == doctest::Approx(1.50169e-4).epsilon(1e-5));
  CHECK(stable_time_step(one, paper, density) == doctest::Approx(rotational));
  CHECK(rotational < p_wave);
  CHECK(stable_time_step(sixteen, paper, density) == doctest::Approx(p_wave));
}
