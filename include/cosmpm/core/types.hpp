#pragma once
// Scalar and fixed-size vector aliases shared by every layer. The spatial dimension is a
// template parameter throughout so 3D can follow without a rewrite; 2D is plane strain.
#include <Eigen/Core>
#include <cstddef>
#include <numbers>

namespace cosmpm {

using Index = std::ptrdiff_t;

template <int Dim, class T = double>
using Vec = Eigen::Matrix<T, Dim, 1>;

template <int Dim, class T = double>
using Mat = Eigen::Matrix<T, Dim, Dim>;

// Plane-strain stress and strain of a classical (nonpolar) point, tension positive:
// [xx, yy, zz, xy] with the tensor (not engineering) shear component.
template <class T = double>
using SymTensor2D = Eigen::Matrix<T, 4, 1>;

// Cosserat plane-strain stress or deformation:
// [xx, yy, zz, xy, yx, m_31 or kappa_31, m_32 or kappa_32]; see docs/theory.md.
template <class T = double>
using CosseratTensor2D = Eigen::Matrix<T, 7, 1>;

inline constexpr double pi = std::numbers::pi;

constexpr double degrees_to_radians(double degrees) {
  return degrees * pi / 180.0;
}
constexpr double radians_to_degrees(double radians) {
  return radians * 180.0 / pi;
}

}  // namespace cosmpm
