#pragma once
// XDMF (version 2) index of a series of HDF5 frame files, so ParaView opens the whole time
// series from one file with either of its readers (Xdmf3ReaderS, the default, and the legacy
// XDMFReader; checked by scripts/check_paraview.sh). The XDMF file holds no data, only
// references `<frame file>:/<dataset>`; it is rewritten (temporary name + rename) after
// every frame, so it lists exactly the frames that are complete on disk. No HDF5 here.
//
// What both readers read alike (ParaView 5.11): Polyvertex topology with an explicit
// connectivity (without one Xdmf3 reports no cells), attributes of 1, 3 or 9 components
// (AttributeType Scalar, Vector, Tensor; a 6-component Tensor6 is expanded differently by
// the two readers, a hyperslab view is dropped by Xdmf3), Polygon cells for rigid bodies,
// and Center="Grid" values, which become ParaView field data.
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/detail/number_text.hpp"

namespace cosmpm::io {

enum class XdmfNumber { float64, int32 };

struct XdmfAttribute {
  enum class Kind { scalar, vector, tensor };  // 1, 3 or 9 components per row
  enum class Center { node, cell, grid };      // per point, per cell, one value per mesh
  std::string name;                            // name shown in ParaView
  std::string dataset;                         // absolute path in the frame file
  Kind kind = Kind::scalar;
  Center center = Center::node;
  XdmfNumber number = XdmfNumber::float64;
};

// A cloud of points (particles, grid nodes), one polygon (a 2D rigid body's outline) or
// polygons sharing points (a 3D rigid body's faces, XDMF Mixed topology of Polygon cells).
struct XdmfMesh {
  enum class Topology { polyvertex, polygon, polygons };
  std::string name;
  Topology topology = Topology::polyvertex;
  Index points = 0;
  std::string geometry_dataset;      // points x 3 doubles
  std::string connectivity_dataset;  // polyvertex: points int32 ids 0 .. points - 1
  std::vector<XdmfAttribute> attributes;
  std::vector<std::vector<Index>> polygons;  // Topology::polygons: each cell's point ids
  Index cells() const {
    return topology == Topology::polyvertex ? points
           : topology == Topology::polygons ? static_cast<Index>(polygons.size())
                                            : 1;
  }
};

struct XdmfFrame {
  std::string file;  // frame file name, relative to the XDMF file's directory
  double time = 0.0;
  std::vector<XdmfMesh> meshes;
};

namespace detail {
inline std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

inline std::string xdmf_number_type(XdmfNumber number) {
  return number == XdmfNumber::int32 ? R"(NumberType="Int" Precision="4")"
                                     : R"(NumberType="Float" Precision="8")";
}

inline void xdmf_heavy_item(std::ostream& out, const std::string& indent, const std::string& file,
                            const std::string& dataset, const std::string& dimensions,
                            XdmfNumber number) {
  out << indent << "<DataItem Dimensions=\"" << dimensions << "\" " << xdmf_number_type(number)
      << " Format=\"HDF\">" << xml_escape(file) << ':' << xml_escape(dataset) << "</DataItem>\n";
}

inline void xdmf_attribute(std::ostream& out, const std::string& indent, const std::string& file,
                           const XdmfMesh& mesh, const XdmfAttribute& attribute) {
  using Kind = XdmfAttribute::Kind;
  using Center = XdmfAttribute::Center;
  const char* type = attribute.kind == Kind::scalar   ? "Scalar"
                     : attribute.kind == Kind::vector ? "Vector"
                                                      : "Tensor";
  const char* center = attribute.center == Center::node   ? "Node"
                       : attribute.center == Center::cell ? "Cell"
                                                          : "Grid";
  const Index rows = attribute.center == Center::node   ? mesh.points
                     : attribute.center == Center::cell ? mesh.cells()
                                                        : 1;
  std::string dimensions = std::to_string(rows);
  if (attribute.kind == Kind::vector) dimensions += " 3";
  if (attribute.kind == Kind::tensor) dimensions += " 9";
  out << indent << "<Attribute Name=\"" << xml_escape(attribute.name) << "\" AttributeType=\""
      << type << "\" Center=\"" << center << "\">\n";
  xdmf_heavy_item(out, indent + "  ", file, attribute.dataset, dimensions, attribute.number);
  out << indent << "</Attribute>\n";
}

inline void xdmf_mesh(std::ostream& out, const std::string& indent, const XdmfFrame& frame,
                      const XdmfMesh& mesh, bool with_time) {
  const std::string inner = indent + "  ";
  const std::string n = std::to_string(mesh.points);
  out << indent << "<Grid Name=\"" << xml_escape(mesh.name) << "\" GridType=\"Uniform\">\n";
  if (with_time) out << inner << "<Time Value=\"" << format_number_exact(frame.time) << "\"/>\n";
  if (mesh.topology == XdmfMesh::Topology::polyvertex) {
    out << inner << "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
        << "\" NodesPerElement=\"1\">\n";
    xdmf_heavy_item(out, inner + "  ", frame.file, mesh.connectivity_dataset, n + " 1",
                    XdmfNumber::int32);
  } else if (mesh.topology == XdmfMesh::Topology::polygons) {
    // Mixed topology: per cell the Polygon type (3), its point count, its point ids.
    std::ostringstream ids;
    Index length = 0;
    for (const auto& cell : mesh.polygons) {
      ids << (length == 0 ? "" : " ") << 3 << ' ' << cell.size();
      for (const Index k : cell) ids << ' ' << k;
      length += 2 + static_cast<Index>(cell.size());
    }
    out << inner << "<Topology TopologyType=\"Mixed\" NumberOfElements=\"" << mesh.cells()
        << "\">\n";
    out << inner << "  <DataItem Dimensions=\"" << length << "\" "
        << xdmf_number_type(XdmfNumber::int32) << " Format=\"XML\">" << ids.str()
        << "</DataItem>\n";
  } else {
    out << inner << "<Topology TopologyType=\"Polygon\" NumberOfElements=\"1\" NodesPerElement=\""
        << n << "\">\n";
    out << inner << "  <DataItem Dimensions=\"1 " << n << "\" "
        << xdmf_number_type(XdmfNumber::int32) << " Format=\"XML\">";
    for (Index k = 0; k < mesh.points; ++k) out << (k > 0 ? " " : "") << k;
    out << "</DataItem>\n";
  }
  out << inner << "</Topology>\n";
  out << inner << "<Geometry GeometryType=\"XYZ\">\n";
  xdmf_heavy_item(out, inner + "  ", frame.file, mesh.geometry_dataset, n + " 3",
                  XdmfNumber::float64);
  out << inner << "</Geometry>\n";
  for (const auto& attribute : mesh.attributes) {
    xdmf_attribute(out, inner, frame.file, mesh, attribute);
  }
  out << indent << "</Grid>\n";
}
}  // namespace detail

// The XML of one frame inside the temporal collection: its only mesh, or a spatial
// collection of its meshes. Frame files keep this text, so an index can be rebuilt from them.
inline std::string render_xdmf_frame(const XdmfFrame& frame) {
  std::ostringstream out;
  const std::string indent = "      ";
  if (frame.meshes.size() == 1) {
    detail::xdmf_mesh(out, indent, frame, frame.meshes.front(), true);
  } else {
    out << indent << "<Grid Name=\"frame\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    out << indent << "  <Time Value=\"" << detail::format_number_exact(frame.time) << "\"/>\n";
    for (const auto& mesh : frame.meshes) detail::xdmf_mesh(out, indent + "  ", frame, mesh, false);
    out << indent << "</Grid>\n";
  }
  return out.str();
}

// The text of an XDMF file listing frames, each given as render_xdmf_frame's text.
inline std::string render_xdmf(const std::vector<std::string>& frame_texts) {
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n"
      "  <Domain>\n"
      "    <Grid Name=\"series\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& text : frame_texts) out += text;
  out +=
      "    </Grid>\n"
      "  </Domain>\n"
      "</Xdmf>\n";
  return out;
}

inline std::string render_xdmf(const std::vector<XdmfFrame>& frames) {
  std::vector<std::string> texts;
  texts.reserve(frames.size());
  for (const auto& frame : frames) texts.push_back(render_xdmf_frame(frame));
  return render_xdmf(texts);
}

// Keeps the list of frames and rewrites the XDMF file after each one.
class XdmfWriter {
 public:
  explicit XdmfWriter(std::filesystem::path path) : path_(std::move(path)) {}

  const std::filesystem::path& path() const { return path_; }
  Index frame_count() const { return static_cast<Index>(frames_.size()); }

  void add_frame(const XdmfFrame& frame) { add_frame_text(render_xdmf_frame(frame)); }
  // A frame given as render_xdmf_frame's text (as kept in a frame file).
  void add_frame_text(std::string text) {
    frames_.push_back(std::move(text));
    write();
  }
  // Lists a frame without rewriting the file yet (a restart re-lists many at once).
  void append_text(std::string text) { frames_.push_back(std::move(text)); }
  // Forgets the listed frames (a restart rebuilds the list); the file is kept until the next
  // add_frame or write.
  void clear() { frames_.clear(); }

  void write() const { write_file_atomically(path_, render_xdmf(frames_)); }

 private:
  std::filesystem::path path_;
  std::vector<std::string> frames_;
};

}  // namespace cosmpm::io
