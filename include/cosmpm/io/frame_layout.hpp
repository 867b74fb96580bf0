#pragma once
// The arrays of a frame, with no HDF5: every particle field as a scalar (N values), a vector
// (N x 3, 2D padded with zeros) or a tensor (N x 9, row-major xx xy xz yx yy yz zx zy zz),
// the shapes both of ParaView's XDMF readers read the same way. Each array carries its unit,
// its component names and its meaning. Nothing is a view into another array, so no reader
// can drop one.
//
//   2D plane-strain stress [xx, yy, zz, xy]     -> tensor, sigma_yx = sigma_xy
//   Cosserat [xx, yy, zz, xy, yx, m_31, m_32]   -> tensor (sigma_xy != sigma_yx) plus the
//                                                  vector couple_stress (m_31, m_32, 0);
//                                                  strain likewise with curvature
//   Mat<2> (velocity and deformation gradient) -> tensor, zz = 0 (F_zz = 1)
//   material state                              -> one scalar per label
//   other Eigen shapes                          -> one scalar per component (label_0, ...)
// plus displacement = position - initial_position. position itself is the geometry.
#include <cstdint>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/io/field_layout.hpp"
#include "cosmpm/material/stress_space.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::io {

enum class ArrayShape { scalar, vector, tensor };

inline constexpr const char* vector_components = "x y z";
inline constexpr const char* tensor_components = "xx xy xz yx yy yz zx zy zz";

struct FrameArray {
  std::string name;  // dataset name and ParaView array name
  ArrayShape shape = ArrayShape::scalar;
  bool integer = false;  // int32 scalars (body index)
  std::string units;
  std::string components;  // vector_components, tensor_components or empty
  std::string description;
  std::vector<double> values;  // N, N x 3 or N x 9 values, row-major
  std::vector<std::int32_t> integers;

  Index columns() const {
    return shape == ArrayShape::scalar ? 1 : shape == ArrayShape::vector ? 3 : 9;
  }
};

// The particle arrays of one frame and the geometry.
struct FrameArrays {
  int dimension = 0;             // of the space the particles live in
  std::vector<double> geometry;  // N x 3 positions
  std::vector<FrameArray> arrays;
};

namespace detail {

// Row-major 3 x 3 index of (i, j).
constexpr std::size_t t9(int i, int j) {
  return static_cast<std::size_t>(3 * i + j);
}

template <class V>
void put_vector(std::vector<double>& out, std::size_t p, const V& v) {
  for (Index d = 0; d < EigenFixed<V>::rows && d < 3; ++d) out[3 * p + d] = v[d];
}

class ArrayList {
 public:
  explicit ArrayList(Index points) : points_(points) {}

  FrameArray& add(std::string name, ArrayShape shape, std::string units, std::string description,
                  bool integer = false) {
    if (!names_.insert(name).second) {
      throw Error("io: two particle fields or state labels would both be written as array '" +
                  name + "'; labels must be unique");
    }
    FrameArray array;
    array.name = std::move(name);
    array.shape = shape;
    array.integer = integer;
    array.units = std::move(units);
    array.description = std::move(description);
    if (shape == ArrayShape::vector) array.components = vector_components;
    if (shape == ArrayShape::tensor) array.components = tensor_components;
    const auto count = static_cast<std::size_t>(points_ * array.columns());
    if (integer) {
      array.integers.assign(count, 0);
    } else {
      array.values.assign(count, 0.0);
    }
    out_.arrays.push_back(std::move(array));
    return out_.arrays.back();
  }

  FrameArrays take() { return std::move(out_); }
  FrameArrays& result() { return out_; }

 private:
  Index points_;
  std::set<std::string> names_;
  FrameArrays out_;
};

// One Eigen-valued field into its arrays.
template <class Tag>
void add_eigen_field(ArrayList& list, const std::vector<typename Tag::value_type>& column, int dim,
                     const double* cell_size) {
  using V = typename Tag::value_type;
  using Info = FieldInfo<Tag>;
  constexpr Index rows = EigenFixed<V>::rows;
  constexpr Index cols = EigenFixed<V>::cols;
  const std::string label = Tag::label();
  const std::size_t n = column.size();
  if constexpr (Info::layout == TensorLayout::symmetric3d) {
    static_assert(cols == 1 && rows == 6, "io: a 3D symmetric tensor has 6 components");
    auto& tensor = list.add(label, ArrayShape::tensor, Info::units(dim), Info::description());
    for (std::size_t p = 0; p < n; ++p) {
      const Eigen::Matrix3d full = material::to_tensor<3, double>(column[p]);
      double* t = tensor.values.data() + 9 * p;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) t[t9(i, j)] = full(i, j);
      }
    }
  } else if constexpr (Info::layout == TensorLayout::symmetric2d ||
                       Info::layout == TensorLayout::cosserat2d) {
    static_assert(cols == 1 && (rows == 4 || rows == 7), "io: a 2D tensor has 4 or 7 components");
    auto& tensor = list.add(label, ArrayShape::tensor, Info::units(dim), Info::description());
    for (std::size_t p = 0; p < n; ++p) {
      const V& s = column[p];
      double* t = tensor.values.data() + 9 * p;
      if constexpr (rows == 4) {
        // The classical order is the library's own (material/stress_space.hpp).
        const Eigen::Matrix3d full = material::to_tensor<2, double>(s);
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) t[t9(i, j)] = full(i, j);
        }
      } else {
        // Cosserat [xx, yy, zz, xy, yx, ...]: not symmetric.
        t[t9(0, 0)] = s[0];
        t[t9(1, 1)] = s[1];
        t[t9(2, 2)] = s[2];
        t[t9(0, 1)] = s[3];
        t[t9(1, 0)] = s[4];
      }
    }
    if constexpr (Info::layout == TensorLayout::cosserat2d) {
      auto& couple = list.add(Info::couple_label, ArrayShape::vector, Info::couple_units(),
                              Info::couple_description());
      for (std::size_t p = 0; p < n; ++p) {
        couple.values[3 * p] = column[p][5];
        couple.values[3 * p + 1] = column[p][6];
      }
    }
  } else if constexpr (cols == 1 && rows <= 3) {
    if constexpr (std::is_same_v<Tag, particles::field::HalfWidth<static_cast<int>(rows)>>) {
      if (cell_size != nullptr) {
        auto& half = list.add(label, ArrayShape::vector, "m", Info::description());
        for (std::size_t p = 0; p < n; ++p) {
          for (Index d = 0; d < rows; ++d) half.values[3 * p + d] = column[p][d] * cell_size[d];
        }
        return;
      }
      auto& half =
          list.add(label + "_in_cells", ArrayShape::vector, Info::units(dim), Info::description());
      for (std::size_t p = 0; p < n; ++p) put_vector(half.values, p, column[p]);
      return;
    }
    if constexpr (std::is_same_v<Tag, particles::field::Position<static_cast<int>(rows)>>) {
      auto& geometry = list.result().geometry;
      geometry.assign(3 * n, 0.0);
      for (std::size_t p = 0; p < n; ++p) put_vector(geometry, p, column[p]);
      return;
    }
    auto& vector = list.add(label, ArrayShape::vector, Info::units(dim), Info::description());
    for (std::size_t p = 0; p < n; ++p) put_vector(vector.values, p, column[p]);
  } else if constexpr (rows == cols && rows <= 3) {
    auto& tensor = list.add(label, ArrayShape::tensor, Info::units(dim), Info::description());
    for (std::size_t p = 0; p < n; ++p) {
      double* t = tensor.values.data() + 9 * p;
      for (int i = rows; i < 3; ++i) t[t9(i, i)] = Info::out_of_plane_diagonal;
      for (Index i = 0; i < rows; ++i) {
        for (Index j = 0; j < cols; ++j)
          t[t9(static_cast<int>(i), static_cast<int>(j))] = column[p](i, j);
      }
    }
  } else {
    for (Index i = 0; i < rows; ++i) {
      for (Index j = 0; j < cols; ++j) {
        const std::string suffix =
            cols == 1 ? std::to_string(i) : std::to_string(i) + "_" + std::to_string(j);
        auto& scalar = list.add(label + "_" + suffix, ArrayShape::scalar, Info::units(dim),
                                Info::description());
        for (std::size_t p = 0; p < n; ++p) scalar.values[p] = column[p](i, j);
      }
    }
  }
}

template <class Store>
constexpr int store_dimension() {
  if constexpr (Store::template has<particles::field::Position<1>>) return 1;
  if constexpr (Store::template has<particles::field::Position<2>>) return 2;
  if constexpr (Store::template has<particles::field::Position<3>>) return 3;
  return 0;
}

}  // namespace detail

// The arrays of a frame of `store`. `cell_size` (one value per axis, or null) converts
// half_width from cell units to metres; without it the array is half_width_in_cells.
template <class Store>
FrameArrays particle_frame_arrays(const Store& store, const double* cell_size = nullptr) {
  constexpr int dim = detail::store_dimension<Store>();
  static_assert(dim > 0, "io: a frame needs the particles' Position<Dim> field");
  detail::ArrayList list(store.size());
  list.result().dimension = dim;
  detail::for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const auto& column = store.template get<Tag>();
    constexpr detail::FieldKind kind = detail::field_kind<V>();
    using Info = FieldInfo<Tag>;
    if constexpr (kind == detail::FieldKind::real) {
      list.add(Tag::label(), ArrayShape::scalar, Info::units(dim), Info::description()).values =
          column;
    } else if constexpr (kind == detail::FieldKind::integer) {
      list.add(Tag::label(), ArrayShape::scalar, Info::units(dim), Info::description(), true)
          .integers = column;
    } else if constexpr (kind == detail::FieldKind::eigen) {
      detail::add_eigen_field<Tag>(list, column, dim, cell_size);
    } else {
      for (std::size_t k = 0; k < V::labels.size(); ++k) {
        auto& array = list.add(std::string(V::labels[k]), ArrayShape::scalar, state_units<V>(k),
                               state_description<V>(k));
        for (std::size_t p = 0; p < column.size(); ++p) array.values[p] = column[p].values()[k];
      }
    }
  });
  using particles::field::InitialPosition;
  using particles::field::Position;
  if constexpr (Store::template has<InitialPosition<dim>>) {
    const auto& x = store.template get<Position<dim>>();
    const auto& x0 = store.template get<InitialPosition<dim>>();
    auto& u = list.add("displacement", ArrayShape::vector, "m",
                       "displacement from the start, position - initial_position");
    for (std::size_t p = 0; p < x.size(); ++p) {
      detail::put_vector(u.values, p, Vec<dim>(x[p] - x0[p]));
    }
  }
  return list.take();
}

}  // namespace cosmpm::io
