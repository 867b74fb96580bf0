// The Cosserat continuum in the engine: the elastic shear layer between rough plates against
// its boundary-layer solution, the classical limit, rigid rotation without stress, and
// angular momentum conservation.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/particles/store.hpp"
#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;
using CosseratModel = material::CosseratElastic<double>;
using Polar = continuum::Cosserat<CosseratModel>;

// A test-only contact law that makes a one-cell-wide grid periodic in x (every node of a
// row takes the row's mass-weighted velocity and spin) and drives the rough plates: the
// top row moves at `plate_velocity` without rotating, the bottom row is held.
struct PeriodicShearPlates {
  static constexpr const char* name() { return "periodic shear plates (test)"; }
  double plate_velocity = 0.0;
  void correct(contact::GridView<2>& view) {
    const auto& g = view.grid;
    for (Index j = 0; j < g.nodes(1); ++j) {
      double mass = 0.0, spin = 0.0;
      Vec<2> momentum = Vec<2>::Zero();
      for (Index i = 0; i < g.nodes(0); ++i) {
        const Index n = g.node_index({i, j});
        mass += view.mass[n];
        momentum += view.mass[n] * view.velocity[n];
        if (!view.spin.empty()) spin += view.mass[n] * view.spin[n];
      }
      for (Index i = 0; i < g.nodes(0); ++i) {
        const Index n = g.node_index({i, j});
        if (mass <= view.empty_mass) continue;
        view.velocity[n] = momentum / mass;
        if (!view.spin.empty()) view.spin[n] = spin / mass;
        if (j == 0 || j == g.nodes(1) - 1) {
          view.velocity[n] = Vec<2>(j == 0 ? 0.0 : plate_velocity, 0.0);
          if (!view.spin.empty()) view.spin[n] = 0.0;
        }
      }
    }
  }
  void advance(double, double) {}
};

struct ShearLayerResult {
  double displacement_error;  // max |u - u_exact| / U
  double rotation_error;      // max |omega - omega_exact| / max |omega_exact|
  double max_rotation;        // max |omega_exact|
};

// Analytic solution (derived in docs/theory/mpm.md, "Cosserat"): with B = 2 G l^2 and
// k^2 = 4 G Gc / (B (G + Gc)), the shear stress tau = s_yx is uniform and
//   omega(y) = -tau / (2 G) (1 - cosh(k (y - H/2)) / cosh(k H / 2)),
//   u(y) = tau y / G - tau Gc / (G (G + Gc)) (sinh(k (y - H/2)) + sinh(k H/2)) / (k cosh(k H/2)),
// tau fixed by u(H) = U.
ShearLayerResult shear_layer(double length_scale) {
  const double youngs = 1e6, poisson = 0.25, density = 1000.0;
  const double shear = youngs / (2.0 * (1.0 + poisson));
  const double cosserat_shear = shear;
  const double height = 0.1, top_displacement = 1e-3;
  const Index cells = 20;
  const double h = height / static_cast<double>(cells);
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(h, height), {1, cells});
  SimulationParameters<2> parameters;
  parameters.damping = 0.2;
  const Polar polar(CosseratModel(youngs, poisson, cosserat_shear, length_scale),
                    {.micro_inertia = 0.125 * 0.01 * 0.01});  // J of 10 mm grains, as in the paper
  Simulation<2, shape::Linear, Polar, PeriodicShearPlates, integrator::USL> sim(grid, polar,
                                                                                parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(h, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);

  const double dt = sim.time_step();
  const double ramp = 0.02;  // s to move the plate, then relax
  const double end = 0.3;
  while (sim.time() < end) {
    sim.contact().plate_velocity = sim.time() < ramp ? top_displacement / ramp : 0.0;
    sim.step(dt);
  }
  // The plate moved sum(v dt) over the ramp's whole steps; use what it really moved.
  const double moved = top_displacement / ramp * dt * std::ceil(ramp / dt - 1e-9);

  const double bending = 2.0 * shear * length_scale * length_scale;
  const double k = std::sqrt(4.0 * shear * cosserat_shear / (bending * (shear + cosserat_shear)));
  const double c = std::cosh(0.5 * k * height);
  const double factor = cosserat_shear / (shear * (shear + cosserat_shear));
  const double tau = moved / (height / shear - factor * 2.0 * std::tanh(0.5 * k * height) / k);
  auto omega_exact = [&](double y) {
    return -tau / (2.0 * shear) * (1.0 - std::cosh(k * (y - 0.5 * height)) / c);
  };
  auto u_exact = [&](double y) {
    return tau * y / shear - tau * factor *
                                 (std::sinh(k * (y - 0.5 * height)) + std::sinh(0.5 * k * height)) /
                                 (k * c);
  };
  const auto& x0 = sim.particles().get<particles::field::InitialPosition<2>>();
  const auto& x = sim.particles().get<particles::field::Position<2>>();
  const auto& omega = sim.particles().get<particles::field::MicroRotation>();
  ShearLayerResult result{0.0, 0.0, tau / (2.0 * shear)};
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double y = x0[p][1];
    result.displacement_error =
        std::max(result.displacement_error, std::abs((x[p][0] - x0[p][0]) - u_exact(y)) / moved);
    result.rotation_error = std::max(result.rotation_error, std::abs(omega[p] - omega_exact(y)));
  }
  result.rotation_error /= result.max_rotation;
  return result;
}
}  // namespace

TEST_CASE("Cosserat elastic shear layer between rough plates matches the boundary layer") {
  // l = 10 mm: boundary layer 1/k = 10 mm, two cells of 5 mm.
  const ShearLayerResult polar = shear_layer(0.01);
  MESSAGE("l = 10 mm: max |u - u_exact| / U = " << polar.displacement_error
                                                << ", max |omega - exact| / max|omega| = "
                                                << polar.rotation_error);
  // Tolerances: the layer is resolved by two cells, linear shape functions; 3 % of U for the
  // displacement and 10 % of the peak rotation for the rotation field.
  CHECK(polar.displacement_error <= 0.03);
  CHECK(polar.rotation_error <= 0.10);
}

TEST_CASE("Cosserat shear layer recovers the classical solution as l -> 0") {
  // l = 0.1 mm: the boundary layer (0.1 mm) is far below the cell; u is linear.
  const ShearLayerResult nearly_classical = shear_layer(1e-4);
  MESSAGE("l = 0.1 mm: max |u - u_exact| / U = " << nearly_classical.displacement_error);
  CHECK(nearly_classical.displacement_error <= 0.01);
}

namespace {
// A Cosserat elastic block spinning rigidly about its centre at `rate`; the particles'
// micro-spin is `micro_spin`.
auto rotating_block(double rate, double micro_spin) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {20, 20});
  Simulation<2, shape::Linear, Polar> sim(
      grid, Polar(CosseratModel(1e6, 0.25, 4e5, 0.01), {.micro_inertia = 1.25e-5}));
  const auto seeding = particles::seed_box(grid, Vec<2>(0.2, 0.2), Vec<2>(0.8, 0.8), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  auto& v = sim.particles().get<particles::field::Velocity<2>>();
  auto& spin = sim.particles().get<particles::field::MicroSpin>();
  const auto& x = sim.particles().get<particles::field::Position<2>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const Vec<2> r = x[p] - Vec<2>(0.5, 0.5);
    v[p] = rate * Vec<2>(-r[1], r[0]);
    spin[p] = micro_spin;
  }
  return sim;
}

// Largest stress component over particles more than 1.5 cells inside the block, where the
// grid velocity is the exact rigid field (at the edge, partly filled nodes average it).
template <class Sim>
double interior_stress(const Sim& sim) {
  const auto& x0 = sim.particles().template get<particles::field::InitialPosition<2>>();
  const auto& stress = sim.particles().template get<particles::field::Stress<CosseratModel>>();
  double largest = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    if ((x0[p] - Vec<2>(0.5, 0.5)).cwiseAbs().maxCoeff() > 0.3 - 0.075) continue;
    largest = std::max(largest, stress[p].cwiseAbs().maxCoeff());
  }
  return largest;
}
}  // namespace

TEST_CASE("a rigid rotation of a Cosserat body produces no stress") {
  const double rate = 0.5;  // rad/s
  auto matched = rotating_block(rate, rate);
  auto unmatched = rotating_block(rate, 0.0);
  const double dt = matched.time_step();
  matched.step(dt);
  unmatched.step(dt);
  // Reference: a micro-rotation lagging the rigid rotation deforms the body by
  // e_xy = -e_yx = rate dt, hence |s_xy| = 2 Gc rate dt (Gc = 4e5 Pa here).
  const double reference = 2.0 * 4e5 * rate * dt;
  MESSAGE("interior stress, spin matched: " << interior_stress(matched) << " Pa; spin not matched: "
                                            << interior_stress(unmatched) << " Pa");
  CHECK(interior_stress(unmatched) == doctest::Approx(reference).epsilon(1e-6));
  CHECK(interior_stress(matched) <= 1e-9 * reference);  // round-off
}

TEST_CASE("the Cosserat grid update conserves angular momentum exactly") {
  // Internal forces and moments exert no net torque on the grid: sum_i x_i x f_i + M_i = 0
  // for any stress (linear reproduction: sum_i x_i grad N_i = I, and sum_i N_i = 1). So the
  // grid's angular momentum sum_i (x_i x m_i v_i + I_i spin_i) is the same before and after
  // the update, to round-off, whatever the (non-symmetric) stress and couple stress.
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {20, 20});
  Simulation<2, shape::Linear, Polar> sim(
      grid, Polar(CosseratModel(1e5, 0.25, 8e4, 0.02), {.micro_inertia = 1.25e-5}));
  const auto seeding = particles::seed_box(grid, Vec<2>(0.3, 0.35), Vec<2>(0.7, 0.65), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  auto& stress = sim.particles().get<particles::field::Stress<CosseratModel>>();
  auto& v = sim.particles().get<particles::field::Velocity<2>>();
  auto& spin = sim.particles().get<particles::field::MicroSpin>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double phase = 0.37 * static_cast<double>(p);
    stress[p] << 100 * std::sin(phase), 50 * std::cos(phase), 10, 300 * std::sin(2 * phase),
        -200 * std::cos(3 * phase), 5 * std::sin(phase), -3 * std::cos(phase);
    v[p] = Vec<2>(0.01 * std::cos(phase), 0.02 * std::sin(phase));
    spin[p] = std::sin(5 * phase);
  }
  auto grid_angular_momentum = [&](const std::vector<Vec<2>>& velocity,
                                   const std::vector<double>& node_spin) {
    double total = 0.0;
    const auto& nodes = sim.nodes();
    for (Index n = 0; n < grid.node_count(); ++n) {
      const Vec<2> r = grid.node_position(n) - Vec<2>(0.5, 0.5);
      total += nodes.mass[n] * (r[0] * velocity[n][1] - r[1] * velocity[n][0]) +
               nodes.rotational_inertia[n] * node_spin[n];
    }
    return total;
  };
  sim.map_to_grid(true);
  sim.update_grid(1e-5);
  const double before = grid_angular_momentum(sim.nodes().momentum, sim.nodes().spin_momentum);
  const double after = grid_angular_momentum(sim.nodes().velocity, sim.nodes().spin);
  // Scale: the torque impulse each term alone would add, |sum x_i x f_i| dt.
  double torque = 0.0;
  for (Index n = 0; n < grid.node_count(); ++n) {
    const Vec<2> r = grid.node_position(n) - Vec<2>(0.5, 0.5);
    torque += std::abs(r[0] * sim.nodes().force[n][1] - r[1] * sim.nodes().force[n][0]);
  }
  MESSAGE("grid angular momentum before " << before << ", after " << after
                                          << ", torque impulse scale " << torque * 1e-5);
  CHECK(std::abs(after - before) <= 1e-12 * torque * 1e-5 + 1e-15);
  CHECK(torque * 1e-5 > 1e3 * std::abs(after - before));  // the check is not vacuous
}

TEST_CASE("Cosserat::update_rotations on a pack of particles is the per-particle update") {
  // The grid-to-particle map updates the rotations of a pack of particles at once; each lane
  // must take the one-particle arithmetic, bit for bit (FLIP blend and PIC, flip = 0).
  using Store = particles::Store<particles::field::MicroSpin, particles::field::MicroRotation>;
  constexpr int W = 2;
  for (const double flip : {0.97, 0.0}) {
    Store by_pack, by_particle;
    by_pack.append(2 * W);
    by_particle.append(2 * W);
    for (Index p = 0; p < 2 * W; ++p) {
      for (Store* store : {&by_pack, &by_particle}) {
        store->get<particles::field::MicroSpin>()[p] = std::sin(1.3 * static_cast<double>(p) + 0.2);
        store->get<particles::field::MicroRotation>()[p] = 0.01 * static_cast<double>(p) - 0.013;
      }
    }
    const double dt = 3.7e-5;
    const Pack<W> spin_grid{0.31, -1.7}, spin_acceleration{-250.0, 1.9e3};
    // The pack at particles 1 and 2, so the first and last particle must stay as they were.
    Polar::update_rotations(by_pack, 1, dt, flip, std::array<Pack<W>, 1>{spin_grid},
                            std::array<Pack<W>, 1>{spin_acceleration});
    for (int l = 0; l < W; ++l) {
      Polar::update_rotations(by_particle, 1 + l, dt, flip, std::array<double, 1>{spin_grid[l]},
                              std::array<double, 1>{spin_acceleration[l]});
    }
    for (Index p = 0; p < 2 * W; ++p) {
      CAPTURE(p);
      CHECK(by_pack.get<particles::field::MicroSpin>()[p] ==
            by_particle.get<particles::field::MicroSpin>()[p]);
      CHECK(by_pack.get<particles::field::MicroRotation>()[p] ==
            by_particle.get<particles::field::MicroRotation>()[p]);
    }
    // Not vacuous: the updated lanes moved.
    CHECK(by_pack.get<particles::field::MicroRotation>()[1] != 0.01 - 0.013);
    CHECK(by_pack.get<particles::field::MicroSpin>()[2] != std::sin(2.6 + 0.2));
  }
}
