#pragma once
// Exact return for perfect plasticity with up to six linear yield planes in principal-stress
// space (Koiter's rule, non-associated flow allowed): try every active set of one to three planes
// and accept the first whose multipliers are non-negative and whose stress violates no plane.
// Used where the closed-form Mohr-Coulomb regions do not apply (a tension cut-off below the apex)
// and by the tests as an independent oracle for the closed-form regions.
#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <bit>
#include <cmath>

namespace cosmpm::material::detail {

template <class T>
struct PlaneSet {
  static constexpr int max_planes = 6;
  int count = 0;
  std::array<Eigen::Matrix<T, 3, 1>, max_planes> normal{};       // a_i: f_i = a_i . sigma - r_i
  std::array<T, max_planes> offset{};                            // r_i
  std::array<Eigen::Matrix<T, 3, 1>, max_planes> flow_stress{};  // D b_i, b_i = d g_i / d sigma

  void add(const Eigen::Matrix<T, 3, 1>& a, T r, const Eigen::Matrix<T, 3, 1>& d_times_b) {
    normal[count] = a;
    offset[count] = r;
    flow_stress[count] = d_times_b;
    ++count;
  }
};

// Returns false if no active set satisfies the conditions (then the caller decides). On success
// `returned` holds the stress and, if `map` is given, d returned / d trial.
template <class T>
bool multisurface_return(const PlaneSet<T>& planes, const Eigen::Matrix<T, 3, 1>& trial,
                         T tolerance, Eigen::Matrix<T, 3, 1>& returned,
                         Eigen::Matrix<T, 3, 3>* map = nullptr) {
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  const unsigned all = (1u << planes.count) - 1u;
  for (int size = 1; size <= 3; ++size) {
    for (unsigned set = 1; set <= all; ++set) {
      if (std::popcount(set) != size) continue;
      std::array<int, 3> active{};
      int n = 0;
      for (int i = 0; i < planes.count; ++i)
        if (set & (1u << i)) active[n++] = i;
      // sum_j (a_i . D b_j) dl_j = f_i(trial) for the active i.
      Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> matrix(n, n);
      Eigen::Matrix<T, Eigen::Dynamic, 1, 0, 3, 1> rhs(n);
      for (int i = 0; i < n; ++i) {
        rhs[i] = planes.normal[active[i]].dot(trial) - planes.offset[active[i]];
        for (int j = 0; j < n; ++j)
          matrix(i, j) = planes.normal[active[i]].dot(planes.flow_stress[active[j]]);
      }
      Eigen::FullPivLU<Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>> lu(matrix);
      if (!lu.isInvertible()) continue;
      const Eigen::Matrix<T, Eigen::Dynamic, 1, 0, 3, 1> multipliers = lu.solve(rhs);
      bool ok = true;
      Vec3 candidate = trial;
      for (int j = 0; j < n; ++j) {
        // Compared in stress units so one tolerance serves both checks.
        if (multipliers[j] * planes.flow_stress[active[j]].norm() < -tolerance) ok = false;
        candidate -= multipliers[j] * planes.flow_stress[active[j]];
      }
      if (!ok) continue;
      for (int i = 0; i < planes.count && ok; ++i)
        ok = planes.normal[i].dot(candidate) - planes.offset[i] <= tolerance;
      if (!ok) continue;
      returned = candidate;
      if (map) {
        // returned = trial - [D b] M^-1 ([a]^T trial - r)
        Eigen::Matrix<T, 3, Eigen::Dynamic, 0, 3, 3> flows(3, n);
        Eigen::Matrix<T, 3, Eigen::Dynamic, 0, 3, 3> normals(3, n);
        for (int j = 0; j < n; ++j) {
          flows.col(j) = planes.flow_stress[active[j]];
          normals.col(j) = planes.normal[active[j]];
        }
        *map = Eigen::Matrix<T, 3, 3>::Identity() - flows * lu.inverse() * normals.transpose();
      }
      return true;
    }
  }
  return false;
}

}  // namespace cosmpm::material::detail
