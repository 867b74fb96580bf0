#pragma once
// Structured Cartesian background grid. Nodes are numbered x fastest: node (i, j) of a 2D grid
// has index i + j * nodes(0). Cell sizes may differ per axis (the paper's 80 x 50 mesh has
// 15 mm x 14 mm cells).
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::grid {

template <int Dim>
class Grid {
 public:
  static constexpr int dim = Dim;

  Grid() = default;

  // A grid spanning [origin, origin + extent] with `cells[d]` cells along axis d.
  Grid(const Vec<Dim>& origin, const Vec<Dim>& extent, const std::array<Index, Dim>& cells)
      : origin_(origin), cells_(cells) {
    for (int d = 0; d < Dim; ++d) {
      const std::string axis = "axis " + std::to_string(d);
      require_positive("Grid", "extent along " + axis, extent[d]);
      require_in_range("Grid", "cell count along " + axis, static_cast<double>(cells[d]), 1.0, 1e8,
                       Bounds::closed);
      cell_size_[d] = extent[d] / static_cast<double>(cells[d]);
      inv_cell_size_[d] = 1.0 / cell_size_[d];
      nodes_[d] = cells[d] + 1;
    }
    node_total_ = 1;
    for (int d = 0; d < Dim; ++d) node_total_ *= nodes_[d];
  }

  const Vec<Dim>& origin() const { return origin_; }
  const Vec<Dim>& cell_size() const { return cell_size_; }
  const Vec<Dim>& inverse_cell_size() const { return inv_cell_size_; }
  Vec<Dim> extent() const {
    Vec<Dim> e;
    for (int d = 0; d < Dim; ++d) e[d] = cell_size_[d] * static_cast<double>(cells_[d]);
    return e;
  }
  Index cells(int axis) const { return cells_[axis]; }
  Index nodes(int axis) const { return nodes_[axis]; }
  Index node_count() const { return node_total_; }
  double cell_volume() const {
    double v = 1.0;
    for (int d = 0; d < Dim; ++d) v *= cell_size_[d];
    return v;
  }
  double min_cell_size() const { return cell_size_.minCoeff(); }

  Index node_index(const std::array<Index, Dim>& ijk) const {
    Index index = 0;
    for (int d = Dim - 1; d >= 0; --d) index = index * nodes_[d] + ijk[d];
    return index;
  }
  std::array<Index, Dim> node_ijk(Index index) const {
    std::array<Index, Dim> ijk{};
    for (int d = 0; d < Dim; ++d) {
      ijk[d] = index % nodes_[d];
      index /= nodes_[d];
    }
    return ijk;
  }
  Vec<Dim> node_position(Index index) const {
    const auto ijk = node_ijk(index);
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = origin_[d] + cell_size_[d] * static_cast<double>(ijk[d]);
    return x;
  }
  // Position in cell units from the origin: node k of axis d sits at k.
  Vec<Dim> to_cell_units(const Vec<Dim>& x) const {
    return (x - origin_).cwiseProduct(inv_cell_size_);
  }
  // Strictly inside the grid box (particles on the outer faces have no full stencil).
  bool contains(const Vec<Dim>& x) const {
    for (int d = 0; d < Dim; ++d) {
      const double xi = (x[d] - origin_[d]) * inv_cell_size_[d];
      if (!(xi > 0.0 && xi < static_cast<double>(cells_[d]))) return false;
    }
    return true;
  }

 private:
  Vec<Dim> origin_ = Vec<Dim>::Zero();
  Vec<Dim> cell_size_ = Vec<Dim>::Ones();
  Vec<Dim> inv_cell_size_ = Vec<Dim>::Ones();
  std::array<Index, Dim> cells_{};
  std::array<Index, Dim> nodes_{};
  Index node_total_ = 0;
};

// Calls f(node index) for the nodes lo[d] <= ijk[d] <= hi[d] of every axis, x fastest (the
// grid's own numbering order, so sums over the nodes do not depend on the dimension's code).
template <int Dim, class F>
void for_each_node_in_box(const Grid<Dim>& grid,
                          const std::type_identity_t<std::array<Index, Dim>>& lo,
                          const std::type_identity_t<std::array<Index, Dim>>& hi, F&& f) {
  for (int d = 0; d < Dim; ++d) {
    if (hi[d] < lo[d]) return;
  }
  std::array<Index, Dim> ijk = lo;
  while (true) {
    f(grid.node_index(ijk));
    int d = 0;
    while (d < Dim && ijk[d] == hi[d]) {
      ijk[d] = lo[d];
      ++d;
    }
    if (d == Dim) return;
    ++ijk[d];
  }
}

}  // namespace cosmpm::grid
