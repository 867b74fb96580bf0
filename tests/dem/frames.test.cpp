// HDF5/XDMF frames of a DEM run: what is written reads back, the XDMF index lists the frames
// with the particles, the contact network and the walls, and a run that goes unstable keeps
// the frames written before.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/dem/hdf5_frames.hpp"
#include "cosmpm/dem/simulation.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "test_output.hpp"

namespace {
using namespace cosmpm;
namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

dem::Simulation<> small_pile() {
  dem::Assembly a;
  a.add_disk(Vec<2>(0.0, 0.005), 0.005, 855.0);
  a.add_disk(Vec<2>(0.0099, 0.005), 0.005, 855.0);
  a.add_clump(dem::ClumpShape::two_disks(0.010, 0.006), 1.0, Vec<2>(0.005, 0.0128), 0.0, 855.0);
  dem::Simulation<> sim(std::move(a));
  sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {});
  sim.add_polygon_wall("blade", contact::RigidBody<2>::box(Vec<2>(-0.02, 0), Vec<2>(-0.005, 0.1)),
                       {});
  return sim;
}

}  // namespace

TEST_CASE("frames: particles, contacts and walls read back and are indexed for ParaView") {
  const fs::path dir = cosmpm::test::output_root() / "dem_frames";
  fs::remove_all(dir);
  auto sim = small_pile();
  dem::FrameWriter writer(dir, "pile");
  const double dt = 0.5 * sim.critical_time_step();
  for (int k = 0; k < 200; ++k) sim.step(dt);
  std::vector<double> layer{0.0, 1.0, 2.0, 2.0};
  writer.write(sim, {{"layer", &layer}});
  for (int k = 0; k < 4000; ++k) sim.step(dt);  // the clump lands on the disks
  writer.write(sim, {{"layer", &layer}});
  CHECK(writer.frame_count() == 2);

  io::Hdf5File file = io::Hdf5File::open_read(writer.frame_path(1));
  CHECK(file.string_attribute("format") == "cosmpm-dem-frame");
  CHECK(file.attribute<std::int64_t>("element_count") == 4);
  CHECK(file.attribute<std::int64_t>("step") == 4200);
  std::vector<double> radius(4);
  file.read("/particles/radius", radius.data(), {4});
  CHECK(radius[0] == 0.005);
  CHECK(radius[2] == doctest::Approx(0.003));
  std::vector<double> position(12);
  file.read("/particles/position3", position.data(), {4, 3});
  const auto& x = sim.assembly().elements().get<particles::field::Position<2>>();
  CHECK(position[3] == x[1][0]);
  CHECK(position[4] == x[1][1]);
  std::vector<double> read_layer(4);
  file.read("/particles/layer", read_layer.data(), {4});
  CHECK(read_layer == layer);
  const auto contacts = static_cast<hsize_t>(file.attribute<std::int64_t>("contact_count"));
  CHECK(contacts == static_cast<hsize_t>(sim.active_contacts()));
  CHECK(contacts >= 4);  // two disks on the floor, the clump on both disks
  std::vector<double> force(contacts);
  file.read("/contacts/force", force.data(), {contacts});
  for (double f : force) CHECK(f > 0.0);
  std::vector<std::int32_t> lines(2 * contacts);
  file.read("/contacts/connectivity", lines.data(), {contacts, 2});
  CHECK(lines[1] == 1);
  CHECK(file.shape("/walls/connectivity") == std::vector<hsize_t>{5, 2});  // plane + 4 edges

  const std::string xdmf = read_text(writer.xdmf_path());
  CHECK(xdmf.find("pile_000000.h5:/particles/position3") != std::string::npos);
  CHECK(xdmf.find("pile_000001.h5:/contacts/connectivity") != std::string::npos);
  CHECK(xdmf.find("TopologyType=\"Polyline\"") != std::string::npos);
  CHECK(xdmf.find("Name=\"layer\"") != std::string::npos);
}

TEST_CASE("frames: an unstable run keeps the frames written before it stopped") {
  const fs::path dir = cosmpm::test::output_root() / "dem_frames_unstable";
  fs::remove_all(dir);
  auto sim = small_pile();
  dem::FrameWriter writer(dir, "pile");
  const double dt = 0.5 * sim.critical_time_step();
  sim.step(dt);
  writer.write(sim);
  // Fling a particle: it crosses more than its radius in the next step.
  sim.assembly().bodies().get<particles::field::Velocity<2>>()[0] = Vec<2>(1e4, 0.0);
  sim.assembly().sync_elements();
  CHECK_THROWS_WITH_AS(sim.step(dt), doctest::Contains("moved more than its radius"), Error);
  CHECK(fs::exists(writer.frame_path(0)));
  const std::string xdmf = read_text(writer.xdmf_path());
  CHECK(xdmf.find("pile_000000.h5") != std::string::npos);
  CHECK(io::Hdf5File::open_read(writer.frame_path(0)).attribute<std::int64_t>("step") == 1);
}
