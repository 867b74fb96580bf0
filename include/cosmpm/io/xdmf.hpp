#pragma once
// XDMF (version 2) index of a series of HDF5 frame files, so ParaView ("Xdmf Reader") opens
// the whole time series from one file. The XDMF file holds no data, only references
// `<frame file>:/<dataset>`; it is rewritten (temporary name + rename) after every frame, so
// it always lists exactly the frames that are complete on disk. No HDF5 dependency here.
//
// Layout: a temporal collection; each frame is one Polyvertex grid per mesh (particles, and
// optionally grid nodes, then wrapped in a spatial collection). Vector attributes reference
// datasets padded to 3 components; tensor components are hyperslabs (one column of an N x C
// dataset), so no data is duplicated for them.
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
  enum class Kind {
    scalar,     // a 1D dataset of N values
    vector,     // an N x 3 dataset
    component,  // column `component` of an N x `columns` dataset, shown as a scalar
  };
  std::string name;     // name shown in ParaView
  std::string dataset;  // absolute path in the frame file, e.g. "/stress"
  Kind kind = Kind::scalar;
  Index columns = 1;    // columns of the referenced dataset (vector: 3)
  Index component = 0;  // for Kind::component
  XdmfNumber number = XdmfNumber::float64;
};

// A cloud of points: particles or grid nodes.
struct XdmfMesh {
  std::string name;
  Index points = 0;
  std::string geometry_dataset;  // N x 3 doubles
  std::vector<XdmfAttribute> attributes;
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
                           Index points, const XdmfAttribute& attribute) {
  using Kind = XdmfAttribute::Kind;
  const std::string type = attribute.kind == Kind::vector ? "Vector" : "Scalar";
  out << indent << "<Attribute Name=\"" << xml_escape(attribute.name) << "\" AttributeType=\""
      << type << "\" Center=\"Node\">\n";
  const std::string inner = indent + "  ";
  const std::string n = std::to_string(points);
  switch (attribute.kind) {
    case Kind::scalar:
      xdmf_heavy_item(out, inner, file, attribute.dataset, n, attribute.number);
      break;
    case Kind::vector:
      xdmf_heavy_item(out, inner, file, attribute.dataset, n + " 3", attribute.number);
      break;
    case Kind::component:
      // Start, stride and count rows of the hyperslab over the N x C dataset.
      out << inner << "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" << n
          << " 1\">\n";
      out << inner << "  <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " << attribute.component
          << " 1 1 " << n << " 1</DataItem>\n";
      xdmf_heavy_item(out, inner + "  ", file, attribute.dataset,
                      n + " " + std::to_string(attribute.columns), attribute.number);
      out << inner << "</DataItem>\n";
      break;
  }
  out << indent << "</Attribute>\n";
}

inline void xdmf_mesh(std::ostream& out, const std::string& indent, const XdmfFrame& frame,
                      const XdmfMesh& mesh, bool with_time) {
  const std::string inner = indent + "  ";
  const std::string n = std::to_string(mesh.points);
  out << indent << "<Grid Name=\"" << xml_escape(mesh.name) << "\" GridType=\"Uniform\">\n";
  if (with_time) out << inner << "<Time Value=\"" << format_number_exact(frame.time) << "\"/>\n";
  out << inner << "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"1\"/>\n";
  out << inner << "<Geometry GeometryType=\"XYZ\">\n";
  xdmf_heavy_item(out, inner + "  ", frame.file, mesh.geometry_dataset, n + " 3",
                  XdmfNumber::float64);
  out << inner << "</Geometry>\n";
  for (const auto& attribute : mesh.attributes) {
    xdmf_attribute(out, inner, frame.file, mesh.points, attribute);
  }
  out << indent << "</Grid>\n";
}
}  // namespace detail

// The text of an XDMF file listing `frames` in order.
inline std::string render_xdmf(const std::vector<XdmfFrame>& frames) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" ?>\n"
      << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"2.0\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"series\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& frame : frames) {
    if (frame.meshes.size() == 1) {
      detail::xdmf_mesh(out, "      ", frame, frame.meshes.front(), true);
      continue;
    }
    out << "      <Grid Name=\"frame\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    out << "        <Time Value=\"" << detail::format_number_exact(frame.time) << "\"/>\n";
    for (const auto& mesh : frame.meshes) detail::xdmf_mesh(out, "        ", frame, mesh, false);
    out << "      </Grid>\n";
  }
  out << "    </Grid>\n"
      << "  </Domain>\n"
      << "</Xdmf>\n";
  return out.str();
}

// Keeps the list of frames and rewrites the XDMF file after each one.
class XdmfWriter {
 public:
  explicit XdmfWriter(std::filesystem::path path) : path_(std::move(path)) {}

  const std::filesystem::path& path() const { return path_; }
  const std::vector<XdmfFrame>& frames() const { return frames_; }

  void add_frame(XdmfFrame frame) {
    frames_.push_back(std::move(frame));
    write();
  }
  // Lists a frame without rewriting the file yet (a restart re-lists many at once).
  void append(XdmfFrame frame) { frames_.push_back(std::move(frame)); }
  // Forgets the listed frames (a restart rebuilds the list); the file is kept until the next
  // add_frame or write.
  void clear() { frames_.clear(); }

  void write() const { write_file_atomically(path_, render_xdmf(frames_)); }

 private:
  std::filesystem::path path_;
  std::vector<XdmfFrame> frames_;
};

}  // namespace cosmpm::io
