// Cost of one end-of-step contact correction (detection, normals, Coulomb correction and the
// force records) for the flat-blade set-up: 120 x 70 cells of 10 mm, a 10 mm x 350 mm blade
// moving at 10 mm/s against a 0.25 m layer at rest in front of it. The figure to quote is the
// time per correct() call; compare it with a full step (benchmarks/simulation).
#include <benchmark/benchmark.h>

#include <vector>

#include "cosmpm/contact.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape/linear.hpp"

namespace {
using namespace cosmpm;

void blade_correction(benchmark::State& state) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.2, 0.7), {120, 70});
  contact::RigidContact<2> law;
  law.add_body(contact::RigidBody<2>::box(Vec<2>(0.05, 0.0), Vec<2>(0.06, 0.35))
                   .set_velocity(Vec<2>(0.01, 0.0)),
               contact::Interface::coulomb_angle(14.0));
  // Layer mass on the nodes from one cell behind the blade's front face to the far wall, the
  // trial velocity a small downward settling one: every face node approaches.
  std::vector<double> mass(static_cast<std::size_t>(grid.node_count()), 0.0);
  std::vector<Vec<2>> trial(mass.size(), Vec<2>::Zero());
  for (Index n = 0; n < grid.node_count(); ++n) {
    const Vec<2> x = grid.node_position(n);
    if (x[0] >= 0.05 && x[1] <= 0.25) {
      mass[static_cast<std::size_t>(n)] = 0.0778;  // 778 kg/m^3 * (10 mm)^2
      trial[static_cast<std::size_t>(n)] = Vec<2>(0.0, -1e-3);
    }
  }
  std::vector<Vec<2>> velocity = trial;
  for (auto _ : state) {
    velocity = trial;
    contact::GridView<2> view{grid,
                              mass,
                              velocity,
                              1e-12,
                              1e-5,
                              0.3,
                              contact::Phase::end_velocity,
                              {},
                              contact::node_reach<shape::Linear>()};
    law.correct(view);
    benchmark::DoNotOptimize(velocity.data());
  }
  state.counters["contact_nodes"] = static_cast<double>(law.contact_nodes().size());
}
BENCHMARK(blade_correction);

}  // namespace
