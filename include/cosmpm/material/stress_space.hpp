#pragma once
// The component order of the classical (nonpolar) stress and strain vectors, in plane strain and
// in 3D: the convention the models, the engine and the output share.
//
//   Dim = 2 (plane strain):  [xx, yy, zz, xy]               (SymTensor2D, sigma_zz carried)
//   Dim = 3:                 [xx, yy, zz, xy, xz, yz]
//
// Tension positive. Shear components are TENSOR components: the strain vector holds
// eps_xy = gamma_xy / 2 (not the engineering gamma_xy), the stress vector sigma_xy, so that
// sigma_xy = 2 G eps_xy elastically and the power is sigma : eps = sum of the normal products +
// 2 sum of the shear products. The 3D order extends the plane-strain one (the first four
// components are the same), as in Abaqus (11, 22, 33, 12, 13, 23). A consistent tangent is
// tangent(a, b) = d stress[a] / d strain[b] in this order.
#include <Eigen/Core>
#include <array>
#include <string_view>

namespace cosmpm::material {

// The number of stress components of the classical models in dimension Dim.
template <int Dim>
inline constexpr int symmetric_components = [] {
  static_assert(Dim == 2 || Dim == 3, "material: Dim is 2 (plane strain) or 3");
  return Dim == 2 ? 4 : 6;
}();

// A classical stress or strain vector in dimension Dim (Dim = 2 is SymTensor2D).
template <int Dim, class T = double>
using SymmetricTensor = Eigen::Matrix<T, symmetric_components<Dim>, 1>;

// Component c is the tensor entry (i, j) = tensor_index<Dim>[c] (and (j, i)).
template <int Dim>
inline constexpr std::array<std::array<int, 2>, symmetric_components<Dim>> tensor_index = [] {
  if constexpr (Dim == 2) {
    return std::array<std::array<int, 2>, 4>{{{0, 0}, {1, 1}, {2, 2}, {0, 1}}};
  } else {
    return std::array<std::array<int, 2>, 6>{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
  }
}();

// The component names in order ("xx", ...), for output.
template <int Dim>
inline constexpr std::array<std::string_view, symmetric_components<Dim>> component_names = [] {
  if constexpr (Dim == 2) {
    return std::array<std::string_view, 4>{"xx", "yy", "zz", "xy"};
  } else {
    return std::array<std::string_view, 6>{"xx", "yy", "zz", "xy", "xz", "yz"};
  }
}();

// The vector as a symmetric 3x3 tensor (plane strain: xz = yz = 0) and back.
template <int Dim, class T>
Eigen::Matrix<T, 3, 3> to_tensor(const SymmetricTensor<Dim, T>& v) {
  Eigen::Matrix<T, 3, 3> m = Eigen::Matrix<T, 3, 3>::Zero();
  for (int c = 0; c < symmetric_components<Dim>; ++c) {
    const auto [i, j] = tensor_index<Dim>[c];
    m(i, j) = m(j, i) = v[c];
  }
  return m;
}
template <int Dim, class T>
SymmetricTensor<Dim, T> from_tensor(const Eigen::Matrix<T, 3, 3>& m) {
  SymmetricTensor<Dim, T> v;
  for (int c = 0; c < symmetric_components<Dim>; ++c) {
    const auto [i, j] = tensor_index<Dim>[c];
    v[c] = m(i, j);
  }
  return v;
}

}  // namespace cosmpm::material
