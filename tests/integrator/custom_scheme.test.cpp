// A scheme a user writes in one file of their own, from the engine's public stages, and runs
// without touching the engine (integrator/concept.hpp).
#include <doctest/doctest.h>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/integrator/concept.hpp"

namespace {
using namespace cosmpm;

// USL without the library's fusion of the stress update into the grid-to-particle pass: the
// velocity gradient and the stress update as stages of their own, from the end velocity.
struct UnfusedUSL {
  static constexpr const char* name() { return "USL, unfused (test)"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/true);
    sim.update_grid(dt);
    sim.map_to_particles(dt);
    sim.velocity_gradient_from_grid(sim.nodes().velocity, sim.nodes().spin);
    sim.update_stress(dt);
  }
};
static_assert(integrator::Integrator<UnfusedUSL>);

template <class Scheme>
auto make_column() {
  using Sim = Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, Scheme>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4), {20, 20});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.5, -9.81);  // sideways too, so the column shears
  parameters.threads = 1;
  Sim sim(grid, test::Elastic(1e5, 0.3), parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.1, 0.0), Vec<2>(0.3, 0.3), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

}  // namespace

TEST_CASE("integrator: a scheme defined outside the library runs through the public stages") {
  auto custom = make_column<UnfusedUSL>();
  auto library = make_column<integrator::USL>();
  const double dt = library.time_step();
  for (int i = 0; i < 300; ++i) {
    custom.step(dt);
    library.step(dt);
  }
  // The engine keeps the clock around any scheme.
  CHECK(custom.step_count() == 300);
  CHECK(custom.time() == library.time());
  CHECK(std::string(decltype(custom)::scheme_type::name()) == "USL, unfused (test)");
  // The same arithmetic in another order of passes: the fused pass does every particle's
  // operations in the same order as the separate stages, so the results are equal bit for
  // bit (and the column has moved and sheared, so the comparison covers a real state).
  const auto& x1 = custom.particles().get<particles::field::Position<2>>();
  const auto& x2 = library.particles().get<particles::field::Position<2>>();
  const auto& s1 = custom.particles().get<particles::field::Stress<test::Elastic>>();
  const auto& s2 = library.particles().get<particles::field::Stress<test::Elastic>>();
  const auto& x0 = library.particles().get<particles::field::InitialPosition<2>>();
  bool identical = true;
  double largest_move = 0.0;
  double largest_shear = 0.0;
  for (Index p = 0; p < library.particles().size(); ++p) {
    identical = identical && x1[p] == x2[p] && s1[p] == s2[p];
    largest_move = std::max(largest_move, (x2[p] - x0[p]).norm());
    largest_shear = std::max(largest_shear, std::abs(s2[p][3]));
  }
  CHECK(largest_move > 1e-4);
  CHECK(largest_shear > 10.0);  // Pa
  CHECK(identical);
}
