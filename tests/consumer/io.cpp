// A user's solver with output: a frame for ParaView and a checkpoint, read back.
#include <cosmpm/cosmpm.hpp>
#include <cosmpm/io/checkpoint.hpp>
#include <cosmpm/io/hdf5.hpp>
#include <cstdio>
#include <filesystem>

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
  const double dt = sim.time_step();
  for (int i = 0; i < 5; ++i) sim.step(dt);
  const auto out = std::filesystem::temp_directory_path() / "cosmpm_consumer_io";
  std::filesystem::remove_all(out);
  try {
    io::ParticleFrameWriter frames(out, "block");
    frames.write(sim);
    io::save_checkpoint(sim, out / "checkpoint.h5");
    Sim restarted(grid, material::LinearElastic<>(1e6, 0.3), parameters);
    restarted.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
    io::load_checkpoint(restarted, out / "checkpoint.h5");
    if (restarted.time() != sim.time()) return 1;
  } catch (const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  std::printf("cosmpm consumer with HDF5: frame and checkpoint in %s\n", out.c_str());
  std::filesystem::remove_all(out);
  return 0;
}
