// A user's solver: compose a simulation from cosmpm's policies and run a few steps.
#include <cosmpm/cosmpm.hpp>
#include <cstdio>

int main() {
  using namespace cosmpm;
  using Sim = Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<>>,
                         contact::SingleField, integrator::USL>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {20, 10});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  Sim sim(grid, material::LinearElastic<>(1e6, 0.3), parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.25), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  const double dt = sim.time_step();
  for (int i = 0; i < 10; ++i) sim.step(dt);
  std::printf("cosmpm %d.%d.%d consumer: %ld particles, t = %g s\n", version_major, version_minor,
              version_patch, static_cast<long>(sim.particles().size()), sim.time());
  return 0;
}
