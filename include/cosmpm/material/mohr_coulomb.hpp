#pragma once
// Perfectly plastic Mohr-Coulomb in plane strain with sigma_zz carried, non-associated flow and a
// tension cut-off. The return is exact (no iteration, no drift): it is done in principal-stress
// space, where the yield surface is a set of planes, after Clausen, Damkilde and Andersen (2006,
// 2007), and the stress is rotated back with the trial eigenvectors. See docs/theory/materials.md.
//
// Tension positive. Principal stresses sorted s1 >= s2 >= s3 (s3 the most compressive):
//   f = k s1 - s3 - 2 c sqrt(k),  k = (1 + sin phi) / (1 - sin phi)
//   g = m s1 - s3,                m = (1 + sin psi) / (1 - sin psi)
// Return regions: elastic, the yield plane, the compression edge (s1 = s2), the extension edge
// (s2 = s3), the apex (c cot phi, the default tension cut-off) and, when a lower cut-off is set,
// the tension cut-off regions (associated flow on s_i <= cut-off).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/elastic_parameters.hpp"
#include "cosmpm/material/detail/multisurface_return.hpp"
#include "cosmpm/material/detail/principal_2d.hpp"

namespace cosmpm::material {

// Where the last return mapping ended; `tension` is any return that involves the cut-off planes
// below the apex.
enum class MohrCoulombRegion { elastic, plane, compression_edge, extension_edge, apex, tension };

template <class T = double>
class MohrCoulomb {
 public:
  using scalar_type = T;
  using stress_type = SymTensor2D<T>;  // [xx, yy, zz, xy], tension positive
  using strain_type = SymTensor2D<T>;  // [dxx, dyy, dzz, dxy], tensor shear
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, 4, 4>;
  static constexpr bool is_cosserat = false;

  // Angles in degrees: 0 < phi < 90, 0 <= psi <= phi; cohesion c >= 0 (Pa). The tension
  // cut-off (Pa, the largest principal stress allowed) defaults to the apex c cot(phi) and may be
  // set anywhere in [0, c cot(phi)].
  MohrCoulomb(T youngs_modulus, T poisson_ratio, T friction_angle_deg, T dilatancy_angle_deg,
              T cohesion = T(0), std::optional<T> tension_cutoff = std::nullopt)
      : elastic_(detail::isotropic_elasticity<T>("MohrCoulomb", youngs_modulus, poisson_ratio)),
        phi_deg_(friction_angle_deg),
        psi_deg_(dilatancy_angle_deg),
        cohesion_(cohesion) {
    detail::check_friction_angles("MohrCoulomb", static_cast<double>(friction_angle_deg),
                                  static_cast<double>(dilatancy_angle_deg));
    require_non_negative("MohrCoulomb", "cohesion", static_cast<double>(cohesion));
    const T sin_phi = std::sin(T(degrees_to_radians(static_cast<double>(phi_deg_))));
    const T sin_psi = std::sin(T(degrees_to_radians(static_cast<double>(psi_deg_))));
    sin_phi_ = sin_phi;
    cos_phi_ = std::sqrt(1 - sin_phi * sin_phi);
    k_ = (1 + sin_phi) / (1 - sin_phi);
    m_ = (1 + sin_psi) / (1 - sin_psi);
    offset_ = 2 * cohesion_ * std::sqrt(k_);
    apex_ = cohesion_ * cos_phi_ / sin_phi;
    cutoff_ = apex_;
    if (tension_cutoff) {
      require_in_range("MohrCoulomb", "tension_cutoff", static_cast<double>(*tension_cutoff), 0.0,
                       static_cast<double>(apex_), Bounds::closed);
      cutoff_ = *tension_cutoff;
      has_cutoff_ = cutoff_ < apex_;
    }
    setup_return_geometry();
  }

  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }
  T friction_angle_deg() const { return phi_deg_; }
  T dilatancy_angle_deg() const { return psi_deg_; }
  T cohesion() const { return cohesion_; }
  T apex_stress() const { return apex_; }       // c cot(phi): all three principal stresses
  T tension_cutoff() const { return cutoff_; }  // largest principal stress allowed

  // f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) in Pa; <= 0 inside.
  T yield_function(const stress_type& stress) const {
    const auto spectrum = detail::plane_strain_spectrum(stress[0], stress[1], stress[2], stress[3]);
    const auto sorted = spectrum.sorted();
    return (sorted[0] - sorted[2]) + (sorted[0] + sorted[2]) * sin_phi_ - 2 * cohesion_ * cos_phi_;
  }

  // The hot path: scalar code for the regions of the cone with the cut-off at the apex (the
  // general path below handles a lower cut-off and gives the same results otherwise).
  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    const T g2 = 2 * elastic_.shear;
    const T volumetric = elastic_.lambda * (de[0] + de[1] + de[2]);
    const T xx = stress[0] + (volumetric + g2 * de[0]);
    const T yy = stress[1] + (volumetric + g2 * de[1]);
    const T zz = stress[2] + (volumetric + g2 * de[2]);
    const T xy = stress[3] + g2 * de[3];
    const T mean = (xx + yy) / 2;
    const T half = (xx - yy) / 2;
    const T radius = std::sqrt(half * half + xy * xy);
    const T a = mean + radius;
    const T b = mean - radius;
    const T s1 = std::max(a, zz);
    const T s2 = std::min(std::max(zz, b), a);
    const T s3 = std::min(b, zz);
    const T f = k_ * s1 - s3 - offset_;
    if (f <= T(0) && (!has_cutoff_ || s1 <= cutoff_)) {
      stress = stress_type(xx, yy, zz, xy);
      state.plastic = 0.0;
      return;
    }
    if (has_cutoff_) {
      stress = stress_type(xx, yy, zz, xy);
      (void)update_impl<false>(stress, state, strain_type::Zero(), nullptr);
      return;
    }
    // Yield plane first; if its result leaves the sorted sector, an edge line or the apex.
    T r1 = s1 - plane_step_[0] * f;
    T r2 = s2 - plane_step_[1] * f;
    T r3 = s3 - plane_step_[2] * f;
    T gamma;
    if (r1 >= r2 && r2 >= r3) {
      gamma = plane_gamma_ * f;
    } else {
      const bool compression_side = r1 < r2;
      const Vec3& normal = compression_side ? edge_c_scaled_normal_ : edge_e_scaled_normal_;
      const Vec3& direction = compression_side ? edge_c_direction_ : edge_e_direction_;
      const T t = std::min(
          T(0), normal[0] * (s1 - apex_) + normal[1] * (s2 - apex_) + normal[2] * (s3 - apex_));
      r1 = apex_ + t * direction[0];
      r2 = apex_ + t * direction[1];
      r3 = apex_ + t * direction[2];
      const T d1 = s1 - r1, d2 = s2 - r2, d3 = s3 - r3;
      const T removed_mean = (d1 + d2 + d3) / 3;
      gamma = std::sqrt(2 * ((d1 - removed_mean) * (d1 - removed_mean) +
                             (d2 - removed_mean) * (d2 - removed_mean) +
                             (d3 - removed_mean) * (d3 - removed_mean))) /
              g2;
    }
    // Back to (a, b, zz) by the rank sigma_zz had, then rotate with the trial directions.
    T na, nb, nz;
    if (zz >= a) {
      nz = r1, na = r2, nb = r3;
    } else if (zz >= b) {
      na = r1, nz = r2, nb = r3;
    } else {
      na = r1, nb = r2, nz = r3;
    }
    const T ratio = radius > T(0) ? (na - nb) / (2 * radius) : T(0);
    const T new_mean = (na + nb) / 2;
    stress = stress_type(new_mean + half * ratio, new_mean - half * ratio, nz, xy * ratio);
    state.plastic_shear_strain += static_cast<double>(gamma);
    state.plastic = 1.0;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    (void)update_impl<true>(stress, state, de, &tangent);
  }

  // The same update, reporting which return region it used (tests, diagnostics).
  MohrCoulombRegion update_region(stress_type& stress, state_type& state,
                                  const strain_type& de) const {
    return update_impl<false>(stress, state, de, nullptr);
  }

  tangent_type elastic_tangent() const {
    tangent_type d = tangent_type::Zero();
    d.template topLeftCorner<3, 3>().setConstant(elastic_.lambda);
    for (int i = 0; i < 3; ++i) d(i, i) += 2 * elastic_.shear;
    d(3, 3) = 2 * elastic_.shear;
    return d;
  }

  // The principal-space return on its own: `trial` sorted descending, result sorted likewise.
  // `map` (optional) receives d result / d trial. Exposed for tests and for 3D users.
  MohrCoulombRegion principal_return(const Eigen::Matrix<T, 3, 1>& trial,
                                     Eigen::Matrix<T, 3, 1>& result,
                                     Eigen::Matrix<T, 3, 3>* map = nullptr) const {
    const T f = k_ * trial[0] - trial[2] - offset_;
    if (f <= T(0) && (!has_cutoff_ || trial[0] <= cutoff_)) {
      result = trial;
      if (map) map->setIdentity();
      return MohrCoulombRegion::elastic;
    }
    MohrCoulombRegion region = fast_return(trial, f, result, map);
    if (has_cutoff_ && (result[0] > cutoff_ || f <= T(0))) {
      const T tolerance = T(1e-12) * std::max({trial.cwiseAbs().maxCoeff(), apex_, T(1)});
      const bool found = detail::multisurface_return(cutoff_planes_, trial, tolerance, result, map);
      if (!found) {  // unreachable for valid parameters: the cut-off octant always admits a return
        result = Vec3::Constant(cutoff_);
        if (map) map->setZero();
      }
      region = MohrCoulombRegion::tension;
    }
    return region;
  }

 private:
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  using Mat3 = Eigen::Matrix<T, 3, 3>;

  Vec3 elastic_times(const Vec3& v) const {
    return Vec3::Constant(elastic_.lambda * v.sum()) + 2 * elastic_.shear * v;
  }

  void setup_return_geometry() {
    // Yield plane f = a . s - offset, flow D b.
    normal_ = Vec3(k_, 0, -1);
    const Vec3 b_plane(m_, 0, -1);
    flow_plane_ = elastic_times(b_plane);
    plane_denominator_ = normal_.dot(flow_plane_);
    plane_step_ = flow_plane_ / plane_denominator_;
    // Plane region: the stress removed is f * plane_step_, so the plastic shear strain
    // sqrt(2 e:e) of its deviator / 2G is f times a constant.
    const Vec3 step_deviator = plane_step_ - Vec3::Constant(plane_step_.mean());
    plane_gamma_ = std::sqrt(2 * step_deviator.squaredNorm()) / (2 * elastic_.shear);
    // Compression edge s1 = s2: planes k s1 - s3 and k s2 - s3 both active. The return lies on
    // the line apex + t (1, 1, k) and moves in the span of their flows, so t follows from the
    // normal of that span.
    const Vec3 b_second(0, m_, -1);
    edge_c_direction_ = Vec3(1, 1, k_);
    edge_c_normal_ = flow_plane_.cross(elastic_times(b_second));
    edge_c_denominator_ = edge_c_normal_.dot(edge_c_direction_);
    edge_c_scaled_normal_ = edge_c_normal_ / edge_c_denominator_;
    // Extension edge s2 = s3: planes k s1 - s3 and k s1 - s2, line apex + t (1, k, k).
    const Vec3 b_third(m_, -1, 0);
    edge_e_direction_ = Vec3(1, k_, k_);
    edge_e_normal_ = flow_plane_.cross(elastic_times(b_third));
    edge_e_denominator_ = edge_e_normal_.dot(edge_e_direction_);
    edge_e_scaled_normal_ = edge_e_normal_ / edge_e_denominator_;
    // The general solver for a cut-off below the apex: the three Mohr-Coulomb planes that can be
    // active for sorted stresses and the three associated cut-off planes.
    cutoff_planes_.add(normal_, offset_, flow_plane_);
    cutoff_planes_.add(Vec3(0, k_, -1), offset_, elastic_times(b_second));
    cutoff_planes_.add(Vec3(k_, -1, 0), offset_, elastic_times(b_third));
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = Vec3::Unit(i);
      cutoff_planes_.add(e, cutoff_, elastic_times(e));
    }
  }

  // Closed-form regions of the Mohr-Coulomb cone with the cut-off at the apex.
  MohrCoulombRegion fast_return(const Vec3& trial, T f, Vec3& result, Mat3* map) const {
    result = trial - flow_plane_ * (f / plane_denominator_);
    if (result[0] >= result[1] && result[1] >= result[2]) {
      if (map) *map = Mat3::Identity() - flow_plane_ * normal_.transpose() / plane_denominator_;
      return MohrCoulombRegion::plane;
    }
    const Vec3 from_apex = trial - Vec3::Constant(apex_);
    const bool compression_side = result[0] < result[1];
    const Vec3& direction = compression_side ? edge_c_direction_ : edge_e_direction_;
    const Vec3& normal = compression_side ? edge_c_normal_ : edge_e_normal_;
    const T denominator = compression_side ? edge_c_denominator_ : edge_e_denominator_;
    const T t = normal.dot(from_apex) / denominator;
    if (t <= T(0)) {
      result = Vec3::Constant(apex_) + t * direction;
      if (map) *map = direction * normal.transpose() / denominator;
      return compression_side ? MohrCoulombRegion::compression_edge
                              : MohrCoulombRegion::extension_edge;
    }
    result = Vec3::Constant(apex_);
    if (map) map->setZero();
    return MohrCoulombRegion::apex;
  }

  template <bool WithTangent>
  MohrCoulombRegion update_impl(stress_type& stress, state_type& state, const strain_type& de,
                                tangent_type* tangent) const {
    const T g2 = 2 * elastic_.shear;
    const T volumetric = elastic_.lambda * (de[0] + de[1] + de[2]);
    const T xx = stress[0] + (volumetric + g2 * de[0]);
    const T yy = stress[1] + (volumetric + g2 * de[1]);
    const T zz = stress[2] + (volumetric + g2 * de[2]);
    const T xy = stress[3] + g2 * de[3];
    const auto spectrum = detail::plane_strain_spectrum(xx, yy, zz, xy);
    const Vec3 trial = spectrum.sorted();
    // Cheap elastic exit before anything else: the common case in a large batch.
    if (k_ * trial[0] - trial[2] - offset_ <= T(0) && (!has_cutoff_ || trial[0] <= cutoff_)) {
      stress = stress_type(xx, yy, zz, xy);
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_tangent();
      return MohrCoulombRegion::elastic;
    }
    Vec3 sorted_result;
    Mat3 sorted_map;
    const MohrCoulombRegion region =
        principal_return(trial, sorted_result, WithTangent ? &sorted_map : nullptr);
    Vec3 natural;
    for (int i = 0; i < 3; ++i) natural[spectrum.order[i]] = sorted_result[i];
    stress = detail::rotate_back(natural, spectrum.cos_2theta, spectrum.sin_2theta);

    // Plastic strain = compliance times the stress removed; its deviator gives the equivalent
    // (engineering) plastic shear strain sqrt(2 e:e).
    const Vec3 removed = spectrum.natural - natural;
    const Vec3 deviator = (removed - Vec3::Constant(removed.mean())) / g2;
    state.plastic_shear_strain += static_cast<double>(std::sqrt(2 * deviator.squaredNorm()));
    state.plastic = 1.0;

    if constexpr (WithTangent) {
      Mat3 natural_map;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          natural_map(spectrum.order[i], spectrum.order[j]) = sorted_map(i, j);
      Mat3 elastic_principal = Mat3::Constant(elastic_.lambda);
      elastic_principal.diagonal().array() += g2;
      const T gap = spectrum.natural[0] - spectrum.natural[1];
      // Equal in-plane trial eigenvalues: the ratio's limit is the map's derivative along a - b.
      const T shear_ratio =
          gap > T(1e-12) * std::max(std::abs(spectrum.natural[0]), T(1))
              ? (natural[0] - natural[1]) / gap
              : (natural_map(0, 0) - natural_map(0, 1) - natural_map(1, 0) + natural_map(1, 1)) / 2;
      *tangent = detail::spectral_tangent<T>(natural_map * elastic_principal, elastic_.shear,
                                             shear_ratio, spectrum.cos_2theta, spectrum.sin_2theta);
    }
    return region;
  }

  detail::IsotropicElasticity<T> elastic_;
  T phi_deg_{};
  T psi_deg_{};
  T cohesion_{};
  T sin_phi_{};
  T cos_phi_{};
  T k_{};
  T m_{};
  T offset_{};
  T apex_{};
  T cutoff_{};
  bool has_cutoff_ = false;
  Vec3 normal_;
  Vec3 flow_plane_;
  T plane_denominator_{};
  Vec3 plane_step_;
  T plane_gamma_{};
  Vec3 edge_c_direction_, edge_c_normal_, edge_c_scaled_normal_;
  T edge_c_denominator_{};
  Vec3 edge_e_direction_, edge_e_normal_, edge_e_scaled_normal_;
  T edge_e_denominator_{};
  detail::PlaneSet<T> cutoff_planes_;
};

static_assert(ConstitutiveModel<MohrCoulomb<double>>);
static_assert(HasConsistentTangent<MohrCoulomb<double>>);

}  // namespace cosmpm::material
