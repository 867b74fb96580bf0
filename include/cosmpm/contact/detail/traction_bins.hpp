#pragma once
// The binning behind RigidContact::traction_profile (2D, along an edge) and traction_map (3D,
// over a face): the recorded nodal forces of one edge or face, binned by their foot points and
// divided by the bin's width or area. Bin k is centred at phase + k * size, with the phase
// putting bin centres where grid lines cross the edge or face.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "cosmpm/contact/interface.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::detail {

inline Index bin_index(double at, double phase, double size) {
  return static_cast<Index>(std::floor((at - phase) / size + 0.5));
}

inline std::vector<contact::TractionBin> edge_traction_bins(
    const std::vector<contact::ContactNode<2>>& records, const contact::RigidBody<2>& body, int b,
    int edge, double bin_width, const Vec<2>& cell_size, const Vec<2>& origin) {
  using contact::NodeState;
  using contact::TractionBin;
  const Vec<2> t = body.edge_tangent(edge);
  const Vec<2> n = body.edge_normal(edge);
  if (bin_width == 0.0) bin_width = std::abs(t[0]) * cell_size[0] + std::abs(t[1]) * cell_size[1];
  const double length = body.edge_length(edge);
  // Bin k is centred at phase + k * width: grid nodes project onto bin centres.
  const double phase = (origin - body.edge_start(edge)).dot(t);
  const auto bin_of = [&](double along) { return bin_index(along, phase, bin_width); };
  const Index first = bin_of(0.0);
  const Index last = bin_of(length);
  std::vector<TractionBin> bins(static_cast<std::size_t>(last - first + 1));
  for (std::size_t k = 0; k < bins.size(); ++k) {
    bins[k].centre = phase + static_cast<double>(first + static_cast<Index>(k)) * bin_width;
    bins[k].width = bin_width;
  }
  for (const auto& r : records) {
    if (r.body != b || r.edge != edge) continue;
    const Index k = std::clamp(bin_of(r.along), first, last) - first;
    auto& bin = bins[static_cast<std::size_t>(k)];
    // The material pushes the body with -force_on_material.
    bin.normal_traction += r.force_on_material.dot(n) / bin_width;
    bin.shear_traction -= r.force_on_material.dot(t) / bin_width;
    if (r.state != NodeState::separating) ++bin.nodes;
  }
  return bins;
}

inline std::vector<contact::TractionPatch> face_traction_patches(
    const std::vector<contact::ContactNode<3>>& records, const contact::RigidBody<3>& body, int b,
    int face, Vec<2> size, const Vec<3>& cell_size, const Vec<3>& origin) {
  using contact::NodeState;
  using contact::TractionPatch;
  const contact::ConvexPolyhedron& shape = body.shape();
  const std::array<Vec<3>, 2> axes{shape.face_tangent(face), shape.face_bitangent(face)};
  Vec<2> phase;
  Vec<2> low = Vec<2>::Constant(std::numeric_limits<double>::infinity());
  Vec<2> high = -low;
  for (int i : shape.face_vertices(face)) {
    const Vec<2> c = shape.face_coordinates(face, shape.vertices()[static_cast<std::size_t>(i)]);
    low = low.cwiseMin(c);
    high = high.cwiseMax(c);
  }
  std::array<Index, 2> first{};
  std::array<Index, 2> count{};
  for (int k = 0; k < 2; ++k) {
    if (size[k] == 0.0) size[k] = axes[k].cwiseAbs().dot(cell_size);
    phase[k] = (origin - shape.face_origin(face)).dot(axes[k]);
    first[k] = bin_index(low[k], phase[k], size[k]);
    count[k] = bin_index(high[k], phase[k], size[k]) - first[k] + 1;
  }
  std::vector<TractionPatch> patches(static_cast<std::size_t>(count[0] * count[1]));
  for (Index kv = 0; kv < count[1]; ++kv) {
    for (Index ku = 0; ku < count[0]; ++ku) {
      auto& patch = patches[static_cast<std::size_t>(ku + count[0] * kv)];
      patch.centre = phase + Vec<2>(static_cast<double>(first[0] + ku) * size[0],
                                    static_cast<double>(first[1] + kv) * size[1]);
      patch.size = size;
    }
  }
  const double area = size[0] * size[1];
  const Vec<3>& n = shape.face_normal(face);
  for (const auto& r : records) {
    if (r.body != b || r.edge != face) continue;
    const Vec<2> at(r.along, r.across);
    std::array<Index, 2> k{};
    for (int a = 0; a < 2; ++a) {
      k[a] = std::clamp(bin_index(at[a], phase[a], size[a]) - first[a], Index{0}, count[a] - 1);
    }
    auto& patch = patches[static_cast<std::size_t>(k[0] + count[0] * k[1])];
    patch.normal_traction += r.force_on_material.dot(n) / area;
    patch.shear_traction -=
        Vec<2>(r.force_on_material.dot(axes[0]), r.force_on_material.dot(axes[1])) / area;
    if (r.state != NodeState::separating) ++patch.nodes;
  }
  return patches;
}

}  // namespace cosmpm::detail
