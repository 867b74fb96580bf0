#pragma once
// Perfectly plastic Mohr-Coulomb with non-associated flow and a tension cut-off, in plane strain
// with sigma_zz carried (Dim = 2) or in 3D (Dim = 3); component order in stress_space.hpp. The
// return is exact (no iteration, no drift): it is done in principal-stress space
// (detail/mohr_coulomb_return.hpp, after Clausen, Damkilde and Andersen 2006, 2007), the same
// code in both dimensions, and the stress is rotated back with the trial eigenvectors. See
// docs/theory/materials.md.
//
// Tension positive. Principal stresses sorted s1 >= s2 >= s3 (s3 the most compressive):
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi)        (yield_function, Pa)
//   g = m s1 - s3,  m = (1 + sin psi) / (1 - sin psi)
// The split into principal values: sigma_zz is principal in plane strain, so there it is the
// closed-form in-plane 2x2 problem (detail/principal_2d.hpp); in 3D the symmetric 3x3
// eigenproblem (detail/principal_3d.hpp), skipped for trials inside the Drucker-Prager cone
// inscribed in the yield surface.
//
// phi = 0 with psi = 0 and c > 0 is Tresca (undrained clay): f = s1 - s3 - 2 c, no apex, isochoric
// flow; the return's edge regions then keep the mean stress (detail/mohr_coulomb_return.hpp).
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/detail/isotropic_elasticity.hpp"
#include "cosmpm/material/detail/mohr_coulomb_batch.hpp"
#include "cosmpm/material/detail/mohr_coulomb_return.hpp"
#include "cosmpm/material/detail/parameter_checks.hpp"
#include "cosmpm/material/detail/principal_2d.hpp"
#include "cosmpm/material/detail/principal_3d.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace cosmpm::material {

// Parameters by name, e.g. MohrCoulomb({.youngs_modulus = 2.76e6, .poisson_ratio = 0.2,
// .friction_angle_deg = 26, .dilatancy_angle_deg = 2}). Angles in degrees.
struct MohrCoulombParameters {
  double youngs_modulus = detail::unset;       // E (Pa), > 0
  double poisson_ratio = detail::unset;        // nu, -1 < nu < 0.5
  double friction_angle_deg = detail::unset;   // phi, 0 < phi < 90; 0 (Tresca) needs c > 0
  double dilatancy_angle_deg = detail::unset;  // psi, 0 <= psi <= phi
  double cohesion = 0.0;                       // c (Pa), >= 0; > 0 when phi = 0
  // The largest principal stress allowed (Pa), in [0, c cot(phi)]; none: the apex c cot(phi)
  // (none at phi = 0: any cut-off >= 0).
  std::optional<double> tension_cutoff = std::nullopt;
  // Dilatancy cut-off: the plastic shear strain (state.plastic_shear_strain, sqrt(2 e:e) of the
  // plastic strain deviator) from which the flow is isochoric (psi = 0), as a dense granular
  // soil stops dilating at its critical state; in simple shear the volume then grows by about
  // this times tan(psi). > 0; none: psi throughout (perfect plasticity dilates without end).
  std::optional<double> dilatancy_cutoff_strain = std::nullopt;
  // Separation of a cohesionless packing (c = 0): the volumetric strain an apex return takes
  // (p_trial / K) is free volume, the grains apart; the point stays stress-free until
  // compression has closed it (state.separation), as a granular gas carries no stress
  // (Dunatunga and Kamrin 2015). Without it a point that dilated at the apex is stressed again
  // at its first compression, from a volume many times its own.
  bool separation = false;
};

template <class T = double, int Dim = 2>
class MohrCoulomb {
  static constexpr int n = symmetric_components<Dim>;
  // The split of a trial stress into sorted principal values and back.
  using Split = std::conditional_t<Dim == 2, detail::PlaneStrainSplit<T>, detail::Spectral3D<T>>;

 public:
  using scalar_type = T;
  using stress_type = SymmetricTensor<Dim, T>;  // [xx, yy, zz, xy(, xz, yz)], tension positive
  using strain_type = SymmetricTensor<Dim, T>;  // tensor shear
  using state_type = PlasticState;
  using tangent_type = Eigen::Matrix<T, n, n>;
  using parameters_type = MohrCoulombParameters;
  static constexpr bool is_cosserat = false;
  static constexpr int dimension = Dim;

  explicit MohrCoulomb(const MohrCoulombParameters& parameters)
      : parameters_(checked(parameters)),
        elastic_(detail::isotropic_elasticity<T>("MohrCoulomb", T(parameters.youngs_modulus),
                                                 T(parameters.poisson_ratio))) {
    const T phi = T(parameters.friction_angle_deg), psi = T(parameters.dilatancy_angle_deg);
    const T cohesion = T(parameters.cohesion);
    require_non_negative("MohrCoulomb", "cohesion", static_cast<double>(cohesion));
    check_strength(static_cast<double>(phi), static_cast<double>(psi),
                   static_cast<double>(cohesion));
    const T sin_phi = std::sin(T(degrees_to_radians(static_cast<double>(phi))));
    const T sin_psi = std::sin(T(degrees_to_radians(static_cast<double>(psi))));
    sin_phi_ = sin_phi;
    cos_phi_ = std::sqrt(1 - sin_phi * sin_phi);
    const T k = (1 + sin_phi) / (1 - sin_phi);
    const T m = (1 + sin_psi) / (1 - sin_psi);
    // Tresca (phi = 0) has no apex: the return's edges run without end.
    const T apex = phi == T(0) ? std::numeric_limits<T>::infinity() : cohesion * cos_phi_ / sin_phi;
    T cutoff = apex;
    if (parameters.tension_cutoff) {
      require_in_range("MohrCoulomb", "tension_cutoff",
                       static_cast<double>(T(*parameters.tension_cutoff)), 0.0,
                       static_cast<double>(apex), Bounds::closed);
      cutoff = T(*parameters.tension_cutoff);
    }
    return_ =
        detail::MohrCoulombReturn<T>(elastic_, k, m, 2 * cohesion * std::sqrt(k), apex, cutoff);
    if (parameters.separation &&
        !(cohesion == T(0) && return_.has_apex() && !return_.has_cutoff())) {
      throw Error("MohrCoulomb: separation needs a cohesionless packing (cohesion = " +
                  cosmpm::detail::format_number(parameters.cohesion) +
                  ", valid: 0) with its apex at zero stress (tension_cutoff none or 0)");
    }
    separation_ = parameters.separation;
    if (parameters.dilatancy_cutoff_strain) {
      require_positive("MohrCoulomb", "dilatancy_cutoff_strain",
                       *parameters.dilatancy_cutoff_strain);
      dilatancy_cutoff_strain_ = *parameters.dilatancy_cutoff_strain;
      isochoric_return_ = detail::MohrCoulombReturn<T>(elastic_, k, T(1),
                                                       2 * cohesion * std::sqrt(k), apex, cutoff);
    }
  }
  // Positional, for compatibility: prefer the parameters by name (phi and psi cannot swap).
  MohrCoulomb(T youngs_modulus, T poisson_ratio, T friction_angle_deg, T dilatancy_angle_deg,
              T cohesion = T(0), std::optional<T> tension_cutoff = std::nullopt)
      : MohrCoulomb(MohrCoulombParameters{
            static_cast<double>(youngs_modulus), static_cast<double>(poisson_ratio),
            static_cast<double>(friction_angle_deg), static_cast<double>(dilatancy_angle_deg),
            static_cast<double>(cohesion),
            tension_cutoff ? std::optional<double>(static_cast<double>(*tension_cutoff))
                           : std::nullopt}) {}

  const MohrCoulombParameters& parameters() const { return parameters_; }
  T shear_modulus() const { return elastic_.shear; }
  T lame_lambda() const { return elastic_.lambda; }
  T bulk_modulus() const { return elastic_.bulk(); }
  T p_wave_modulus() const { return elastic_.p_wave(); }
  T friction_angle_deg() const { return T(parameters_.friction_angle_deg); }
  T dilatancy_angle_deg() const { return T(parameters_.dilatancy_angle_deg); }
  T cohesion() const { return T(parameters_.cohesion); }
  T apex_stress() const { return return_.apex(); }       // c cot(phi) (+inf at phi = 0)
  T tension_cutoff() const { return return_.cutoff(); }  // largest principal stress allowed
  // The plastic shear strain from which the flow is isochoric; infinity: none.
  double dilatancy_cutoff_strain() const { return dilatancy_cutoff_strain_; }

  // f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) in Pa; <= 0 inside. With a tension
  // cut-off below the apex, the larger of f and s1 - cut-off.
  T yield_function(const stress_type& stress) const {
    std::array<T, n> components;
    for (int c = 0; c < n; ++c) components[c] = stress[c];
    const Split split(components);
    const T f = (split.s1() - split.s3()) + (split.s1() + split.s3()) * sin_phi_ -
                2 * cohesion() * cos_phi_;
    return return_.has_cutoff() ? std::max(f, split.s1() - return_.cutoff()) : f;
  }

  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    if (separation_) [[unlikely]] {
      (void)update_separating<false>(stress, state, de, nullptr);
      return;
    }
    (void)update_impl<false>(stress, state, de, nullptr);
  }
  // With separation, the step that closes the gap has the tangent of its loaded part.
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    if (separation_) [[unlikely]] {
      (void)update_separating<true>(stress, state, de, &tangent);
      return;
    }
    (void)update_impl<true>(stress, state, de, &tangent);
  }
  // The same update, reporting which return region it used (tests, diagnostics).
  MohrCoulombRegion update_region(stress_type& stress, state_type& state,
                                  const strain_type& de) const {
    if (separation_) return update_separating<false>(stress, state, de, nullptr);
    return update_impl<false>(stress, state, de, nullptr);
  }
  bool separates() const { return separation_; }

  // The batched hook (HasBatchUpdate): update(stress[i], state[i], increment[i]) for every i,
  // bit for bit. Where the target's registers hold 4 doubles or more (AVX), plane strain
  // without a cut-off below the apex runs update_lanes with that many lanes; otherwise the
  // points go one by one (SSE2's 2 lanes measured no faster: docs/performance.md).
  void update_batch(std::span<stress_type> stress, std::span<state_type> state,
                    std::span<const strain_type> increment) const {
    constexpr int lanes = static_cast<int>(detail::register_bytes / sizeof(double));
    if constexpr (Dim == 2 && detail::has_lanes && std::is_same_v<T, double> && lanes >= 4) {
      update_lanes<lanes>(stress, state, increment);
    } else {
      require_equal_batch_sizes("MohrCoulomb::update_batch", stress.size(), state.size(),
                                increment.size());
      for (std::size_t i = 0; i < stress.size(); ++i) update(stress[i], state[i], increment[i]);
    }
  }

  // update_batch with L points at a time in SIMD lanes, without a branch
  // (detail/mohr_coulomb_batch.hpp), for any L from 2 to the register width whatever
  // update_batch picks (tests, benchmarks); with a cut-off below the apex, one by one. Bit for
  // bit equal to update(). (Wider lanes than the registers would change the ABI: -Wpsabi.)
  template <int L>
  void update_lanes(std::span<stress_type> stress, std::span<state_type> state,
                    std::span<const strain_type> increment) const
      requires(Dim == 2 && detail::has_lanes && std::is_same_v<T, double> && L >= 2 &&
               L * sizeof(double) <= detail::register_bytes) {
    require_equal_batch_sizes("MohrCoulomb::update_batch", stress.size(), state.size(),
                              increment.size());
    const auto per_point = [this](stress_type& s, state_type& st, const strain_type& de) {
      update(s, st, de);
    };
    const detail::MohrCoulombBatch2D<T> batch{elastic_, return_, isochoric_return_,
                                              dilatancy_cutoff_strain_, separation_};
    if (return_.has_cutoff()) {
      batch.template run<1>(stress.data(), state.data(), increment.data(), stress.size(),
                            per_point);
    } else {
      batch.template run<L>(stress.data(), state.data(), increment.data(), stress.size(),
                            per_point);
    }
  }

  // The hook on packs (HasPacksUpdate): update_batch for points whose stresses and increments
  // come by component in packs of the register width (4 or more doubles, as update_batch's
  // lanes), point l of pack k with state[k W + l]; bit for bit update(). The engine's stage 4b
  // calls it with the packs of its rotation, which saves update_batch's loads and stores lane by
  // lane.
  template <int W>
  void update_packs(std::span<std::array<detail::Lanes<T, W>, n>> stress,
                    std::span<const std::array<detail::Lanes<T, W>, n>> increment,
                    state_type* state) const
      requires(Dim == 2 && detail::has_lanes && std::is_same_v<T, double> && W >= 4 &&
               W * sizeof(double) == detail::register_bytes) {
    require_equal_pack_counts("MohrCoulomb::update_packs", stress.size(), increment.size());
    const detail::MohrCoulombBatch2D<T> batch{elastic_, return_, isochoric_return_,
                                              dilatancy_cutoff_strain_, separation_};
    batch.template run_packs<W>(
        stress.data(), increment.data(), stress.size(), state, return_.has_cutoff(),
        [this](stress_type& s, state_type& st, const strain_type& de) { update(s, st, de); });
  }

  tangent_type elastic_tangent() const { return elastic_.template tangent<n>(); }

  // The principal-space return on its own: `trial` sorted descending, result sorted likewise.
  // `map` (optional) receives d result / d trial. Exposed for tests.
  MohrCoulombRegion principal_return(const Eigen::Matrix<T, 3, 1>& trial,
                                     Eigen::Matrix<T, 3, 1>& result,
                                     Eigen::Matrix<T, 3, 3>* map = nullptr) const {
    const T f = return_.yield(trial[0], trial[2]);
    if (return_.is_elastic(trial[0], f)) {
      result = trial;
      if (map) map->setIdentity();
      return MohrCoulombRegion::elastic;
    }
    if (return_.has_cutoff())
      return map ? sorted_return<true, true>(trial, f, result, map)
                 : sorted_return<false, true>(trial, f, result, nullptr);
    return map ? sorted_return<true, false>(trial, f, result, map)
               : sorted_return<false, false>(trial, f, result, nullptr);
  }

 private:
  using Mat3 = Eigen::Matrix<T, 3, 3>;

  template <bool WithMap, bool Cutoff>
  MohrCoulombRegion sorted_return(const Eigen::Matrix<T, 3, 1>& trial, T f,
                                  Eigen::Matrix<T, 3, 1>& result, Mat3* map) const {
    T gamma;
    return return_.template plastic_return<WithMap, Cutoff>(
        trial[0], trial[1], trial[2], f, result[0], result[1], result[2], gamma, map);
  }

  // 0 < phi < 90 and 0 <= psi <= phi as for every frictional model, or the Tresca limit phi = 0
  // (then psi = 0) with c > 0: without friction or cohesion there is no strength.
  static void check_strength(double phi, double psi, double cohesion) {
    if (!(phi >= 0.0 && phi < 90.0)) {
      throw Error("MohrCoulomb: friction_angle_deg = " + cosmpm::detail::format_number(phi) +
                  " is outside the valid range [0, 90) (0 only with cohesion > 0: Tresca)");
    }
    if (phi == 0.0 && !(cohesion > 0.0)) {
      throw Error("MohrCoulomb: friction_angle_deg = 0 with cohesion = " +
                  cosmpm::detail::format_number(cohesion) +
                  " has no strength: at friction_angle_deg = 0 (Tresca) cohesion must be in "
                  "(0, inf); without cohesion friction_angle_deg must be in (0, 90)");
    }
    require_in_range("MohrCoulomb", "dilatancy_angle_deg", psi, 0.0, phi, Bounds::closed);
  }

  static const MohrCoulombParameters& checked(const MohrCoulombParameters& p) {
    detail::require_set("MohrCoulomb", "MohrCoulombParameters",
                        {{"youngs_modulus", p.youngs_modulus},
                         {"poisson_ratio", p.poisson_ratio},
                         {"friction_angle_deg", p.friction_angle_deg},
                         {"dilatancy_angle_deg", p.dilatancy_angle_deg}});
    return p;
  }

  // The one stress update: trial, split into principal values, principal return, rotation
  // back, and (WithTangent) the consistent tangent. With a cut-off below the apex the same code
  // runs out of line (Cutoff = true), so that the common case holds no call.
  template <bool WithTangent, bool Cutoff = false>
  MohrCoulombRegion update_impl(stress_type& stress, state_type& state, const strain_type& de,
                                tangent_type* tangent) const {
    const auto t = elastic_.template trial<n>(stress, de);
    const auto elastic_step = [&] {
      for (int c = 0; c < n; ++c) stress[c] = t[c];
      state.plastic = 0.0;
      if constexpr (WithTangent) *tangent = elastic_tangent();
      return MohrCoulombRegion::elastic;
    };
    if constexpr (Dim == 3) {
      // Most points of a 3D run lie well inside: no eigenproblem for them.
      const T p = (t[0] + t[1] + t[2]) / 3;
      const T j2 =
          ((t[0] - p) * (t[0] - p) + (t[1] - p) * (t[1] - p) + (t[2] - p) * (t[2] - p)) / 2 +
          t[3] * t[3] + t[4] * t[4] + t[5] * t[5];
      if (return_.inside_inscribed_cone(p, j2)) return elastic_step();
    }
    const Split split(t);
    const T f = return_.yield(split.s1(), split.s3());
    if (return_.is_elastic(split.s1(), f)) return elastic_step();
    if constexpr (!Cutoff) {
      if (return_.has_cutoff()) [[unlikely]]
        return update_with_cutoff<WithTangent>(stress, state, de, tangent);
    }
    T r1, r2, r3, gamma;
    Mat3 sorted_map;
    // The same yield surface either way; only the flow changes at the dilatancy cut-off.
    const auto& flow =
        state.plastic_shear_strain >= dilatancy_cutoff_strain_ ? isochoric_return_ : return_;
    const MohrCoulombRegion region = flow.template plastic_return<WithTangent, Cutoff>(
        split.s1(), split.s2(), split.s3(), f, r1, r2, r3, gamma,
        WithTangent ? &sorted_map : nullptr);
    stress = split.back(r1, r2, r3);
    state.plastic_shear_strain += static_cast<double>(gamma);
    state.plastic = 1.0;
    if constexpr (WithTangent) *tangent = split.tangent(sorted_map, elastic_, r1, r2, r3);
    return region;
  }

  // sqrt(2 e:e) of the deviator e of a strain increment (tensor shear): the measure of
  // state.plastic_shear_strain.
  static T deviatoric_norm(const strain_type& de) {
    const T mean = (de[0] + de[1] + de[2]) / 3;
    T ee = 0;
    for (int c = 0; c < 3; ++c) ee += (de[c] - mean) * (de[c] - mean);
    for (int c = 3; c < n; ++c) ee += 2 * de[c] * de[c];
    return std::sqrt(2 * ee);
  }

  // update_impl with separation: while the grains are apart the increment only opens or
  // closes the gap (all of it plastic); the part of an increment left once the gap has closed
  // loads the packing from zero stress; an apex return adds its plastic volumetric strain,
  // p_trial / K, to the gap.
  template <bool WithTangent>
  [[gnu::noinline]] MohrCoulombRegion update_separating(stress_type& stress, state_type& state,
                                                        const strain_type& de,
                                                        tangent_type* tangent) const {
    const T volumetric = de[0] + de[1] + de[2];
    strain_type loading = de;
    if (state.separation > 0.0) {
      const T gap = T(state.separation);
      if (volumetric >= -gap) {
        state.separation = static_cast<double>(gap + volumetric);
        state.plastic_shear_strain += static_cast<double>(deviatoric_norm(de));
        state.plastic = 1.0;
        stress.setZero();
        if constexpr (WithTangent) tangent->setZero();
        return MohrCoulombRegion::separated;
      }
      const T closing = -gap / volumetric;  // the part of the increment that closes the gap
      state.plastic_shear_strain += static_cast<double>(closing * deviatoric_norm(de));
      state.separation = 0.0;
      stress.setZero();
      loading = (1 - closing) * de;
    }
    const T bulk = elastic_.bulk();
    const T trial_mean =
        (stress[0] + stress[1] + stress[2]) / 3 + bulk * (loading[0] + loading[1] + loading[2]);
    const MohrCoulombRegion region = update_impl<WithTangent>(stress, state, loading, tangent);
    if (region == MohrCoulombRegion::apex && trial_mean > 0)
      state.separation += static_cast<double>(trial_mean / bulk);
    return region;
  }

  template <bool WithTangent>
  [[gnu::noinline]] MohrCoulombRegion update_with_cutoff(stress_type& stress, state_type& state,
                                                         const strain_type& de,
                                                         tangent_type* tangent) const {
    return update_impl<WithTangent, true>(stress, state, de, tangent);
  }

  MohrCoulombParameters parameters_;
  detail::IsotropicElasticity<T> elastic_;
  T sin_phi_{};
  T cos_phi_{};
  detail::MohrCoulombReturn<T> return_;
  double dilatancy_cutoff_strain_ = std::numeric_limits<double>::infinity();
  bool separation_ = false;
  detail::MohrCoulombReturn<T> isochoric_return_;  // psi = 0, past the dilatancy cut-off
};

static_assert(ConstitutiveModel<MohrCoulomb<double>>);
static_assert(HasConsistentTangent<MohrCoulomb<double>>);
static_assert(HasConsistentTangent<MohrCoulomb<double, 3>>);

}  // namespace cosmpm::material
