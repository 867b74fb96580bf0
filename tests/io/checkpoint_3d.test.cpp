// Checkpoint/restart at Dim = 3: a restarted run continues bit-identically (compared with ==,
// tolerance none) for every scheme and APIC, with a 3D Mohr-Coulomb block whose plastic state
// changes during the run; a 2D checkpoint is refused by a 3D simulation, naming the mismatch.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <type_traits>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/simulation.hpp"
#include "cosmpm/transfer/apic.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;
using namespace cosmpm::test_io;
namespace field = particles::field;
using Soil3 = material::MohrCoulomb<double, 3>;

template <class Kernel, class Scheme, class Transfer = transfer::FlipBlend>
using Sim3 =
    Simulation<3, Kernel, continuum::Classical<Soil3>, contact::SingleField, Scheme, Transfer>;

const grid::Grid<3> block_grid(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.6, 0.4, 0.6), {6, 4, 6});

// A cohesionless block on a fixed floor, thrown sideways (v_x, v_y growing with height): it
// shears and yields, so the plastic state changes every step.
template <class S>
S make_sim(int threads = 0) {
  SimulationParameters<3> parameters;
  parameters.threads = threads;
  if constexpr (!S::transfer_type::affine) parameters.flip_fraction = 0.95;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  parameters.time_step = 2e-4;  // below the stable step 0.1 m / 64 m/s = 1.6e-3 s
  S sim(block_grid,
        Soil3({.youngs_modulus = 2.76e6,
               .poisson_ratio = 0.2,
               .friction_angle_deg = 26.0,
               .dilatancy_angle_deg = 2.0}),
        parameters);
  const auto seeding =
      particles::seed_box(block_grid, Vec<3>(0.2, 0.1, 0.0), Vec<3>(0.4, 0.3, 0.3), 2);
  sim.add_particles(seeding.positions, seeding.volume, 778.0, seeding.half_width);
  auto& v = sim.particles().template get<field::Velocity<3>>();
  const auto& x = sim.particles().template get<field::Position<3>>();
  for (std::size_t p = 0; p < v.size(); ++p) v[p] = Vec<3>(0.5 * x[p][2], 0.3 * x[p][2], 0.0);
  sim.boundary_conditions().set(grid::BoundaryConditions<3>::face(2, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

template <class Store>
void check_identical(const Store& a, const Store& b) {
  REQUIRE(a.size() == b.size());
  a.for_each_field([&](auto tag, const auto& column) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const auto& other = b.template get<Tag>();
    bool equal = true;
    for (std::size_t p = 0; p < column.size(); ++p) {
      if constexpr (std::is_trivially_copyable_v<V> && !std::is_arithmetic_v<V> &&
                    !requires { V::RowsAtCompileTime; }) {
        equal = equal && std::memcmp(&column[p], &other[p], sizeof(V)) == 0;
      } else {
        equal = equal && column[p] == other[p];
      }
    }
    CHECK_MESSAGE(equal, std::string(Tag::label()));
  });
}

template <class S>
void check_restart(const std::string& name, int restart_threads) {
  const auto dir = output_dir("restart_3d_" + name);
  const int first = 30, second = 25;
  const double dt = 2e-4;
  auto straight = make_sim<S>();
  for (int i = 0; i < first + second; ++i) straight.step(dt);
  auto before = make_sim<S>();
  for (int i = 0; i < first; ++i) before.step(dt);
  io::save_checkpoint(before, dir / "at_30.h5");
  auto restarted = make_sim<S>(restart_threads);
  io::load_checkpoint(restarted, dir / "at_30.h5");
  CHECK(restarted.step_count() == first);
  check_identical(restarted.particles(), before.particles());
  for (int i = 0; i < second; ++i) restarted.step(dt);
  CHECK(restarted.time() == straight.time());
  check_identical(restarted.particles(), straight.particles());
  // The run did something: particles moved and yielded.
  const auto& state = straight.particles().template get<field::MaterialState<Soil3>>();
  double plastic = 0.0;
  for (const auto& s : state) plastic = std::max(plastic, s.plastic_shear_strain);
  CHECK(plastic > 0.0);
  const auto& x = straight.particles().template get<field::Position<3>>();
  const auto& x0 = straight.particles().template get<field::InitialPosition<3>>();
  CHECK(x.back()[1] != x0.back()[1]);
}
}  // namespace

TEST_CASE("a 3D run restarted from a checkpoint continues bit-identically") {
  SUBCASE("USL") {
    check_restart<Sim3<shape::Linear, integrator::USL>>("usl", 0);
  }
  SUBCASE("MUSL, quadratic B-spline, restarted on one thread") {
    check_restart<Sim3<shape::QuadraticBSpline, integrator::MUSL>>("musl", 1);
  }
  SUBCASE("USF") {
    check_restart<Sim3<shape::Linear, integrator::USF>>("usf", 0);
  }
  SUBCASE("MUSL with APIC") {
    check_restart<Sim3<shape::QuadraticBSpline, integrator::MUSL, transfer::APIC>>("apic", 0);
  }
}

TEST_CASE("a 2D checkpoint is refused by a 3D simulation, naming the dimension") {
  const auto dir = output_dir("checkpoint_2d_into_3d");
  using Sim2 = Simulation<2, shape::Linear, continuum::Classical<material::MohrCoulomb<>>>;
  const grid::Grid<2> grid2(Vec<2>(0.0, 0.0), Vec<2>(0.6, 0.6), {6, 6});
  Sim2 sim2(grid2, material::MohrCoulomb<>(2.76e6, 0.2, 26.0, 2.0, 0.0));
  // As many particles as the 3D block (96), so the count check passes and the composition
  // check speaks.
  const auto seeding = particles::seed_box(grid2, Vec<2>(0.1, 0.0), Vec<2>(0.5, 0.6), 2);
  sim2.add_particles(seeding.positions, seeding.volume, 778.0, seeding.half_width);
  io::save_checkpoint(sim2, dir / "two.h5");
  auto sim3 = make_sim<Sim3<shape::Linear, integrator::USL>>();
  try {
    io::load_checkpoint(sim3, dir / "two.h5");
    FAIL("expected cosmpm::Error");
  } catch (const Error& error) {
    const std::string message = error.what();
    CAPTURE(message);
    CHECK(message.find("two.h5") != std::string::npos);
    CHECK(message.find("dim is '2' in the file but '3' in this simulation") != std::string::npos);
  }
}
