#pragma once
// The Mohr-Coulomb return in principal-stress space, after Clausen, Damkilde and Andersen (2006,
// 2007): perfect plasticity, non-associated flow, exact (the yield surface is a set of planes).
// It knows nothing of the stress's components or of the dimension: the plane-strain and the 3D
// MohrCoulomb both split their trial stress into sorted principal values, call this, and rotate
// the result back with the trial's principal directions (isotropy keeps them).
//
// Tension positive. Principal stresses sorted s1 >= s2 >= s3 (s3 the most compressive):
//   f = k s1 - s3 - 2 c sqrt(k),  k = (1 + sin phi) / (1 - sin phi)
//   g = m s1 - s3,                m = (1 + sin psi) / (1 - sin psi)
// Regions: the yield plane; the compression edge s1 = s2 (line apex + t (1, 1, k)); the extension
// edge s2 = s3 (line apex + t (1, k, k)); the apex c cot(phi), the default tension cut-off; and,
// with a cut-off below the apex, the tension regions (associated flow on s_i <= cut-off), solved
// by the general active-set return (multisurface_return.hpp).
//
// phi = 0 (Tresca, k = m = 1, c > 0): the edges are parallel to the hydrostatic axis and there
// is no apex (apex = +inf). Each edge line is then anchored at a finite point of it, (c, c, -c)
// and (c, -c, -c), instead of the apex, and the edge return has no end (t unbounded): it keeps
// the trial's mean stress. The plane region is unchanged. With phi > 0 the anchor is the apex
// and t <= 0, the same arithmetic as without the generalisation.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/lanes.hpp"
#include "cosmpm/material/detail/multisurface_return.hpp"

namespace cosmpm::material {

// Where a return mapping ended; `tension` is any return that involves the cut-off planes below
// the apex; `separated`: the grains are apart (MohrCoulombParameters::separation), no stress.
enum class MohrCoulombRegion {
  elastic,
  plane,
  compression_edge,
  extension_edge,
  apex,
  tension,
  separated
};

}  // namespace cosmpm::material

namespace cosmpm::material::detail {

template <class T>
class MohrCoulombReturn {
 public:
  using Vec3 = Eigen::Matrix<T, 3, 1>;
  using Mat3 = Eigen::Matrix<T, 3, 3>;

  MohrCoulombReturn() = default;
  // k, m as above, the apex stress c cot(phi) (+inf for phi = 0: no apex) and the cut-off (the
  // largest principal stress allowed, at most the apex).
  MohrCoulombReturn(const IsotropicElasticity<T>& elastic, T k, T m, T offset, T apex, T cutoff)
      : elastic_(elastic),
        two_shear_(2 * elastic.shear),
        k_(k),
        offset_(offset),
        apex_(apex),
        cutoff_(cutoff),
        has_cutoff_(cutoff < apex),
        has_apex_(std::isfinite(apex)) {
    // Yield plane f = a . s - offset, flow D b.
    normal_ = Vec3(k, 0, -1);
    const Vec3 b_plane(m, 0, -1);
    const Vec3 flow_plane = elastic_times(b_plane);
    plane_step_ = flow_plane / normal_.dot(flow_plane);
    // Plane region: the stress removed is f * plane_step_, so the plastic shear strain
    // sqrt(2 e:e) of its deviator / 2G is f times a constant.
    const Vec3 step_deviator = plane_step_ - Vec3::Constant(plane_step_.mean());
    plane_gamma_ = std::sqrt(2 * step_deviator.squaredNorm()) / (2 * elastic.shear);
    // Compression edge s1 = s2: planes k s1 - s3 and k s2 - s3 both active. The return lies on
    // the line apex + t (1, 1, k) and moves in the span of their flows, so t follows from the
    // normal of that span.
    const Vec3 b_second(0, m, -1);
    edge_c_direction_ = Vec3(1, 1, k);
    const Vec3 edge_c_normal = flow_plane.cross(elastic_times(b_second));
    edge_c_scaled_normal_ = edge_c_normal / edge_c_normal.dot(edge_c_direction_);
    // Extension edge s2 = s3: planes k s1 - s3 and k s1 - s2, line apex + t (1, k, k).
    const Vec3 b_third(m, -1, 0);
    edge_e_direction_ = Vec3(1, k, k);
    const Vec3 edge_e_normal = flow_plane.cross(elastic_times(b_third));
    edge_e_scaled_normal_ = edge_e_normal / edge_e_normal.dot(edge_e_direction_);
    // Where t = 0 on each edge line: the apex, or without one (k = 1) a point of the line.
    if (has_apex_) {
      edge_c_anchor_ = edge_e_anchor_ = Vec3::Constant(apex);
      edge_end_ = T(0);
    } else {
      const T c = offset / 2;  // offset = 2 c sqrt(k), k = 1
      edge_c_anchor_ = Vec3(c, c, -c);
      edge_e_anchor_ = Vec3(c, -c, -c);
      edge_end_ = std::numeric_limits<T>::infinity();
    }
    // The general solver for a cut-off below the apex: the three Mohr-Coulomb planes that can be
    // active for sorted stresses and the three associated cut-off planes.
    cutoff_planes_.add(normal_, offset, flow_plane);
    cutoff_planes_.add(Vec3(0, k, -1), offset, elastic_times(b_second));
    cutoff_planes_.add(Vec3(k, -1, 0), offset, elastic_times(b_third));
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = Vec3::Unit(i);
      cutoff_planes_.add(e, cutoff, elastic_times(e));
    }
    // With the Lode angle t, s1 = p + 2 sqrt(J2 / 3) cos t and s3 = p + 2 sqrt(J2 / 3)
    // cos(t + 2 pi / 3), so k s1 - s3 <= (k - 1) p + 2 sqrt((k^2 + k + 1) / 3) sqrt(J2) for every
    // t: the Drucker-Prager cone inscribed in the yield surface (it touches the yield plane
    // where tan t = sqrt3 / (2 k + 1)).
    inscribed_slope_ = 2 * std::sqrt((k * k + k + 1) / 3);
  }

  T apex() const { return apex_; }  // +inf without an apex (phi = 0)
  T cutoff() const { return cutoff_; }
  bool has_cutoff() const { return has_cutoff_; }  // below the apex
  bool has_apex() const { return has_apex_; }

  // k s1 - s3 - 2 c sqrt(k) of sorted principal stresses.
  // On a T or on lanes of T (lanes.hpp), with the same operations.
  template <class V>
  V yield(const V& s1, const V& s3) const {
    return k_ * s1 - s3 - offset_;
  }
  // Whether a trial of mean stress p and second deviatoric invariant J2 lies inside the cone
  // inscribed in the yield surface (and below the cut-off): elastic for sure, without its
  // principal values.
  bool inside_inscribed_cone(T p, T j2) const {
    return (k_ - 1) * p + inscribed_slope_ * std::sqrt(j2) - offset_ <= T(0) &&
           (!has_cutoff_ || p + 2 * std::sqrt(j2 / 3) <= cutoff_);
  }
  // Whether the sorted trial with f = yield(s1, s3) is elastic.
  bool is_elastic(T s1, T f) const { return f <= T(0) && (!has_cutoff_ || s1 <= cutoff_); }

  // The return of cone() (no cut-off below the apex) on lanes of plastic trials, without a
  // branch: every lane computes the plane and the edge returns and keeps the one cone() would
  // have taken, each with cone()'s operations in cone()'s order, so a lane equals cone() bit for
  // bit. Lanes where `use_isochoric` is set take `isochoric`'s flow (the same yield surface,
  // psi = 0), as MohrCoulomb picks its flow past the dilatancy cut-off. `at_apex`: the lanes
  // that ended at the apex. The lanes set in `unused` (elastic, say) may come out anything:
  // when every other lane stays on the yield plane, the edge returns are skipped.
  template <class V, class Mask>
  void cone_lanes(const V& s1, const V& s2, const V& s3, const V& f,
                  const MohrCoulombReturn& isochoric, const Mask& use_isochoric, const Mask& unused,
                  V& r1, V& r2, V& r3, V& gamma, Mask& at_apex) const {
    const auto pick = [&](T own, T other) {
      return use_isochoric ? splat<V>(other) : splat<V>(own);
    };
    const V p1 = s1 - pick(plane_step_[0], isochoric.plane_step_[0]) * f;
    const V p2 = s2 - pick(plane_step_[1], isochoric.plane_step_[1]) * f;
    const V p3 = s3 - pick(plane_step_[2], isochoric.plane_step_[2]) * f;
    const Mask in_plane = p1 >= p2 && p2 >= p3;
    // Where every lane used stays on the yield plane (the engine's points come in space order,
    // neighbours return alike), one branch spares the pack the edges' square root and divisions.
    if (cosmpm::all_lanes<lane_count<V>()>(in_plane || unused)) {
      r1 = p1;
      r2 = p2;
      r3 = p3;
      gamma = pick(plane_gamma_, isochoric.plane_gamma_) * f;
      at_apex = Mask{};  // no lane at the apex
      return;
    }
    const Mask compression_side = p1 < p2;
    const auto side = [&](const Vec3& compression, const Vec3& extension, int i) {
      return compression_side ? splat<V>(compression[i]) : splat<V>(extension[i]);
    };
    const auto normal = [&](int i) {
      return use_isochoric
                 ? side(isochoric.edge_c_scaled_normal_, isochoric.edge_e_scaled_normal_, i)
                 : side(edge_c_scaled_normal_, edge_e_scaled_normal_, i);
    };
    const V a1 = side(edge_c_anchor_, edge_e_anchor_, 0);
    const V a2 = side(edge_c_anchor_, edge_e_anchor_, 1);
    const V a3 = side(edge_c_anchor_, edge_e_anchor_, 2);
    const V along = normal(0) * (s1 - a1) + normal(1) * (s2 - a2) + normal(2) * (s3 - a3);
    const V end = splat<V>(edge_end_);
    const V t = along < end ? along : end;  // std::min(edge_end_, along)
    const V e1 = a1 + t * side(edge_c_direction_, edge_e_direction_, 0);
    const V e2 = a2 + t * side(edge_c_direction_, edge_e_direction_, 1);
    const V e3 = a3 + t * side(edge_c_direction_, edge_e_direction_, 2);
    const V edge_gamma = deviator_gamma<V>(s1 - e1, s2 - e2, s3 - e3);
    r1 = in_plane ? p1 : e1;
    r2 = in_plane ? p2 : e2;
    r3 = in_plane ? p3 : e3;
    gamma = in_plane ? pick(plane_gamma_, isochoric.plane_gamma_) * f : edge_gamma;
    at_apex = !in_plane && !(along <= end);
  }

  // The return of a plastic trial s1 >= s2 >= s3 with f = yield(s1, s3): the returned principal
  // stresses r1 >= r2 >= r3, the equivalent plastic shear strain sqrt(2 e:e) of the plastic
  // strain's deviator, and (WithMap) d r / d s in the sorted order. `Cutoff` must be
  // has_cutoff(): a compile-time choice, so that the callers' hot path (no cut-off below the
  // apex) holds no call across which its values would have to be spilled.
  template <bool WithMap, bool Cutoff>
  MohrCoulombRegion plastic_return(T s1, T s2, T s3, T f, T& r1, T& r2, T& r3, T& gamma,
                                   Mat3* map) const {
    if constexpr (Cutoff) {
      return with_cutoff<WithMap>(s1, s2, s3, f, r1, r2, r3, gamma, map);
    } else {
      return cone<WithMap>(s1, s2, s3, f, r1, r2, r3, gamma, map);
    }
  }

 private:
  Vec3 elastic_times(const Vec3& v) const {
    return Vec3::Constant(elastic_.lambda * v.sum()) + 2 * elastic_.shear * v;
  }

  // The regions of the cone with the cut-off at the apex: the yield plane first; if its result
  // leaves the sorted sector, the edge line on that side, or the apex beyond it (t > edge_end_,
  // never without an apex).
  template <bool WithMap>
  MohrCoulombRegion cone(T s1, T s2, T s3, T f, T& r1, T& r2, T& r3, T& gamma, Mat3* map) const {
    r1 = s1 - plane_step_[0] * f;
    r2 = s2 - plane_step_[1] * f;
    r3 = s3 - plane_step_[2] * f;
    if (r1 >= r2 && r2 >= r3) {
      gamma = plane_gamma_ * f;
      if constexpr (WithMap) *map = Mat3::Identity() - plane_step_ * normal_.transpose();
      return MohrCoulombRegion::plane;
    }
    const bool compression_side = r1 < r2;
    const Vec3& normal = compression_side ? edge_c_scaled_normal_ : edge_e_scaled_normal_;
    const Vec3& direction = compression_side ? edge_c_direction_ : edge_e_direction_;
    const Vec3& anchor = compression_side ? edge_c_anchor_ : edge_e_anchor_;
    const T along =
        normal[0] * (s1 - anchor[0]) + normal[1] * (s2 - anchor[1]) + normal[2] * (s3 - anchor[2]);
    const T t = std::min(edge_end_, along);
    r1 = anchor[0] + t * direction[0];
    r2 = anchor[1] + t * direction[1];
    r3 = anchor[2] + t * direction[2];
    gamma = deviator_gamma(s1 - r1, s2 - r2, s3 - r3);
    const bool on_edge = along <= edge_end_;
    if constexpr (WithMap) {
      if (on_edge) {
        *map = direction * normal.transpose();
      } else {
        map->setZero();
      }
    }
    if (!on_edge) return MohrCoulombRegion::apex;
    return compression_side ? MohrCoulombRegion::compression_edge
                            : MohrCoulombRegion::extension_edge;
  }

  // With a cut-off below the apex: the cone unless its result (or the trial, when f <= 0)
  // breaks the cut-off, then the active-set return over all six planes.
  template <bool WithMap>
  MohrCoulombRegion with_cutoff(T s1, T s2, T s3, T f, T& r1, T& r2, T& r3, T& gamma,
                                Mat3* map) const {
    if (f > T(0)) {
      const MohrCoulombRegion region = cone<WithMap>(s1, s2, s3, f, r1, r2, r3, gamma, map);
      if (r1 <= cutoff_) return region;
    }
    const Vec3 trial(s1, s2, s3);
    const T scale = has_apex_ ? apex_ : std::max(cutoff_, offset_);
    const T tolerance = T(1e-12) * std::max({trial.cwiseAbs().maxCoeff(), scale, T(1)});
    Vec3 result;
    if (!multisurface_return(cutoff_planes_, trial, tolerance, result, WithMap ? map : nullptr)) {
      // Unreachable for valid parameters: the cut-off octant always admits a return.
      result = Vec3::Constant(cutoff_);
      if constexpr (WithMap) map->setZero();
    }
    r1 = result[0];
    r2 = result[1];
    r3 = result[2];
    gamma = deviator_gamma(s1 - r1, s2 - r2, s3 - r3);
    return MohrCoulombRegion::tension;
  }

  // sqrt(2 e:e) of the plastic strain's deviator for the removed stress d: the deviator of d
  // over 2G (the removed stress is D times the plastic strain, and D scales deviators by 2G).
  // On a T or on lanes of T.
  template <class V>
  V deviator_gamma(const V& d1, const V& d2, const V& d3) const {
    const V removed_mean = (d1 + d2 + d3) / 3;
    V norm =
        2 * ((d1 - removed_mean) * (d1 - removed_mean) + (d2 - removed_mean) * (d2 - removed_mean) +
             (d3 - removed_mean) * (d3 - removed_mean));
    sqrt_in_place(norm);
    return norm / two_shear_;
  }

  IsotropicElasticity<T> elastic_{};
  T two_shear_{};
  T k_{};
  T offset_{};
  T apex_{};
  T cutoff_{};
  bool has_cutoff_ = false;
  bool has_apex_ = true;
  Vec3 normal_ = Vec3::Zero();
  Vec3 plane_step_ = Vec3::Zero();
  T plane_gamma_{};
  T inscribed_slope_{};
  Vec3 edge_c_direction_ = Vec3::Zero(), edge_c_scaled_normal_ = Vec3::Zero();
  Vec3 edge_e_direction_ = Vec3::Zero(), edge_e_scaled_normal_ = Vec3::Zero();
  Vec3 edge_c_anchor_ = Vec3::Zero(), edge_e_anchor_ = Vec3::Zero();
  T edge_end_{};  // t at the apex along both edges (0), +inf without an apex
  PlaneSet<T> cutoff_planes_;
};

}  // namespace cosmpm::material::detail
