#pragma once
// What the conformance kit (conformance.hpp) works on: sample steps of a constitutive model,
// their random generation, and the rotations of the stress and strain layouts (plane strain
// [xx, yy, zz, xy], 3D [xx, yy, zz, xy, xz, yz], Cosserat [xx, yy, zz, xy, yx, m31, m32]).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <concepts>
#include <random>
#include <type_traits>
#include <vector>

#include "cosmpm/material/concept.hpp"

namespace cosmpm::material::conformance {

// One step: old stress, state and strain increment.
template <class M>
struct Step {
  typename M::stress_type old;
  typename M::state_type state{};
  typename M::strain_type increment;
};

namespace detail {

template <class M>
constexpr bool has_yield = requires(const M& m, const typename M::stress_type& s) {
  { m.yield_function(s) } -> std::convertible_to<double>;
};

template <class M>
constexpr bool plastic_state = std::is_same_v<typename M::state_type, PlasticState>;

}  // namespace detail

// --- rotations of the stress and strain layouts ---------------------------------------------

// The vector's components as the 3x3 tensor (plane strain [xx, yy, zz, xy], 3D [xx, yy, zz, xy,
// xz, yz], Cosserat [xx, yy, zz, xy, yx, m31, m32] with the couple vector in `couple`).
template <class Vector>
Eigen::Matrix3d as_tensor(const Vector& v, Eigen::Vector3d* couple = nullptr) {
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  t(0, 0) = v[0], t(1, 1) = v[1], t(2, 2) = v[2];
  if constexpr (Vector::RowsAtCompileTime == 4) {
    t(0, 1) = t(1, 0) = v[3];
  } else if constexpr (Vector::RowsAtCompileTime == 6) {
    t(0, 1) = t(1, 0) = v[3];
    t(0, 2) = t(2, 0) = v[4];
    t(1, 2) = t(2, 1) = v[5];
  } else {
    static_assert(Vector::RowsAtCompileTime == 7);
    t(0, 1) = v[3];  // s_xy: first index the face normal
    t(1, 0) = v[4];
    if (couple) *couple = Eigen::Vector3d(v[5], v[6], 0);
  }
  return t;
}
template <class Vector>
Vector from_tensor(const Eigen::Matrix3d& t, const Eigen::Vector3d& couple = {}) {
  Vector v;
  v[0] = t(0, 0), v[1] = t(1, 1), v[2] = t(2, 2);
  if constexpr (Vector::RowsAtCompileTime == 4) {
    v[3] = t(0, 1);
  } else if constexpr (Vector::RowsAtCompileTime == 6) {
    v[3] = t(0, 1), v[4] = t(0, 2), v[5] = t(1, 2);
  } else {
    v[3] = t(0, 1), v[4] = t(1, 0), v[5] = couple[0], v[6] = couple[1];
  }
  return v;
}
// R v R^T, and the couple stress or curvature vector as a vector.
template <class Vector>
Vector rotated(const Vector& v, const Eigen::Matrix3d& r) {
  Eigen::Vector3d couple = Eigen::Vector3d::Zero();
  const Eigen::Matrix3d t = as_tensor(v, &couple);
  return from_tensor<Vector>(r * t * r.transpose(), r * couple);
}
// A random rotation: about z for the plane layouts (4 and 7 components), any for 3D.
template <int Components>
Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  if constexpr (Components == 6) {
    Eigen::Quaterniond q(unit(rng), unit(rng), unit(rng), unit(rng));
    return q.normalized().toRotationMatrix();
  } else {
    return Eigen::AngleAxisd(3.2 * unit(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
}

// --- sample steps ---------------------------------------------------------------------------

// Random steps around a compressive stress of `pressure` (Pa): the old stress inside the yield
// surface (drawn again until it is), increments of four sizes relative to `strain` (1e-4, 0.1,
// 1 and 10 times; the small ones elastic, the large ones plastic), and every tenth step pulled
// apart by 10 strain in all three normal directions (the apex or tension cut-off). Couple
// stresses (Cosserat layout) are scaled by the characteristic length `length`.
template <class M>
std::vector<Step<M>> random_steps(const M& model, std::size_t count, unsigned seed, double pressure,
                                  double strain, double length = 0.01) {
  constexpr int n = M::stress_type::RowsAtCompileTime;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), uniform(0.0, 1.0);
  std::vector<Step<M>> steps;
  const std::array<double, 4> sizes{1e-4, 0.1, 1.0, 10.0};
  while (steps.size() < count) {
    Step<M> step;
    const double p = pressure * (0.2 + uniform(rng));
    for (int c = 0; c < n; ++c) step.old[c] = 0.3 * p * unit(rng);
    for (int c = 0; c < 3; ++c) step.old[c] -= p;
    if constexpr (n == 7) {
      step.old[5] *= length;
      step.old[6] *= length;
    }
    if constexpr (detail::has_yield<M>) {
      if (model.yield_function(step.old) > 0.0) continue;
    }
    const double size = strain * sizes[steps.size() % sizes.size()];
    for (int c = 0; c < n; ++c) step.increment[c] = size * unit(rng);
    if constexpr (n == 7) {
      step.increment[5] /= length;
      step.increment[6] /= length;
    }
    if (steps.size() % 10 == 9) step.increment.template head<3>().array() += 10 * strain;
    if constexpr (detail::plastic_state<M>) {
      step.state = {1e-3 * uniform(rng), uniform(rng) < 0.5 ? 1.0 : 0.0};  // stale flag
    }
    steps.push_back(step);
  }
  return steps;
}

}  // namespace cosmpm::material::conformance
