#pragma once
// How particle fields become arrays in output files, with no HDF5: the kind of each field's
// value type, row-major flattening of fixed-size Eigen values, and what each field means and
// is measured in (io::FieldInfo). Checkpoints (io/checkpoint.hpp) and frames
// (io/frame_layout.hpp) are both built on it.
//
// A field of your own is described by specialising io::FieldInfo for its tag, or by giving
// the tag `static constexpr const char* units()` and `description()`:
//
//   struct Temperature {
//     using value_type = double;
//     static constexpr const char* label() { return "temperature"; }
//     static constexpr const char* units() { return "K"; }
//     static constexpr const char* description() { return "grain temperature"; }
//   };
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::io {

namespace detail {

template <class V>
struct EigenFixed : std::false_type {};
template <int Rows, int Cols, int Options, int MaxRows, int MaxCols>
struct EigenFixed<Eigen::Matrix<double, Rows, Cols, Options, MaxRows, MaxCols>>
    : std::bool_constant<(Rows > 0 && Cols > 0)> {
  static constexpr Index rows = Rows;
  static constexpr Index cols = Cols;
};

// How a field value type maps to arrays.
enum class FieldKind { real, integer, eigen, state };

template <class V>
constexpr FieldKind field_kind() {
  if constexpr (std::is_same_v<V, double>) {
    return FieldKind::real;
  } else if constexpr (std::is_same_v<V, std::int32_t>) {
    return FieldKind::integer;
  } else if constexpr (EigenFixed<V>::value) {
    return FieldKind::eigen;
  } else {
    static_assert(material::OutputState<V> && std::is_trivially_copyable_v<V>,
                  "io: a particle field must be double, std::int32_t, a fixed-size Eigen double "
                  "matrix or a trivially copyable material state with labels and values()");
    return FieldKind::state;
  }
}

// Row-major flattening of a fixed-size Eigen column: element (i, j) of particle p goes to
// out[p * rows * cols + i * cols + j].
template <class V>
std::vector<double> flatten(const std::vector<V>& column) {
  constexpr Index rows = EigenFixed<V>::rows;
  constexpr Index cols = EigenFixed<V>::cols;
  std::vector<double> out(column.size() * static_cast<std::size_t>(rows * cols));
  std::size_t k = 0;
  for (const V& value : column) {
    for (Index i = 0; i < rows; ++i) {
      for (Index j = 0; j < cols; ++j) out[k++] = value(i, j);
    }
  }
  return out;
}

template <class V>
void unflatten(const std::vector<double>& flat, std::vector<V>& column) {
  constexpr Index rows = EigenFixed<V>::rows;
  constexpr Index cols = EigenFixed<V>::cols;
  std::size_t k = 0;
  for (V& value : column) {
    for (Index i = 0; i < rows; ++i) {
      for (Index j = 0; j < cols; ++j) value(i, j) = flat[k++];
    }
  }
}

template <class Store, class F>
void for_each_tag(F&& f) {
  [&]<class... Tags>(std::tuple<Tags...>*) {
    (f(Tags{}), ...);
  }(static_cast<typename Store::tags*>(nullptr));
}

// Units of an amount per unit of the space's extent: mass in 2D is kg per metre out of plane.
inline std::string per_out_of_plane(const char* units, int dim) {
  if (dim == 3) return units;
  return std::string(units) + (dim == 2 ? "/m" : "/m^2");
}

}  // namespace detail

// How the stress-like values of a field are laid out (core/types.hpp,
// material/stress_space.hpp).
enum class TensorLayout {
  none,         // not a tensor stored as a column
  symmetric2d,  // [xx, yy, zz, xy] (plane strain)
  symmetric3d,  // [xx, yy, zz, xy, xz, yz]
  cosserat2d,   // [xx, yy, zz, xy, yx, c_31, c_32]: a non-symmetric tensor plus a 2-vector
};

namespace detail {
// The layout of a model's stress or strain vector, from its number of components.
template <class V>
constexpr TensorLayout stress_like_layout() {
  constexpr Index rows = EigenFixed<V>::rows;
  if constexpr (rows == 7) {
    return TensorLayout::cosserat2d;
  } else if constexpr (rows == 6) {
    return TensorLayout::symmetric3d;
  } else {
    return TensorLayout::symmetric2d;
  }
}
}  // namespace detail

// What a particle field means and its unit. The primary template reads the tag's own
// units() and description() if it has them.
template <class Tag>
struct FieldInfo {
  static std::string units(int /*dim*/) {
    if constexpr (requires { Tag::units(); }) {
      return Tag::units();
    } else {
      return "unknown";
    }
  }
  static std::string description() {
    if constexpr (requires { Tag::description(); }) {
      return Tag::description();
    } else {
      return "";
    }
  }
  static constexpr TensorLayout layout = TensorLayout::none;
  // Value of the out-of-plane diagonal when a 2D matrix is shown as a 3 x 3 tensor.
  static constexpr double out_of_plane_diagonal = 0.0;
};

namespace detail {
struct SimpleInfo {
  static constexpr TensorLayout layout = TensorLayout::none;
  static constexpr double out_of_plane_diagonal = 0.0;
};
}  // namespace detail

template <int D>
struct FieldInfo<particles::field::Position<D>> : detail::SimpleInfo {
  static std::string units(int) { return "m"; }
  static std::string description() { return "particle position"; }
};
template <int D>
struct FieldInfo<particles::field::InitialPosition<D>> : detail::SimpleInfo {
  static std::string units(int) { return "m"; }
  static std::string description() { return "particle position at the start of the run"; }
};
template <int D>
struct FieldInfo<particles::field::Velocity<D>> : detail::SimpleInfo {
  static std::string units(int) { return "m/s"; }
  static std::string description() { return "particle velocity"; }
};
template <int D>
struct FieldInfo<particles::field::VelocityGradient<D>> : detail::SimpleInfo {
  static std::string units(int) { return "1/s"; }
  static std::string description() {
    return "velocity gradient of the last step, L_ij = d v_i / d x_j";
  }
};
template <int D>
struct FieldInfo<particles::field::DeformationGradient<D>> : detail::SimpleInfo {
  static std::string units(int) { return "1"; }
  static std::string description() {
    return "deformation gradient F_ij = d x_i / d X_j (plane strain: F_zz = 1)";
  }
  static constexpr TensorLayout layout = TensorLayout::none;
  static constexpr double out_of_plane_diagonal = 1.0;
};
template <int D>
struct FieldInfo<particles::field::HalfWidth<D>> : detail::SimpleInfo {
  // Stored in cell units; frames of a simulation convert it to metres (frame_layout.hpp).
  static std::string units(int) { return "cell widths"; }
  static std::string description() { return "particle half-size along each axis"; }
};
template <>
struct FieldInfo<particles::field::Mass> : detail::SimpleInfo {
  static std::string units(int dim) { return detail::per_out_of_plane("kg", dim); }
  static std::string description() { return "particle mass (2D: per metre out of plane)"; }
};
template <>
struct FieldInfo<particles::field::Volume> : detail::SimpleInfo {
  static std::string units(int dim) { return detail::per_out_of_plane("m^3", dim); }
  static std::string description() { return "particle volume (2D: area, per metre out of plane)"; }
};
template <>
struct FieldInfo<particles::field::InitialVolume> : detail::SimpleInfo {
  static std::string units(int dim) { return detail::per_out_of_plane("m^3", dim); }
  static std::string description() { return "particle volume at the start of the run"; }
};
template <>
struct FieldInfo<particles::field::Body> : detail::SimpleInfo {
  static std::string units(int) { return "1"; }
  static std::string description() { return "index of the body the particle belongs to"; }
};
template <class Model>
struct FieldInfo<particles::field::Stress<Model>> {
  static std::string units(int) { return "Pa"; }
  static std::string description() {
    return "Cauchy stress sigma_ij (face normal i, direction j), tension positive";
  }
  static constexpr TensorLayout layout = detail::stress_like_layout<typename Model::stress_type>();
  static constexpr double out_of_plane_diagonal = 0.0;
  // The Cosserat part: couple stresses m_31, m_32.
  static constexpr const char* couple_label = "couple_stress";
  static std::string couple_units() { return "N/m"; }
  static std::string couple_description() { return "couple stress m_31, m_32"; }
};
template <class Model>
struct FieldInfo<particles::field::Strain<Model>> {
  static std::string units(int) { return "1"; }
  static std::string description() {
    return "accumulated small strain (logarithmic rate) eps_ij, extension positive";
  }
  static constexpr TensorLayout layout = detail::stress_like_layout<typename Model::strain_type>();
  static constexpr double out_of_plane_diagonal = 0.0;
  static constexpr const char* couple_label = "curvature";
  static std::string couple_units() { return "1/m"; }
  static std::string couple_description() { return "Cosserat curvature kappa_31, kappa_32"; }
};
template <>
struct FieldInfo<particles::field::MicroRotation> : detail::SimpleInfo {
  static std::string units(int) { return "rad"; }
  static std::string description() { return "Cosserat rotation omega_3, counter-clockwise"; }
};
template <>
struct FieldInfo<particles::field::MicroSpin> : detail::SimpleInfo {
  static std::string units(int) { return "rad/s"; }
  static std::string description() { return "Cosserat spin d omega_3 / dt"; }
};
template <>
struct FieldInfo<particles::field::MicroInertia> : detail::SimpleInfo {
  static std::string units(int) { return "m^2"; }
  static std::string description() { return "Cosserat micro-inertia J per unit mass"; }
};

// Units and meaning of one label of a material state: from the state's own `units` and
// `descriptions` arrays when it has them, else from the labels of the library's states.
template <class State>
std::string state_units(std::size_t k) {
  if constexpr (requires { State::units[0]; }) {
    return std::string(State::units[k]);
  } else {
    const std::string_view label = State::labels[k];
    if (label == "plastic_shear_strain" || label == "plastic" || label == "separation") return "1";
    return "unknown";
  }
}
template <class State>
std::string state_description(std::size_t k) {
  if constexpr (requires { State::descriptions[0]; }) {
    return std::string(State::descriptions[k]);
  } else {
    const std::string_view label = State::labels[k];
    if (label == "plastic_shear_strain") return "accumulated equivalent plastic shear strain";
    if (label == "plastic") return "1 if the last update returned to the yield surface, else 0";
    if (label == "separation") return "volumetric strain by which the grains have come apart";
    return "";
  }
}

}  // namespace cosmpm::io
