#pragma once
// The spectral split of a 3D trial stress for the isotropic principal-space returns (Mohr-Coulomb):
// sorted principal values and their directions, the returned stress rebuilt with the trial's
// directions (isotropy keeps them), and the consistent tangent of such a return.
//
// Component order [xx, yy, zz, xy, xz, yz], tensor shear (stress_space.hpp).
//
// Tangent. With n_i the trial directions (sorted s1 >= s2 >= s3), M_kl = (n_k n_l^T + n_l n_k^T) /
// 2, P_kl its stress-side vector [M_xx, M_yy, M_zz, M_xy, M_xz, M_yz] and Q_kl its strain-side
// one [M_xx, M_yy, M_zz, 2 M_xy, 2 M_xz, 2 M_yz] (so Q_kl . de is n_k . de n_l):
//   d sigma / d eps = sum_ij (A D_p)_ij P_ii Q_jj^T + 4 G sum_(k<l) rho_kl P_kl Q_kl^T,
// A = d r / d s (the principal return's map), D_p the principal elastic matrix, and
// rho_kl = (r_k - r_l) / (s_k - s_l) the factor by which the return scales the shear in the
// plane of n_k, n_l (the directions are kept), its limit for s_k = s_l the map's derivative
// along s_k - s_l. In plane strain (n_3 = z) this is principal_2d.hpp's spectral_tangent.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

#include "cosmpm/material/detail/isotropic_elasticity.hpp"

namespace cosmpm::material::detail {

template <class T>
class Spectral3D {
 public:
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  using Mat3 = Eigen::Matrix<T, 3, 3>;
  using Vec6 = Eigen::Matrix<T, 6, 1>;
  using Mat6 = Eigen::Matrix<T, 6, 6>;

  // The split of a trial [xx, yy, zz, xy, xz, yz].
  explicit Spectral3D(const std::array<T, 6>& t) {
    Mat3 m;
    m << t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2];
    // The closed form first: about a tenth of the iterative solver's cost here. Its
    // eigenvalues lose digits as two of them merge (the cubic's root is ill-conditioned
    // there) and its eigenvectors lose them as 1 / gap, so where the smaller gap is under
    // 1e-3 of the spread (errors then about 1e-13 of it) the iterative solver, accurate to
    // rounding for any gap, redoes the split. A non-finite trial fails the test too.
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(m);
    const Vec3& values = solver.eigenvalues();
    if (!(std::min(values[1] - values[0], values[2] - values[1]) >
          separated_gap * (values[2] - values[0])))
      solver.compute(m);
    // Eigen sorts ascending; s1 >= s2 >= s3 here.
    for (int i = 0; i < 3; ++i) {
      s_[i] = solver.eigenvalues()[2 - i];
      n_.col(i) = solver.eigenvectors().col(2 - i);
    }
  }

  T s1() const { return s_[0]; }
  T s2() const { return s_[1]; }
  T s3() const { return s_[2]; }

  // sum_i r_i n_i n_i^T as [xx, yy, zz, xy, xz, yz], written r2 I + (r1 - r2) n_1 n_1^T +
  // (r3 - r2) n_3 n_3^T: sum_i n_i n_i^T = I holds only to rounding, and so the apex (r1 = r2 =
  // r3) comes out exactly hydrostatic and an edge (r1 = r2 or r2 = r3) exactly axisymmetric.
  Vec6 back(T r1, T r2, T r3) const {
    const T d1 = r1 - r2, d3 = r3 - r2;
    Vec6 out;
    for (int c = 0; c < 6; ++c) {
      const int i = index_[c][0], j = index_[c][1];
      out[c] = d1 * n_(i, 0) * n_(j, 0) + d3 * n_(i, 2) * n_(j, 2);
      if (c < 3) out[c] += r2;
    }
    return out;
  }

  // The consistent tangent of the return (r1, r2, r3) with map d r / d s (sorted order).
  Mat6 tangent(const Mat3& map, const IsotropicElasticity<T>& elastic, T r1, T r2, T r3) const {
    const Vec3 r(r1, r2, r3);
    Mat3 elastic_principal = Mat3::Constant(elastic.lambda);
    elastic_principal.diagonal().array() += 2 * elastic.shear;
    const Mat3 principal = map * elastic_principal;
    std::array<Vec6, 3> p_normal, q_normal;
    for (int i = 0; i < 3; ++i) {
      p_normal[i] = projector(i, i, T(1));
      q_normal[i] = projector(i, i, T(2));
    }
    Mat6 out = Mat6::Zero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        out.noalias() += principal(i, j) * p_normal[i] * q_normal[j].transpose();
    const T scale = std::max({std::abs(s_[0]), std::abs(s_[2]), T(1)});
    for (int k = 0; k < 3; ++k) {
      for (int l = k + 1; l < 3; ++l) {
        const T gap = s_[k] - s_[l];
        const T ratio = gap > T(1e-12) * scale
                            ? (r[k] - r[l]) / gap
                            : (map(k, k) - map(k, l) - map(l, k) + map(l, l)) / 2;
        out.noalias() +=
            4 * elastic.shear * ratio * projector(k, l, T(1)) * projector(k, l, T(2)).transpose();
      }
    }
    return out;
  }

 private:
  // The components of (n_k n_l^T + n_l n_k^T) / 2, shears times `shear_factor` (1 on the
  // stress side, 2 on the strain side).
  Vec6 projector(int k, int l, T shear_factor) const {
    Vec6 v;
    for (int c = 0; c < 6; ++c) {
      const int i = index_[c][0], j = index_[c][1];
      const T m = (n_(i, k) * n_(j, l) + n_(i, l) * n_(j, k)) / 2;
      v[c] = c < 3 ? m : shear_factor * m;
    }
    return v;
  }

  static constexpr T separated_gap = T(1e-3);
  static constexpr int index_[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  Vec3 s_;
  Mat3 n_;  // columns n_1, n_2, n_3
};

}  // namespace cosmpm::material::detail
