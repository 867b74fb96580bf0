#pragma once
// The classical (nonpolar) continuum, in 2D plane strain or in 3D (the model's dimension,
// material::dimension_of): which fields a particle carries, how its stress is updated from the
// velocity gradient of a step, and how it loads the grid. It
// has no degrees of freedom besides the translations, so every rotational term of the
// continuum contract (continuum/concept.hpp) is empty. AntiLocking (continuum/
// antilocking.hpp) chooses how the volumetric strain rate is formed:
//   continuum::Classical<material::MohrCoulomb<>, antilocking::FBar>
//   continuum::Classical<material::LinearElastic<double, 3>>            (3D)
// Stress and strain are in the component order of material/stress_space.hpp.
#include <array>
#include <limits>
#include <span>

#include "cosmpm/continuum/antilocking.hpp"
#include "cosmpm/continuum/objective_update.hpp"
#include "cosmpm/continuum/particle_fields.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/stress_space.hpp"

namespace cosmpm::continuum {

template <material::ConstitutiveModel Model, class AntiLocking = antilocking::None>
requires(!Model::is_cosserat) class Classical {
  static constexpr int n = material::symmetric_components<material::dimension_of<Model>>;

 public:
  using model_type = Model;
  using antilocking_type = AntiLocking;
  using stress_type = typename Model::stress_type;
  using strain_type = typename Model::strain_type;
  using state_type = typename Model::state_type;
  static constexpr bool is_cosserat = false;
  static constexpr int dim = material::dimension_of<Model>;
  static constexpr int rotational_dofs = 0;
  static constexpr const char* name() { return "classical"; }

  template <int Dim>
  using particle_store = particle_store_with<Dim, Model>;
  template <int Dim>
  using rates_type = ParticleRates<Dim, rotational_dofs>;

  // A model is all a classical continuum needs, so a model converts to one (Simulation's
  // constructor takes either).
  Classical(const Model& model) : model_(model) {}  // NOLINT(google-explicit-constructor)
  const Model& model() const { return model_; }

  // --- the stress update: one formula for one particle, for packs and for batches ---------

  // Objective (Jaumann) update for a step with velocity gradient L: rotate the old stress by
  // the spin, then let the model integrate the strain increment.
  static void update_stress(const Model& model, const rates_type<dim>& rates, double dt,
                            stress_type& stress, state_type& state, strain_type& strain) {
    objective_update<Classical>(model, rates, dt, stress, state, strain);
  }

  // update_stress in parts, for callers that hand the model many points in one call
  // (material::update_batch): the rotation, returning the increment, and the accumulation.
  static strain_type rotate_and_increment(const rates_type<dim>& rates, double dt,
                                          stress_type& stress) {
    const auto values = rotate_and_increment_values(rates.velocity_gradient, dt, stress);
    strain_type increment;
    for (int c = 0; c < n; ++c) increment[c] = values[c];
    return increment;
  }

  // Plane strain: the zz increment is zero, so the zz strain stays as it is; in 3D every
  // component accumulates. Strain and increment are indexable by the stress components.
  template <class Strain, class Increment>
  COSMPM_ALWAYS_INLINE static void accumulate_strain(Strain& strain, const Increment& increment) {
    if constexpr (dim == 2) {
      strain[0] += increment[0];
      strain[1] += increment[1];
      strain[3] += increment[3];
    } else {
      for (int c = 0; c < n; ++c) strain[c] += increment[c];
    }
  }

  // Whether the model updates several points at once on packs of their components (the
  // material concept's packed hook; LinearElastic has it): the engine's grid-to-particle loop
  // then runs the whole stress update side by side for W particles.
  template <class Value>
  static constexpr bool updates_values = material::HasPackedUpdate<Model, Value>;

  // update_stress for W particles at once: lane l of every value belongs to particle l, L the
  // velocity gradient, `strain` the accumulated strain (plane strain: component 2, zz, is not
  // touched).
  template <class Value>
  requires updates_values<Value> COSMPM_ALWAYS_INLINE static void update_stress_values(
      const Model& model, const std::array<std::array<Value, dim>, dim>& L, double dt,
      std::array<Value, n>& stress, std::array<Value, n>& strain) {
    const std::array<Value, n> increment = rotate_and_increment_values(L, dt, stress);
    model.update_values(stress, increment);
    accumulate_strain(strain, increment);
  }

  // The rotation of the stress by the step's spin (in place) and the strain increment, on an
  // Eigen matrix L and vector stress or on arrays of packs: the one place both are written.
  // The increment is the symmetric part of L dt, tensor shear (stress_space.hpp).
  template <class Gradient, class Stress>
  COSMPM_ALWAYS_INLINE static auto rotate_and_increment_values(const Gradient& L, double dt,
                                                               Stress& stress) {
    using Value = std::remove_cvref_t<decltype(entry(L, 0, 0))>;
    if constexpr (dim == 2) {
      rotate_by_spin(0.5 * (entry(L, 0, 1) - entry(L, 1, 0)) * dt, stress);
      return std::array<Value, 4>{entry(L, 0, 0) * dt, entry(L, 1, 1) * dt, Value{},
                                  0.5 * (entry(L, 0, 1) + entry(L, 1, 0)) * dt};
    } else {
      rotate_by_spin_3d(L, dt, stress);
      return std::array<Value, 6>{entry(L, 0, 0) * dt,
                                  entry(L, 1, 1) * dt,
                                  entry(L, 2, 2) * dt,
                                  0.5 * (entry(L, 0, 1) + entry(L, 1, 0)) * dt,
                                  0.5 * (entry(L, 0, 2) + entry(L, 2, 0)) * dt,
                                  0.5 * (entry(L, 1, 2) + entry(L, 2, 1)) * dt};
    }
  }

  // The Jaumann rotation of the stress by the spin angle of a step, in place.
  template <class Value, class Stress>
  COSMPM_ALWAYS_INLINE static void rotate_by_spin(const Value& spin, Stress& stress) {
    const Value sxx = stress[0];
    const Value syy = stress[1];
    const Value sxy = stress[3];
    stress[0] = sxx + 2.0 * spin * sxy;
    stress[1] = syy - 2.0 * spin * sxy;
    stress[3] = sxy + spin * (syy - sxx);
  }

  // The same in 3D: sigma <- sigma + W sigma - sigma W with the step's spin W = (L - L^T) dt / 2,
  // i.e. d sigma_ij = sum_k (W_ik sigma_kj + W_jk sigma_ki), all from the old stress. For L in
  // the xy plane it is rotate_by_spin (with spin = W_xy).
  template <class Gradient, class Stress>
  COSMPM_ALWAYS_INLINE static void rotate_by_spin_3d(const Gradient& L, double dt, Stress& stress) {
    using Value = std::remove_cvref_t<decltype(entry(L, 0, 0))>;
    const Value wxy = 0.5 * (entry(L, 0, 1) - entry(L, 1, 0)) * dt;
    const Value wxz = 0.5 * (entry(L, 0, 2) - entry(L, 2, 0)) * dt;
    const Value wyz = 0.5 * (entry(L, 1, 2) - entry(L, 2, 1)) * dt;
    const Value sxx = stress[0];
    const Value syy = stress[1];
    const Value szz = stress[2];
    const Value sxy = stress[3];
    const Value sxz = stress[4];
    const Value syz = stress[5];
    // W = [[0, wxy, wxz], [-wxy, 0, wyz], [-wxz, -wyz, 0]].
    stress[0] = sxx + 2.0 * (wxy * sxy + wxz * sxz);
    stress[1] = syy + 2.0 * (wyz * syz - wxy * sxy);
    stress[2] = szz - 2.0 * (wxz * sxz + wyz * syz);
    stress[3] = sxy + wxy * (syy - sxx) + wxz * syz + wyz * sxz;
    stress[4] = sxz + wxz * (szz - sxx) + wxy * syz - wyz * sxy;
    stress[5] = syz + wyz * (szz - syy) - wxy * sxz - wxz * sxy;
  }

  // --- how a particle loads the grid ----------------------------------------------------

  // A particle's nodal internal force -V sigma . grad N, written as sum_i dN/dx_i b[j][i] for
  // force component j (the transfers contract it one axis at a time). Value: a double, or a
  // pack of particles' volumes with their stresses' components as packs (the scatter of packs).
  template <class Stress, class Value>
  static std::array<std::array<Value, dim>, dim> internal_force_coefficients(const Stress& stress,
                                                                             const Value& volume) {
    if constexpr (dim == 2) {
      const Value sxy = -volume * stress[3];
      return {{{-volume * stress[0], sxy}, {sxy, -volume * stress[1]}}};
    } else {
      const Value sxy = -volume * stress[3];
      const Value sxz = -volume * stress[4];
      const Value syz = -volume * stress[5];
      return {{{-volume * stress[0], sxy, sxz},
               {sxy, -volume * stress[1], syz},
               {sxz, syz, -volume * stress[2]}}};
    }
  }

  // --- rotational degrees of freedom: none ----------------------------------------------
  template <class Store, class V>
  static std::array<V, 0> rotational_inertia(const Store&, Index, const V&) {
    return {};
  }
  template <int W = 1, class Store>
  static std::array<Pack<W>, 0> rotational_velocity(const Store&, Index) {
    return {};
  }
  template <class Stress, class Value>
  static void rotational_force_terms(const Stress&, const Value&, Value*, std::array<Value, dim>*) {
  }
  template <class Store>
  static void update_rotations(Store&, Index, double, double, const std::array<double, 0>&,
                               const std::array<double, 0>&) {}
  template <class Store>
  void initialise_particles(Store&, Index, Index) const {}
  void apply_rotation_conditions(const grid::Grid<dim>&, std::span<double>) const {}
  // No bound of its own: the engine's p-wave bound holds.
  double stable_time_step(const grid::Grid<dim>&, double) const {
    return std::numeric_limits<double>::infinity();
  }

 private:
  static double entry(const Mat<dim>& L, int i, int j) { return L(i, j); }
  template <class Value>
  static const Value& entry(const std::array<std::array<Value, dim>, dim>& L, int i, int j) {
    return L[i][j];
  }

  Model model_;
};

}  // namespace cosmpm::continuum
