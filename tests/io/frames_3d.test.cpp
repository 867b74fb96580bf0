// Frames of a 3D simulation: positions and vectors with their z components, the stress and
// strain (six components) as full symmetric 3 x 3 tensors and F, L as 3 x 3, read back with the
// plain HDF5 C API (not the code under test) and compared with == to the particles' values.
// The files stay in COSMPM_TEST_OUTPUT_DIR/io/frames_3d for ParaView's readers
// (scripts/check_paraview.sh; see docs/validation.md).
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/material/stress_space.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/simulation.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;
using namespace cosmpm::test_io;
namespace field = particles::field;
using Soil3 = material::MohrCoulomb<double, 3>;
using Sim3 = Simulation<3, shape::QuadraticBSpline, continuum::Classical<Soil3>>;

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
}  // namespace

TEST_CASE("a 3D frame holds 3-vectors and 3 x 3 tensors equal to the particles' values") {
  const auto dir = output_dir("frames_3d");
  const grid::Grid<3> grid(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.4, 0.2, 0.3), {8, 4, 6});
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -9.81);
  Sim3 sim(grid,
           Soil3({.youngs_modulus = 2.76e6,
                  .poisson_ratio = 0.2,
                  .friction_angle_deg = 26.0,
                  .dilatancy_angle_deg = 2.0}),
           parameters);
  const auto seeding = particles::seed_box(grid, Vec<3>(0.1, 0.05, 0.0), Vec<3>(0.3, 0.15, 0.2), 2);
  sim.add_particles(seeding.positions, seeding.volume, 778.0, seeding.half_width);
  // Random stresses (inside the cone: a mean pressure well above the deviatoric part) and
  // velocities, so every component differs.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto& stress = sim.particles().get<field::Stress<Soil3>>();
  auto& velocity = sim.particles().get<field::Velocity<3>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    for (int c = 0; c < 6; ++c) stress[p][c] = (c < 3 ? -2000.0 : 0.0) + 100.0 * u(rng);
    velocity[p] = Vec<3>(u(rng), u(rng), u(rng)) * 0.01;
  }
  sim.step(0.5 * sim.stable_time_step());
  io::ParticleFrameWriter writer(dir, "block", {.grid_fields = true});
  const auto path = writer.write(sim);
  const auto n = static_cast<hsize_t>(sim.particles().size());
  CHECK(read_root_double(path, "dimension") == 3.0);

  const RawDataset position = read_raw(path, "/particles/position");
  REQUIRE(position.ok);
  CHECK(position.dims == std::vector<hsize_t>{n, 3});
  const RawDataset v = read_raw(path, "/particles/velocity");
  REQUIRE(v.ok);
  const auto& x = sim.particles().get<field::Position<3>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    for (int d = 0; d < 3; ++d) {
      CHECK(position.values[static_cast<std::size_t>(3 * p + d)] == x[p][d]);
      CHECK(v.values[static_cast<std::size_t>(3 * p + d)] == velocity[p][d]);
    }
  }
  const auto check_tensor = [&](const std::string& name, auto&& expected) {
    const RawDataset t = read_raw(path, "/particles/" + name);
    REQUIRE(t.ok);
    CHECK(t.dims == std::vector<hsize_t>{n, 9});
    CHECK(read_string_attribute(path, "/particles/" + name, "components") ==
          "xx xy xz yx yy yz zx zy zz");
    bool equal = true;
    for (Index p = 0; p < sim.particles().size(); ++p) {
      const Eigen::Matrix3d m = expected(p);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          equal = equal && t.values[static_cast<std::size_t>(9 * p + 3 * i + j)] == m(i, j);
        }
      }
    }
    CHECK_MESSAGE(equal, name);
  };
  const auto& strain = sim.particles().get<field::Strain<Soil3>>();
  const auto& F = sim.particles().get<field::DeformationGradient<3>>();
  const auto& L = sim.particles().get<field::VelocityGradient<3>>();
  check_tensor("stress", [&](Index p) { return material::to_tensor<3, double>(stress[p]); });
  check_tensor("strain", [&](Index p) { return material::to_tensor<3, double>(strain[p]); });
  check_tensor("deformation_gradient", [&](Index p) { return Eigen::Matrix3d(F[p]); });
  check_tensor("velocity_gradient", [&](Index p) { return Eigen::Matrix3d(L[p]); });
  // The shear components are really there (a 3D stress, not a plane-strain one padded).
  CHECK(stress[0][4] != 0.0);
  CHECK(stress[0][5] != 0.0);
  CHECK(read_string_attribute(path, "/particles/mass", "units") == "kg");
  // The XDMF index declares the tensors as Tensor (9 components) for ParaView.
  const std::string xdmf = text_of(writer.xdmf_path());
  CHECK(xdmf.find("Name=\"stress\" AttributeType=\"Tensor\"") != std::string::npos);
  CHECK(xdmf.find("Tensor6") == std::string::npos);
  // Grid nodes: 9 x 5 x 7 positions with z.
  const RawDataset nodes = read_raw(path, "/grid/position");
  REQUIRE(nodes.ok);
  CHECK(nodes.dims == std::vector<hsize_t>{9 * 5 * 7, 3});
  CHECK(nodes.values[3 * (9 * 5 * 7 - 1) + 2] == doctest::Approx(0.3).epsilon(1e-15));
}
