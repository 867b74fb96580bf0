// The node range (stages/node_range.hpp): the dense node passes skip the nodes no particle
// reaches. Runs with it (the default) and without it (EngineState::prune_node_range off)
// must agree bit for bit, particles and every node field, while the range moves up and down
// with a block thrown upward.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "sliding_block.hpp"

namespace {
using namespace cosmpm;
using Soil = material::MohrCoulomb<>;
using Polar = continuum::Cosserat<material::CosseratElastic<double>>;

template <class Continuum>
Continuum make_continuum() {
  if constexpr (std::is_same_v<Continuum, continuum::Classical<Soil>>) {
    return continuum::Classical<Soil>(Soil({.youngs_modulus = 2e5,
                                            .poisson_ratio = 0.25,
                                            .friction_angle_deg = 26.0,
                                            .dilatancy_angle_deg = 2.0}));
  } else if constexpr (std::is_same_v<Continuum, Polar>) {
    return Polar(material::CosseratElastic<double>(2e5, 0.25, 8e4, 0.01),
                 {.micro_inertia = 1.25e-5});
  } else {
    return test::ElasticContinuum(test::Elastic(2e5, 0.25));
  }
}

// A block of 2 x 2 particles per cell thrown up at 0.8 m/s (and 0.1 m/s sideways) from near
// the fixed floor: it rises about 3 cm (3 cells; its lowest layer of particle blocks empties)
// and starts to fall back. `wide`: 10,800 particles
// on a grid 300 cells wide, so the range's node passes (over 4,096 nodes) run in parallel.
template <class Sim>
Sim thrown_up(int threads, bool prune, bool wide) {
  const double length = wide ? 3.0 : 0.4;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(length, 0.4), {wide ? 300 : 40, 40});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = threads;
  Sim sim(grid, make_continuum<typename Sim::continuum_type>(), parameters);
  sim.engine().prune_node_range = prune;
  const auto seeding =
      particles::seed_box(grid, Vec<2>(0.1, 0.02), Vec<2>(length - 0.2, wide ? 0.12 : 0.08), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
    v = Vec<2>(0.1, 0.8);
  }
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

// Particles and every node field, bit for bit.
template <class Sim>
void check_same(const Sim& a, const Sim& b, const std::string& label) {
  INFO(label);
  test::check_same_fields(a, b);
}

// Steps both runs through the throw, comparing them every 50 steps, and checks that the range
// left most nodes out and moved up, then down.
template <class Sim>
void check_throw(int threads, bool wide, const std::string& label) {
  Sim pruned = thrown_up<Sim>(threads, true, wide);
  Sim full = thrown_up<Sim>(threads, false, wide);
  const double dt = pruned.time_step();
  const Index nodes = pruned.grid().node_count();
  Index smallest = nodes, highest_first = 0, first_after_top = nodes;
  const int steps = static_cast<int>(0.15 / dt);  // up for 0.08 s, then down
  int full_ranges = 0;  // the run without the range: every node, every step
  for (int i = 1; i <= steps; ++i) {
    pruned.step(dt);
    full.step(dt);
    const NodeRange range = std::as_const(pruned).engine().node_range;
    full_ranges += std::as_const(full).engine().node_range.size() == nodes;
    smallest = std::min(smallest, range.size());
    if (range.first > highest_first) {
      highest_first = range.first;
      first_after_top = range.first;
    }
    first_after_top = std::min(first_after_top, range.first);
    if (i % 50 == 0 || i == steps) check_same(pruned, full, label + ", step " + std::to_string(i));
  }
  MESSAGE(label << ": " << steps << " steps, smallest range " << smallest << " of " << nodes
                << " nodes");
  CHECK(full_ranges == steps);
  CHECK(smallest < nodes / 2);
  CHECK(highest_first > 0);                // the range rose with the block
  CHECK(first_after_top < highest_first);  // and came down again
}

template <class Kernel, class Continuum, class Scheme>
using Sim2 = Simulation<2, Kernel, Continuum, contact::SingleField, Scheme>;

}  // namespace

TEST_CASE("node range: every scheme gives the same bits as passes over every node") {
  using Elastic = test::ElasticContinuum;
  // USL with the linear kernel tore the flying block's corners apart within 100 steps (small
  // masses on the nodes the block enters); GIMP's smoother crossing keeps it whole.
  check_throw<Sim2<shape::GIMP, Elastic, integrator::USL>>(1, false, "USL");
  check_throw<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::MUSL>>(
      1, false, "MUSL, Mohr-Coulomb");
  check_throw<Sim2<shape::Linear, Elastic, integrator::USF>>(1, false, "USF");
  check_throw<Sim2<shape::GIMP, Elastic, integrator::FusedUSL>>(1, false, "fused USL");
  check_throw<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::FusedMUSL>>(
      1, false, "fused MUSL, Mohr-Coulomb");
}

TEST_CASE("node range: every kernel's stencil lies in the range") {
  using Elastic = test::ElasticContinuum;
  check_throw<Sim2<shape::QuadraticBSpline, Elastic, integrator::MUSL>>(1, false, "quadratic");
  check_throw<Sim2<shape::CubicBSpline, Elastic, integrator::MUSL>>(1, false, "cubic");
  check_throw<Sim2<shape::GIMP, Elastic, integrator::MUSL>>(1, false, "GIMP");
}

TEST_CASE("node range: the Cosserat continuum's rotational node fields") {
  check_throw<Sim2<shape::Linear, Polar, integrator::MUSL>>(1, false, "Cosserat MUSL");
  check_throw<Sim2<shape::Linear, Polar, integrator::USF>>(1, false, "Cosserat USF");
}

TEST_CASE("node range: two threads over the range's shares") {
  check_throw<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::MUSL>>(
      2, true, "MUSL, two threads");
  // The fused pass's second half pending in its nodes until the node pass adds it.
  check_throw<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::FusedMUSL>>(
      2, true, "fused MUSL, two threads");
}

// The block lifted by 10 cells after 20 steps, as a user's stage may: the nodes it held leave
// the range with mass, momentum and velocities that only the clearing removes.
template <class Sim>
void check_lift(const std::string& label) {
  Sim pruned = thrown_up<Sim>(1, true, false);
  Sim full = thrown_up<Sim>(1, false, false);
  const double dt = pruned.time_step();
  for (Sim* sim : {&pruned, &full}) {
    for (int i = 0; i < 20; ++i) sim->step(dt);
    for (auto& x : sim->particles().template get<particles::field::Position<2>>()) x[1] += 0.1;
    sim->step(dt);
  }
  CHECK(std::as_const(pruned).engine().node_range.first >= 9 * 41);  // nine layers left
  check_same(pruned, full, label + ", one step later");
  for (Sim* sim : {&pruned, &full}) {
    for (int i = 0; i < 20; ++i) sim->step(dt);
  }
  check_same(pruned, full, label + ", 21 steps later");
}

TEST_CASE("node range: particles moved between steps leave zeroed nodes behind") {
  check_lift<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::MUSL>>("MUSL");
  check_lift<Sim2<shape::Linear, continuum::Classical<Soil>, integrator::FusedMUSL>>("fused MUSL");
}
