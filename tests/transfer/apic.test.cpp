// The APIC transfer (transfer/apic.hpp): an affine velocity field is carried exactly, and a
// spinning elastic disk keeps its angular momentum, where PIC loses it.
#include <doctest/doctest.h>

#include <cmath>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/transfer/apic.hpp"

namespace {
using namespace cosmpm;

// MUSL: USL strains the disk's edge particles with v_i + dt f_i / m_i at nodes of tiny mass,
// which blows the spinning disk up within 30 steps whatever the transfer.
template <class Kernel, class Transfer, class Scheme = integrator::MUSL>
using DiskSim =
    Simulation<2, Kernel, test::ElasticContinuum, contact::SingleField, Scheme, Transfer>;

const Vec<2> centre(0.5, 0.5);

// D_p = sum_k N_k (x_k - x_p)(x_k - x_p)^T over the particle's full tensor-product stencil
// (shape::Stencil, independent of the engine's separable transfers).
template <class Kernel>
Mat<2> inertia_of_stencil(const grid::Grid<2>& grid, const Vec<2>& x, const Vec<2>& half_width) {
  shape::Stencil<2, Kernel> s;
  s.compute(grid, x, half_width);
  Mat<2> d = Mat<2>::Zero();
  for (int k = 0; k < s.size; ++k) {
    const Vec<2> r = grid.node_position(s.node[k]) - x;
    d += s.weight[k] * r * r.transpose();
  }
  return d;
}

// An elastic disk of radius 0.3 m spinning at omega about the grid's centre; with
// `affine_start`, each particle also carries the rotation's affine part C = grad v
// (B_p = C D_p), otherwise it starts with B_p = 0.
template <class Sim>
Sim spinning_disk(double omega, double flip_fraction = 1.0, bool affine_start = false) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {40, 40});
  SimulationParameters<2> parameters;
  parameters.flip_fraction = flip_fraction;
  parameters.threads = 1;
  Sim sim(grid, test::Elastic(1e5, 0.3), parameters);
  const auto box = particles::seed_box(grid, Vec<2>(0.2, 0.2), Vec<2>(0.8, 0.8), 2);
  std::vector<Vec<2>> disk;
  for (const auto& x : box.positions) {
    if ((x - centre).norm() < 0.3) disk.push_back(x);
  }
  sim.add_particles(disk, box.volume, 1000.0, box.half_width);
  Mat<2> rotation;
  rotation << 0.0, -omega, omega, 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const Vec<2> x = sim.particles().template get<particles::field::Position<2>>()[p];
    sim.particles().template get<particles::field::Velocity<2>>()[p] = rotation * (x - centre);
    if constexpr (Sim::transfer_type::affine) {
      sim.particles().template get<particles::field::AffineMoment<2>>()[p] =
          affine_start ? Mat<2>(rotation * inertia_of_stencil<typename Sim::kernel_type>(
                                               sim.grid(), x, box.half_width))
                       : Mat<2>(Mat<2>::Zero());
    }
  }
  return sim;
}

// Angular momentum about the centre on the grid: sum_i (x_i - c) x p_i, after a
// particle-to-grid map (which also carries APIC's affine part of each particle).
template <class Sim>
double grid_angular_momentum(Sim& sim) {
  sim.map_to_grid(false);
  double l = 0.0;
  for (Index n = 0; n < sim.grid().node_count(); ++n) {
    const Vec<2> r = sim.grid().node_position(n) - centre;
    const Vec<2>& p = sim.nodes().momentum[n];
    l += r[0] * p[1] - r[1] * p[0];
  }
  return l;
}

template <class Kernel, class Scheme = integrator::MUSL>
void check_angular_momentum_kept() {
  auto sim = spinning_disk<DiskSim<Kernel, transfer::APIC, Scheme>>(2.0);
  const double start = grid_angular_momentum(sim);
  const double dt = sim.time_step();
  for (int i = 0; i < 400; ++i) sim.step(dt);
  const double end = grid_angular_momentum(sim);
  // The transfers and the momentum update conserve it; what is left is round-off of ~1,800
  // particles' sums over 400 steps (relative 1e-10 is far above it and far below any loss).
  CHECK(std::abs(end - start) <= 1e-10 * std::abs(start));
  // The disk has turned by omega t = 2 rad/s * 400 dt (more than a quarter turn).
  CHECK(2.0 * sim.time() > 0.5);
}
}  // namespace

TEST_CASE("APIC: a rigid rotation goes to the grid and back exactly") {
  // Particles carry v = C (x - c) and B = C D (C = omega [[0, -1], [1, 0]]). The particle-to-
  // grid map must give every node with mass v(x_i) exactly (each particle spreads the field
  // itself), and the grid-to-particle map must return v(x_p) and B = C D.
  const double omega = 1.5;
  Mat<2> rotation;
  rotation << 0.0, -omega, omega, 0.0;
  const auto check = [&]<class Kernel>(Kernel) {
    CAPTURE(std::string(Kernel::name()));
    auto sim = spinning_disk<DiskSim<Kernel, transfer::APIC>>(omega, 1.0, true);
    const auto x = sim.particles().template get<particles::field::Position<2>>();
    sim.map_to_grid(false);
    double node_error = 0.0;
    for (Index n = 0; n < sim.grid().node_count(); ++n) {
      if (sim.nodes().mass[n] <= 0.0) continue;
      const Vec<2> v = sim.nodes().momentum[n] / sim.nodes().mass[n];
      node_error =
          std::max(node_error, (v - rotation * (sim.grid().node_position(n) - centre)).norm());
    }
    CHECK(node_error < 1e-12);  // m/s, speeds up to 1.1 m/s
    // A step of (almost) zero length and no forces: the grid field comes back.
    sim.update_grid(1e-9);
    sim.map_to_particles(1e-9);
    const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
    const auto& b = sim.particles().template get<particles::field::AffineMoment<2>>();
    double velocity_error = 0.0, moment_error = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) {
      velocity_error = std::max(velocity_error, (v[p] - rotation * (x[p] - centre)).norm());
      const Mat<2> d = inertia_of_stencil<Kernel>(sim.grid(), x[p], Vec<2>(0.25, 0.25));
      moment_error = std::max(moment_error, (b[p] - rotation * d).cwiseAbs().maxCoeff());
    }
    CHECK(velocity_error < 1e-12);  // m/s
    CHECK(moment_error < 1e-15);    // m^2/s, against |C D| ~ omega h^2 / 4 ~ 2e-4
  };
  check(shape::GIMP{});
  check(shape::QuadraticBSpline{});
  check(shape::CubicBSpline{});
}

TEST_CASE("APIC: a spinning elastic disk keeps its angular momentum, every kernel it takes") {
  // shape::Linear is rejected at compile time (tests/compile_fail/apic_with_linear.cpp).
  check_angular_momentum_kept<shape::GIMP>();
  check_angular_momentum_kept<shape::QuadraticBSpline>();
  check_angular_momentum_kept<shape::CubicBSpline>();
  check_angular_momentum_kept<shape::QuadraticBSpline, integrator::USL>();
  check_angular_momentum_kept<shape::QuadraticBSpline, integrator::USF>();
}

TEST_CASE("APIC: the problem it solves, PIC loses the spinning disk's angular momentum") {
  auto sim = spinning_disk<DiskSim<shape::Linear, transfer::FlipBlend>>(2.0, /*PIC*/ 0.0);
  const double start = grid_angular_momentum(sim);
  const double dt = sim.time_step();
  for (int i = 0; i < 400; ++i) sim.step(dt);
  CHECK(grid_angular_momentum(sim) < 0.9 * start);  // more than 10 % lost
}

TEST_CASE("APIC: a FLIP fraction with APIC is an error naming both") {
  CHECK_THROWS_WITH_AS((spinning_disk<DiskSim<shape::GIMP, transfer::APIC>>(1.0, 0.95)),
                       doctest::Contains("flip_fraction = 0.95 blends FLIP into APIC"), Error);
}
