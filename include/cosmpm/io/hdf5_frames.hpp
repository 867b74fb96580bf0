#pragma once
// One HDF5 file per frame and an XDMF index of the series for ParaView.
//
// Frame file layout, format version 2 (`<dir>/<prefix>_<NNNNNN>.h5`, NNNNNN from 000000):
//   attributes of /   format = "cosmpm-frame", version = 2, time (s), step, frame,
//                     particle_count, dimension, library ("cosmpm 0.1.0"), sign_convention,
//                     run_parameters (the run's settings as given by its driver, may be
//                     empty), xdmf, xdmf_bodies, xdmf_grid (this frame's entries of the
//                     XDMF indexes)
//   /particles/       position (N x 3, the geometry), connectivity (N int32 0 .. N-1), and
//                     every field as io/frame_layout.hpp lays it out: scalars N, vectors
//                     N x 3, tensors N x 9 row-major; each dataset has the string attributes
//                     units, components (vectors and tensors) and description
//   /values/<name>    one value per frame given by the driver (blade travel, ...), shown as
//                     ParaView field data
//   /bodies/<name>/   the contact law's rigid bodies, if any: vertices (V x 3), velocity and
//                     force_on_material (1 x 3 each, one polygon cell; 3D: F x 3, the body's
//                     value on each of its F faces, which the XDMF index lists)
//   /grid/            with FrameOptions::grid_fields: node position, mass, velocity
// Format version 1 (before cosmpm 0.1.0's output rework) kept fields at the root with
// N x 2 vectors and N x 4 stresses; such frames still open in ParaView's legacy reader but
// resume() refuses them, naming the version.
//
// One XDMF index per kind of mesh: <prefix>.xdmf (particles), <prefix>_bodies.xdmf (rigid
// bodies) and <prefix>_grid.xdmf (grid nodes). ParaView's default Xdmf3ReaderS merges all
// meshes of one file into pieces of a single dataset, and then cannot colour by an array that
// only some of them have; one file per kind keeps every array usable in both readers.
#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/frame_layout.hpp"
#include "cosmpm/io/hdf5_file.hpp"
#include "cosmpm/io/hdf5_meshes.hpp"
#include "cosmpm/io/xdmf.hpp"
#include "cosmpm/version.hpp"

namespace cosmpm::io {

inline constexpr const char* frame_format = "cosmpm-frame";
inline constexpr std::int64_t frame_format_version = 2;
inline constexpr const char* frame_sign_convention =
    "stress and strain tension positive (continuum mechanics); 2D runs are plane strain and "
    "carry sigma_zz; tensors are 3 x 3 row-major, component ij acting on the face with normal i "
    "in direction j; forces on bodies are per metre out of plane in 2D";

// One value per frame, e.g. the blade travel: ParaView shows it as field data.
struct FrameValue {
  std::string name{};
  double value = 0.0;
  std::string units{};
  std::string description{};
};

struct FrameOptions {
  bool grid_fields = false;      // also write node positions, mass and velocity (write(sim) only)
  bool xdmf = true;              // keep <prefix>.xdmf up to date
  bool bodies = true;            // write the contact law's rigid bodies (write(sim) only)
  std::string run_parameters{};  // stored in every frame
  std::vector<std::string> body_names{};  // default: body_0, body_1, ...
};

// Writes one HDF5 file per frame and keeps the XDMF index of the series current. Each frame is
// written under a temporary name and renamed, then the index is rewritten the same way:
// after a crash every frame listed is complete, and a restart (resume) lists again every
// frame on disk up to the restart time.
class ParticleFrameWriter {
 public:
  ParticleFrameWriter(std::filesystem::path directory, std::string prefix,
                      FrameOptions options = {})
      : directory_(std::move(directory)),
        prefix_(std::move(prefix)),
        options_(std::move(options)),
        xdmf_(directory_ / (prefix_ + ".xdmf")),
        bodies_xdmf_(directory_ / (prefix_ + "_bodies.xdmf")),
        grid_xdmf_(directory_ / (prefix_ + "_grid.xdmf")) {
    require(
        !prefix_.empty() && prefix_.find('/') == std::string::npos,
        "ParticleFrameWriter: prefix '" + prefix_ + "' must be a non-empty file name without '/'");
    create_directories(directory_, "ParticleFrameWriter");
  }

  std::filesystem::path frame_path(Index frame) const {
    return directory_ / frame_file_name(frame);
  }
  // The index of the particles, the one to open in ParaView.
  std::filesystem::path xdmf_path() const { return xdmf_.path(); }
  // The indexes of the rigid bodies and the grid nodes (written once such frames exist).
  std::filesystem::path bodies_xdmf_path() const { return bodies_xdmf_.path(); }
  std::filesystem::path grid_xdmf_path() const { return grid_xdmf_.path(); }
  Index frame_count() const { return next_frame_; }
  const FrameOptions& options() const { return options_; }

  // A frame of a bare particle store at the given clock.
  template <class Store>
  std::filesystem::path write(const Store& particles, double time, std::int64_t step,
                              const std::vector<FrameValue>& values = {}) {
    const FrameArrays arrays = particle_frame_arrays(particles);
    return write_frame(arrays, particles.size(), time, step, values,
                       [](Hdf5File&, XdmfFrame&, XdmfFrame&) {});
  }

  // A frame of a simulation: its particles (half_width in metres), clock, rigid bodies and
  // (with grid_fields) grid nodes.
  template <detail::FrameSource Sim>
  std::filesystem::path write(const Sim& sim, const std::vector<FrameValue>& values = {}) {
    const auto& grid = sim.grid();
    constexpr int dim = std::remove_cvref_t<decltype(grid)>::dim;
    double cell_size[dim];
    for (int d = 0; d < dim; ++d) cell_size[d] = grid.cell_size()[d];
    const FrameArrays arrays = particle_frame_arrays(sim.particles(), cell_size);
    return write_frame(
        arrays, sim.particles().size(), sim.time(), sim.step_count(), values,
        [&](Hdf5File& file, XdmfFrame& bodies, XdmfFrame& nodes) {
          if constexpr (detail::HasRigidBodies<std::remove_cvref_t<decltype(sim.contact())>>) {
            if (options_.bodies) detail::put_bodies(file, bodies, sim, options_.body_names);
          }
          if (options_.grid_fields) {
            nodes.meshes.push_back(detail::put_grid<dim>(file, grid, sim.nodes()));
          }
        });
  }

  // After a restart of `sim`: see resume(time).
  template <detail::FrameSource Sim>
  Index resume(const Sim& sim) {
    return resume(sim.time());
  }

  // After a restart at `time`: lists again the frames on disk (consecutive from frame 0)
  // whose time is <= `time`, from the index entry each frame keeps, and continues numbering
  // after them; later frames are overwritten as the run reaches them. Returns the count.
  Index resume(double time) {
    xdmf_.clear();
    bodies_xdmf_.clear();
    grid_xdmf_.clear();
    next_frame_ = 0;
    for (;;) {
      const std::filesystem::path path = frame_path(next_frame_);
      std::error_code error;
      if (!std::filesystem::is_regular_file(path, error)) break;
      Hdf5File file = Hdf5File::open_read(path);
      check_format(file, path);
      if (!(file.attribute<double>("time") <= time)) break;
      xdmf_.append_text(file.string_attribute("xdmf"));
      if (file.has_attribute("xdmf_bodies")) {
        bodies_xdmf_.append_text(file.string_attribute("xdmf_bodies"));
      }
      if (file.has_attribute("xdmf_grid")) {
        grid_xdmf_.append_text(file.string_attribute("xdmf_grid"));
      }
      ++next_frame_;
    }
    if (options_.xdmf) {
      xdmf_.write();
      if (bodies_xdmf_.frame_count() > 0) bodies_xdmf_.write();
      if (grid_xdmf_.frame_count() > 0) grid_xdmf_.write();
    }
    return next_frame_;
  }

  // Throws unless `file` is a frame of the format version this build writes.
  static void check_format(const Hdf5File& file, const std::filesystem::path& path) {
    if (!file.has_attribute("format") || file.string_attribute("format") != frame_format) {
      throw Error("frame '" + path.string() + "' is not a cosmpm frame (no format = '" +
                  frame_format + "' attribute)");
    }
    const auto version = file.attribute<std::int64_t>("version");
    if (version != frame_format_version) {
      throw Error("frame '" + path.string() + "' has frame format version " +
                  std::to_string(version) + "; this build reads and continues version " +
                  std::to_string(frame_format_version) +
                  " only (older frames still open in ParaView; continue the run in a new "
                  "output folder)");
    }
  }

 private:
  std::string frame_file_name(Index frame) const {
    std::string number = std::to_string(frame);
    if (number.size() < 6) number.insert(0, 6 - number.size(), '0');
    return prefix_ + "_" + number + ".h5";
  }

  template <class Extra>
  std::filesystem::path write_frame(const FrameArrays& arrays, Index particles, double time,
                                    std::int64_t step, const std::vector<FrameValue>& values,
                                    Extra&& extra) {
    const std::filesystem::path final_path = frame_path(next_frame_);
    XdmfFrame frame;
    frame.file = frame_file_name(next_frame_);
    frame.time = time;
    XdmfFrame bodies = frame;
    XdmfFrame nodes = frame;
    {
      TemporaryFile temporary(final_path);
      Hdf5File file = Hdf5File::create(temporary.path());
      file.set_attribute("format", std::string(frame_format));
      file.set_attribute("version", frame_format_version);
      file.set_attribute("time", time);
      file.set_attribute("time_units", std::string("s"));
      file.set_attribute("step", step);
      file.set_attribute("frame", static_cast<std::int64_t>(next_frame_));
      file.set_attribute("particle_count", static_cast<std::int64_t>(particles));
      file.set_attribute("dimension", static_cast<std::int64_t>(arrays.dimension));
      file.set_attribute("library", "cosmpm " + std::to_string(version_major) + "." +
                                        std::to_string(version_minor) + "." +
                                        std::to_string(version_patch));
      file.set_attribute("sign_convention", std::string(frame_sign_convention));
      file.set_attribute("run_parameters", options_.run_parameters);
      XdmfMesh mesh = detail::put_point_mesh(file, "/particles", "particles", arrays, particles);
      if (!values.empty()) file.create_group("/values");
      for (const FrameValue& value : values) {
        const std::string dataset = "/values/" + value.name;
        file.write(dataset, &value.value, {1});
        detail::describe(file, dataset, value.units, "", value.description);
        XdmfAttribute attribute;
        attribute.name = value.name;
        attribute.dataset = dataset;
        attribute.center = XdmfAttribute::Center::grid;
        mesh.attributes.push_back(attribute);
      }
      frame.meshes.push_back(std::move(mesh));
      extra(file, bodies, nodes);
      const std::string entry = render_xdmf_frame(frame);
      const std::string bodies_entry = bodies.meshes.empty() ? "" : render_xdmf_frame(bodies);
      const std::string nodes_entry = nodes.meshes.empty() ? "" : render_xdmf_frame(nodes);
      file.set_attribute("xdmf", entry);
      if (!bodies_entry.empty()) file.set_attribute("xdmf_bodies", bodies_entry);
      if (!nodes_entry.empty()) file.set_attribute("xdmf_grid", nodes_entry);
      file.close();
      temporary.commit();
      ++next_frame_;
      if (options_.xdmf) {
        xdmf_.add_frame_text(entry);
        if (!bodies_entry.empty()) bodies_xdmf_.add_frame_text(bodies_entry);
        if (!nodes_entry.empty()) grid_xdmf_.add_frame_text(nodes_entry);
      }
    }
    return final_path;
  }

  std::filesystem::path directory_;
  std::string prefix_;
  FrameOptions options_;
  XdmfWriter xdmf_;
  XdmfWriter bodies_xdmf_;
  XdmfWriter grid_xdmf_;
  Index next_frame_ = 0;
};

}  // namespace cosmpm::io
