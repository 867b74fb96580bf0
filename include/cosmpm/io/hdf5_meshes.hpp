#pragma once
// The meshes of a frame file (io/hdf5_frames.hpp): a point cloud (particles or grid nodes)
// with its arrays, a simulation's rigid bodies as polygons, and the grid nodes; each written
// to HDF5 and described for the XDMF index.
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/io/frame_layout.hpp"
#include "cosmpm/io/hdf5_file.hpp"
#include "cosmpm/io/xdmf.hpp"

namespace cosmpm::io::detail {

template <class Sim>
concept FrameSource = requires(const Sim& sim) {
  sim.particles();
  sim.grid();
  sim.nodes().mass;
  sim.nodes().velocity;
  { sim.time() } -> std::convertible_to<double>;
  { sim.step_count() } -> std::convertible_to<std::int64_t>;
};

template <class Contact>
concept HasRigidBodies = requires(const Contact& contact) {
  { contact.body_count() } -> std::convertible_to<int>;
  contact.body(0).vertices();
  contact.body(0).velocity(0.0);
  contact.force_on_material(0);
};

inline void describe(Hdf5File& file, const std::string& dataset, const std::string& units,
                     const std::string& components, const std::string& description) {
  file.set_attribute("units", units, dataset);
  if (!components.empty()) file.set_attribute("components", components, dataset);
  if (!description.empty()) file.set_attribute("description", description, dataset);
}

inline XdmfAttribute::Kind xdmf_kind(ArrayShape shape) {
  return shape == ArrayShape::scalar   ? XdmfAttribute::Kind::scalar
         : shape == ArrayShape::vector ? XdmfAttribute::Kind::vector
                                       : XdmfAttribute::Kind::tensor;
}

// Writes `arrays` under `group` as the points of a polyvertex mesh and describes them.
inline XdmfMesh put_point_mesh(Hdf5File& file, const std::string& group, const std::string& name,
                               const FrameArrays& arrays, Index points) {
  const auto n = static_cast<hsize_t>(points);
  XdmfMesh mesh;
  mesh.name = name;
  mesh.points = points;
  file.create_group(group);
  mesh.geometry_dataset = group + "/position";
  file.write(mesh.geometry_dataset, arrays.geometry.data(), {n, 3});
  describe(file, mesh.geometry_dataset, "m", vector_components, "position (the geometry)");
  std::vector<std::int32_t> ids(static_cast<std::size_t>(points));
  for (std::size_t p = 0; p < ids.size(); ++p) ids[p] = static_cast<std::int32_t>(p);
  mesh.connectivity_dataset = group + "/connectivity";
  file.write(mesh.connectivity_dataset, ids.data(), {n, 1});
  describe(file, mesh.connectivity_dataset, "1", "", "point ids of the polyvertex cells");
  for (const FrameArray& array : arrays.arrays) {
    const std::string dataset = group + "/" + array.name;
    std::vector<hsize_t> dims{n};
    if (array.shape != ArrayShape::scalar) dims.push_back(static_cast<hsize_t>(array.columns()));
    if (array.integer) {
      file.write(dataset, array.integers.data(), dims);
    } else {
      file.write(dataset, array.values.data(), dims);
    }
    describe(file, dataset, array.units, array.components, array.description);
    XdmfAttribute attribute;
    attribute.name = array.name;
    attribute.dataset = dataset;
    attribute.kind = xdmf_kind(array.shape);
    attribute.number = array.integer ? XdmfNumber::int32 : XdmfNumber::float64;
    mesh.attributes.push_back(attribute);
  }
  return mesh;
}

inline std::string body_name(const std::vector<std::string>& names, int b) {
  const auto k = static_cast<std::size_t>(b);
  return k < names.size() ? names[k] : "body_" + std::to_string(b);
}

// Each rigid body of the simulation's contact law with its velocity and the force it applied
// to the material in the last step: a 2D body as one polygon cell, a 3D body as its faces
// (one polygon cell each, the body's values repeated on every face).
template <class Sim>
void put_bodies(Hdf5File& file, XdmfFrame& frame, const Sim& sim,
                const std::vector<std::string>& names) {
  const auto& contact = sim.contact();
  if (contact.body_count() == 0) return;
  file.create_group("/bodies");
  for (int b = 0; b < contact.body_count(); ++b) {
    const std::string group = "/bodies/" + body_name(names, b);
    file.create_group(group);
    const auto& vertices = contact.body(b).vertices();
    std::vector<double> xyz(3 * vertices.size(), 0.0);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      for (Index d = 0; d < static_cast<Index>(vertices[v].size()) && d < 3; ++d) {
        xyz[3 * v + d] = vertices[v][d];
      }
    }
    XdmfMesh mesh;
    mesh.name = body_name(names, b);
    mesh.topology = XdmfMesh::Topology::polygon;
    constexpr int dim = std::remove_cvref_t<decltype(sim.grid())>::dim;
    if constexpr (dim == 3) {
      const auto& shape = contact.body(b).shape();
      mesh.topology = XdmfMesh::Topology::polygons;
      for (int f = 0; f < shape.face_count(); ++f) {
        const auto& loop = shape.face_vertices(f);
        mesh.polygons.emplace_back(loop.begin(), loop.end());
      }
    }
    mesh.points = static_cast<Index>(vertices.size());
    mesh.geometry_dataset = group + "/vertices";
    file.write(mesh.geometry_dataset, xyz.data(), {static_cast<hsize_t>(vertices.size()), 3});
    detail::describe(file, mesh.geometry_dataset, "m", vector_components,
                     dim == 2 ? "outline of the rigid body, in order around it"
                              : "vertices of the rigid body (its faces: the topology)");
    auto cell_vector = [&](const std::string& label, const auto& v, const std::string& units,
                           const std::string& description) {
      const auto cells = static_cast<std::size_t>(mesh.cells());
      std::vector<double> rows(3 * cells, 0.0);
      for (std::size_t c = 0; c < cells; ++c) {
        for (Index d = 0; d < static_cast<Index>(v.size()) && d < 3; ++d) {
          rows[3 * c + static_cast<std::size_t>(d)] = v[d];
        }
      }
      const std::string dataset = group + "/" + label;
      file.write(dataset, rows.data(), {static_cast<hsize_t>(cells), 3});
      detail::describe(file, dataset, units, vector_components, description);
      XdmfAttribute attribute;
      attribute.name = label;
      attribute.dataset = dataset;
      attribute.kind = XdmfAttribute::Kind::vector;
      attribute.center = XdmfAttribute::Center::cell;
      mesh.attributes.push_back(attribute);
    };
    cell_vector("velocity", contact.body(b).velocity(sim.time()), "m/s",
                "velocity of the body's reference point");
    cell_vector("force_on_material", contact.force_on_material(b), dim == 2 ? "N/m" : "N",
                "force the body applied to the material in the last step (2D: per metre "
                "out of plane)");
    frame.meshes.push_back(std::move(mesh));
  }
}

template <int Dim, class Grid, class Nodes>
XdmfMesh put_grid(Hdf5File& file, const Grid& grid, const Nodes& nodes) {
  const Index count = grid.node_count();
  FrameArrays arrays;
  arrays.dimension = Dim;
  arrays.geometry.assign(static_cast<std::size_t>(3 * count), 0.0);
  for (Index n = 0; n < count; ++n) {
    const Vec<Dim> x = grid.node_position(n);
    for (int d = 0; d < Dim && d < 3; ++d)
      arrays.geometry[static_cast<std::size_t>(3 * n + d)] = x[d];
  }
  FrameArray mass;
  mass.name = "mass";
  mass.units = detail::per_out_of_plane("kg", Dim);
  mass.description = "lumped node mass of the last step";
  mass.values = nodes.mass;
  FrameArray velocity;
  velocity.name = "velocity";
  velocity.shape = ArrayShape::vector;
  velocity.units = "m/s";
  velocity.components = vector_components;
  velocity.description = "node velocity at the end of the last step";
  velocity.values.assign(static_cast<std::size_t>(3 * count), 0.0);
  for (Index n = 0; n < count; ++n) {
    for (int d = 0; d < Dim && d < 3; ++d) {
      velocity.values[static_cast<std::size_t>(3 * n + d)] = nodes.velocity[n][d];
    }
  }
  arrays.arrays.push_back(std::move(mass));
  arrays.arrays.push_back(std::move(velocity));
  XdmfMesh mesh = detail::put_point_mesh(file, "/grid", "grid", arrays, count);
  file.set_attribute("node_count", static_cast<std::int64_t>(count), "/grid");
  std::vector<std::int64_t> per_axis;
  std::vector<double> origin;
  std::vector<double> cell_size;
  for (int d = 0; d < Dim; ++d) {
    per_axis.push_back(static_cast<std::int64_t>(grid.nodes(d)));
    origin.push_back(grid.origin()[d]);
    cell_size.push_back(grid.cell_size()[d]);
  }
  file.set_attribute("nodes_per_axis", per_axis, "/grid");
  file.set_attribute("origin", origin, "/grid");
  file.set_attribute("cell_size", cell_size, "/grid");
  return mesh;
}

}  // namespace cosmpm::io::detail
