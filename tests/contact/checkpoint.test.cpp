// A blade run restarted from a checkpoint continues bit-identically: the blade's pose is part
// of the checkpoint (RigidContact::checkpoint_values).
#include <doctest/doctest.h>

#include <filesystem>

#include "contact_test_support.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "test_output.hpp"

namespace {
using namespace cosmpm;

test::RigidSim make_blade_run() {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.6, 0.3), {40, 20});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  contact::RigidContact<2> law;
  law.add_body(contact::RigidBody<2>::box(Vec<2>(0.1, 0.0), Vec<2>(0.11, 0.28))
                   .set_velocity(Vec<2>(0.2, 0.0))
                   .set_angular_velocity(0.05),
               contact::Interface::coulomb_angle(14.0));
  test::RigidSim sim(grid, test::Elastic(test::youngs_modulus, test::poisson_ratio), parameters,
                     law);
  sim.boundary_conditions().set(2, grid::BoundaryKind::fixed);
  test::add_at_rest(sim, particles::seed_box(grid, Vec<2>(0.11, 0.0), Vec<2>(0.6, 0.15), 2));
  return sim;
}

}  // namespace

TEST_CASE("checkpoint: a blade run restarts bit-identically, the blade's pose included") {
  const auto dir = test::output_root() / "contact";
  std::filesystem::create_directories(dir);
  const double dt = 2e-4;  // below the stable 0.5 * 0.015 / 36.7 = 2.04e-4 s
  auto straight = make_blade_run();
  for (int i = 0; i < 60; ++i) straight.step(dt);
  auto before = make_blade_run();
  for (int i = 0; i < 30; ++i) before.step(dt);
  io::save_checkpoint(before, dir / "blade_at_30.h5");
  auto restarted = make_blade_run();
  io::load_checkpoint(restarted, dir / "blade_at_30.h5");
  CHECK(restarted.contact().body(0).reference_point() ==
        before.contact().body(0).reference_point());
  CHECK(restarted.contact().body(0).angle() == before.contact().body(0).angle());
  for (int i = 0; i < 30; ++i) restarted.step(dt);
  CHECK(restarted.contact().body(0).vertices() == straight.contact().body(0).vertices());
  CHECK(restarted.contact().force_on_material(0) == straight.contact().force_on_material(0));
  const auto& xa = restarted.particles().get<particles::field::Position<2>>();
  const auto& xb = straight.particles().get<particles::field::Position<2>>();
  CHECK(xa == xb);
  CHECK(straight.contact().force_on_material(0)[0] > 0.0);  // the blade did push

  // A pose vector of the wrong length is refused.
  CHECK_THROWS_AS(restarted.contact().restore_checkpoint_values({0.0, 0.0}), Error);
}

namespace {

using Elastic3 = material::LinearElastic<double, 3>;
using BladeSim3 = Simulation<3, shape::Linear, continuum::Classical<Elastic3>,
                             contact::RigidContact<3>, integrator::MUSL>;

// The 3D twin: a blade turning about a tilted axis while it moves, so the rotation matrix,
// not only the position, must come back bit for bit.
BladeSim3 make_blade_run_3d() {
  const grid::Grid<3> grid(Vec<3>::Zero(), Vec<3>(0.45, 0.09, 0.3), {30, 6, 20});
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  contact::RigidContact<3> law;
  law.add_body(contact::RigidBody<3>::box(Vec<3>(0.1, 0.02, 0.0), Vec<3>(0.11, 0.07, 0.28))
                   .set_velocity(Vec<3>(0.2, 0.0, 0.0))
                   .set_angular_velocity(Vec<3>(0.02, 0.03, 0.05)),
               contact::Interface::coulomb_angle(14.0));
  BladeSim3 sim(grid, Elastic3(test::youngs_modulus, test::poisson_ratio), parameters, law);
  sim.boundary_conditions().set(grid::BoundaryConditions<3>::face(2, false),
                                grid::BoundaryKind::fixed);
  test::add_at_rest(sim,
                    particles::seed_box(grid, Vec<3>(0.11, 0.0, 0.0), Vec<3>(0.45, 0.09, 0.15), 2));
  return sim;
}

}  // namespace

TEST_CASE("checkpoint 3D: a turning blade's run restarts bit-identically") {
  const auto dir = test::output_root() / "contact";
  std::filesystem::create_directories(dir);
  const double dt = 2e-4;  // below the stable 0.5 * 0.015 / 36.7 = 2.04e-4 s
  auto straight = make_blade_run_3d();
  for (int i = 0; i < 40; ++i) straight.step(dt);
  auto before = make_blade_run_3d();
  for (int i = 0; i < 20; ++i) before.step(dt);
  io::save_checkpoint(before, dir / "blade_3d_at_20.h5");
  auto restarted = make_blade_run_3d();
  io::load_checkpoint(restarted, dir / "blade_3d_at_20.h5");
  CHECK(restarted.contact().body(0).rotation() == before.contact().body(0).rotation());
  for (int i = 0; i < 20; ++i) restarted.step(dt);
  CHECK(restarted.contact().body(0).vertices() == straight.contact().body(0).vertices());
  CHECK(restarted.contact().force_on_material(0) == straight.contact().force_on_material(0));
  CHECK(restarted.particles().get<particles::field::Position<3>>() ==
        straight.particles().get<particles::field::Position<3>>());
  CHECK(straight.contact().force_on_material(0)[0] > 0.0);  // the blade did push
  CHECK_THROWS_AS(restarted.contact().restore_checkpoint_values({0.0, 0.0, 0.0}), Error);
}
