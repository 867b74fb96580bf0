#pragma once
// HDF5 frames of a DEM run with an XDMF index for ParaView ("Xdmf Reader"): the disks, the
// contact force network and the walls. Built on the project's io helpers (io::Hdf5File,
// io::TemporaryFile, io::write_file_atomically, io::create_directories); every frame is
// written under a temporary name and renamed, then the index is rewritten the same way, so a
// run that stops keeps every frame listed so far. Needs HDF5 (link cosmpm::hdf5).
//
// Frame file `<dir>/<prefix>_<NNNNNN>.h5`:
//   attributes of /    format = "cosmpm-dem-frame", version = 1, time [s], step, frame,
//                      element_count, body_count, contact_count
//   /particles/        one row per element (disk): position (N x 2) and position3 (N x 3),
//                      radius, velocity(3), rotation (its body's angle, rad), spin, body
//                      (int32), contact_count (int32), displacement(3) (its body's, from
//                      the initial position), and any extra per-element fields
//   /contacts/         one polyline per touching contact: points (2M x 3: the two centres,
//                      or centre and wall point), connectivity (M x 2, int32), normal_force,
//                      shear_force, force (magnitude) in N/m, wall (int32, -1 between disks)
//   /walls/            points (K x 3) and connectivity (S x 2, int32): plane walls as a
//                      segment across the particles' extent, polygons edge by edge
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/fields.hpp"
#include "cosmpm/dem/walls.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/detail/number_text.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/io/xdmf.hpp"

namespace cosmpm::dem {

// A per-element field added to a frame (the driver's layer colours, displacement ratios...).
struct ExtraField {
  std::string name;
  const std::vector<double>* values = nullptr;
};

class FrameWriter {
 public:
  FrameWriter(std::filesystem::path directory, std::string prefix)
      : directory_(std::move(directory)), prefix_(std::move(prefix)) {
    require(!prefix_.empty() && prefix_.find('/') == std::string::npos,
            "dem::FrameWriter: prefix '" + prefix_ + "' must be a file name without '/'");
    io::create_directories(directory_, "dem::FrameWriter");
  }

  std::filesystem::path xdmf_path() const { return directory_ / (prefix_ + ".xdmf"); }
  Index frame_count() const { return static_cast<Index>(frames_.size()); }
  std::filesystem::path frame_path(Index frame) const { return directory_ / file_name(frame); }

  template <class Sim>
  std::filesystem::path write(const Sim& sim, const std::vector<ExtraField>& extra = {}) {
    const auto& assembly = sim.assembly();
    const auto& elements = assembly.elements();
    const auto& bodies = assembly.bodies();
    const Index n = assembly.element_count();
    for (const ExtraField& f : extra) {
      require(f.values != nullptr && static_cast<Index>(f.values->size()) == n,
              "dem::FrameWriter: extra field '" + f.name + "' needs one value per element");
    }
    Frame frame;
    frame.file = file_name(frame_count());
    frame.time = sim.time();
    frame.elements = n;
    for (const ExtraField& f : extra) frame.extra.push_back(f.name);

    // Particles.
    const auto& x = elements.template get<tag::Position<2>>();
    const auto& v = elements.template get<tag::Velocity<2>>();
    const auto& body = elements.template get<tag::Body>();
    std::vector<double> position3(3 * static_cast<std::size_t>(n), 0.0);
    std::vector<double> velocity3(position3.size(), 0.0), displacement3(position3.size(), 0.0);
    std::vector<double> rotation(static_cast<std::size_t>(n)), spin(rotation.size());
    const auto& xb = bodies.template get<tag::Position<2>>();
    const auto& xb0 = bodies.template get<tag::InitialPosition<2>>();
    for (std::size_t e = 0; e < static_cast<std::size_t>(n); ++e) {
      const auto b = static_cast<std::size_t>(body[e]);
      for (int d = 0; d < 2; ++d) {
        position3[3 * e + static_cast<std::size_t>(d)] = x[e][d];
        velocity3[3 * e + static_cast<std::size_t>(d)] = v[e][d];
        displacement3[3 * e + static_cast<std::size_t>(d)] = xb[b][d] - xb0[b][d];
      }
      rotation[e] = bodies.template get<field::Angle>()[b];
      spin[e] = bodies.template get<field::Spin>()[b];
    }
    std::vector<double> position2(2 * static_cast<std::size_t>(n));
    for (std::size_t e = 0; e < static_cast<std::size_t>(n); ++e) {
      position2[2 * e] = x[e][0];
      position2[2 * e + 1] = x[e][1];
    }

    // Contacts.
    std::vector<double> points;
    std::vector<std::int32_t> wall_of;
    std::vector<double> normal, shear;
    sim.for_each_pair_contact([&](const auto& c) {
      for (const Index e : {c.first, c.second}) push_point(points, x[static_cast<std::size_t>(e)]);
      wall_of.push_back(-1);
      normal.push_back(c.normal_force);
      shear.push_back(c.shear_force);
    });
    sim.for_each_wall_contact([&](const WallContact& c) {
      push_point(points, x[static_cast<std::size_t>(c.element)]);
      push_point(points, c.point);
      wall_of.push_back(static_cast<std::int32_t>(c.wall));
      normal.push_back(c.normal_force);
      shear.push_back(c.shear_force);
    });
    frame.contacts = static_cast<Index>(normal.size());
    std::vector<std::int32_t> contact_lines(2 * normal.size());
    std::vector<double> magnitude(normal.size());
    for (std::size_t c = 0; c < normal.size(); ++c) {
      contact_lines[2 * c] = static_cast<std::int32_t>(2 * c);
      contact_lines[2 * c + 1] = static_cast<std::int32_t>(2 * c + 1);
      magnitude[c] = std::hypot(normal[c], shear[c]);
    }

    // Walls.
    std::vector<double> wall_points;
    std::vector<std::int32_t> wall_lines;
    Vec<2> lo = Vec<2>::Constant(1e300), hi = Vec<2>::Constant(-1e300);
    for (const Vec<2>& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double extent = n > 0 ? (hi - lo).norm() : 1.0;
    for (Index w = 0; w < sim.walls().size(); ++w) {
      const auto& wall = sim.walls()[w];
      if (!wall.enabled) continue;
      if (wall.kind == WallKind::plane) {
        const Vec<2> t(-wall.normal[1], wall.normal[0]);
        const Vec<2> centre =
            n > 0 ? Vec<2>(wall.point + t * t.dot(0.5 * (lo + hi) - wall.point)) : wall.point;
        add_segment(wall_points, wall_lines, centre - 0.6 * extent * t, centre + 0.6 * extent * t);
      } else {
        const auto& body_wall = *wall.body;
        for (int k = 0; k < body_wall.edge_count(); ++k) {
          add_segment(wall_points, wall_lines, body_wall.edge_start(k), body_wall.edge_end(k));
        }
      }
    }
    frame.wall_points = static_cast<Index>(wall_points.size() / 3);
    frame.wall_segments = static_cast<Index>(wall_lines.size() / 2);

    const std::filesystem::path final_path = directory_ / frame.file;
    {
      io::TemporaryFile temporary(final_path);
      io::Hdf5File file = io::Hdf5File::create(temporary.path());
      file.set_attribute("format", std::string("cosmpm-dem-frame"));
      file.set_attribute("version", std::int64_t{1});
      file.set_attribute("time", sim.time());
      file.set_attribute("step", static_cast<std::int64_t>(sim.step_count()));
      file.set_attribute("frame", static_cast<std::int64_t>(frame_count()));
      file.set_attribute("element_count", static_cast<std::int64_t>(n));
      file.set_attribute("body_count", static_cast<std::int64_t>(assembly.body_count()));
      file.set_attribute("contact_count", static_cast<std::int64_t>(frame.contacts));
      const auto rows = static_cast<hsize_t>(n);
      file.create_group("/particles");
      file.write("/particles/position", position2.data(), {rows, 2});
      file.write("/particles/position3", position3.data(), {rows, 3});
      file.write("/particles/radius", elements.template get<field::Radius>().data(), {rows});
      file.write("/particles/velocity3", velocity3.data(), {rows, 3});
      file.write("/particles/displacement3", displacement3.data(), {rows, 3});
      file.write("/particles/rotation", rotation.data(), {rows});
      file.write("/particles/spin", spin.data(), {rows});
      file.write("/particles/body", body.data(), {rows});
      file.write("/particles/contact_count", elements.template get<field::ContactCount>().data(),
                 {rows});
      for (const ExtraField& f : extra) {
        file.write("/particles/" + f.name, f.values->data(), {rows});
      }
      const auto m = static_cast<hsize_t>(frame.contacts);
      file.create_group("/contacts");
      file.write("/contacts/points", points.data(), {2 * m, 3});
      file.write("/contacts/connectivity", contact_lines.data(), {m, 2});
      file.write("/contacts/normal_force", normal.data(), {m});
      file.write("/contacts/shear_force", shear.data(), {m});
      file.write("/contacts/force", magnitude.data(), {m});
      file.write("/contacts/wall", wall_of.data(), {m});
      file.create_group("/walls");
      file.write("/walls/points", wall_points.data(), {static_cast<hsize_t>(frame.wall_points), 3});
      file.write("/walls/connectivity", wall_lines.data(),
                 {static_cast<hsize_t>(frame.wall_segments), 2});
      file.close();
      temporary.commit();
    }
    frames_.push_back(std::move(frame));
    io::write_file_atomically(xdmf_path(), render());
    return final_path;
  }

 private:
  struct Frame {
    std::string file;
    double time = 0.0;
    Index elements = 0;
    Index contacts = 0;
    Index wall_points = 0;
    Index wall_segments = 0;
    std::vector<std::string> extra;
  };

  static void add_segment(std::vector<double>& points, std::vector<std::int32_t>& lines,
                          const Vec<2>& a, const Vec<2>& b) {
    const auto first = static_cast<std::int32_t>(points.size() / 3);
    push_point(points, a);
    push_point(points, b);
    lines.push_back(first);
    lines.push_back(first + 1);
  }
  // One point at a time (GCC 12 warns falsely on inserting initializer lists here).
  static void push_point(std::vector<double>& points, const Vec<2>& p) {
    points.push_back(p[0]);
    points.push_back(p[1]);
    points.push_back(0.0);
  }

  std::string file_name(Index frame) const {
    std::string number = std::to_string(frame);
    if (number.size() < 6) number.insert(0, 6 - number.size(), '0');
    return prefix_ + "_" + number + ".h5";
  }

  static void item(std::ostream& out, const std::string& file, const std::string& dataset,
                   const std::string& dims, bool integer) {
    out << "          <DataItem Dimensions=\"" << dims << "\" NumberType=\""
        << (integer ? "Int\" Precision=\"4\"" : "Float\" Precision=\"8\"") << " Format=\"HDF\">"
        << io::detail::xml_escape(file) << ":" << dataset << "</DataItem>\n";
  }
  static void attribute(std::ostream& out, const std::string& file, const std::string& name,
                        const std::string& dataset, const std::string& dims, bool vector,
                        bool integer, const char* centre) {
    out << "        <Attribute Name=\"" << io::detail::xml_escape(name) << "\" AttributeType=\""
        << (vector ? "Vector" : "Scalar") << "\" Center=\"" << centre << "\">\n";
    item(out, file, dataset, dims, integer);
    out << "        </Attribute>\n";
  }

  std::string render() const {
    std::ostringstream out;
    out << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"2.0\">\n  <Domain>\n"
        << "    <Grid Name=\"series\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const Frame& f : frames_) {
      out << "    <Grid Name=\"frame\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
          << "      <Time Value=\"" << io::detail::format_number_exact(f.time) << "\"/>\n";
      const std::string n = std::to_string(f.elements);
      out << "      <Grid Name=\"particles\" GridType=\"Uniform\">\n"
          << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
          << "\" NodesPerElement=\"1\"/>\n        <Geometry GeometryType=\"XYZ\">\n";
      item(out, f.file, "/particles/position3", n + " 3", false);
      out << "        </Geometry>\n";
      attribute(out, f.file, "radius", "/particles/radius", n, false, false, "Node");
      attribute(out, f.file, "velocity", "/particles/velocity3", n + " 3", true, false, "Node");
      attribute(out, f.file, "displacement", "/particles/displacement3", n + " 3", true, false,
                "Node");
      attribute(out, f.file, "rotation", "/particles/rotation", n, false, false, "Node");
      attribute(out, f.file, "spin", "/particles/spin", n, false, false, "Node");
      attribute(out, f.file, "body", "/particles/body", n, false, true, "Node");
      attribute(out, f.file, "contact_count", "/particles/contact_count", n, false, true, "Node");
      for (const std::string& name : f.extra) {
        attribute(out, f.file, name, "/particles/" + name, n, false, false, "Node");
      }
      out << "      </Grid>\n";
      if (f.contacts > 0) {
        const std::string m = std::to_string(f.contacts);
        out << "      <Grid Name=\"contacts\" GridType=\"Uniform\">\n"
            << "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << m
            << "\" NodesPerElement=\"2\">\n";
        item(out, f.file, "/contacts/connectivity", m + " 2", true);
        out << "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n";
        item(out, f.file, "/contacts/points", std::to_string(2 * f.contacts) + " 3", false);
        out << "        </Geometry>\n";
        attribute(out, f.file, "force", "/contacts/force", m, false, false, "Cell");
        attribute(out, f.file, "normal_force", "/contacts/normal_force", m, false, false, "Cell");
        attribute(out, f.file, "shear_force", "/contacts/shear_force", m, false, false, "Cell");
        attribute(out, f.file, "wall", "/contacts/wall", m, false, true, "Cell");
        out << "      </Grid>\n";
      }
      if (f.wall_segments > 0) {
        const std::string s = std::to_string(f.wall_segments);
        out << "      <Grid Name=\"walls\" GridType=\"Uniform\">\n"
            << "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << s
            << "\" NodesPerElement=\"2\">\n";
        item(out, f.file, "/walls/connectivity", s + " 2", true);
        out << "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n";
        item(out, f.file, "/walls/points", std::to_string(f.wall_points) + " 3", false);
        out << "        </Geometry>\n      </Grid>\n";
      }
      out << "    </Grid>\n";
    }
    out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return out.str();
  }

  std::filesystem::path directory_;
  std::string prefix_;
  std::vector<Frame> frames_;
};

}  // namespace cosmpm::dem
