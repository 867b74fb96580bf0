#pragma once
// The classical (nonpolar) continuum: which fields a particle carries and how its stress is
// updated from the velocity gradient of a step.
#include <array>
#include <tuple>

#include "cosmpm/continuum/particle_fields.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"

namespace cosmpm::continuum {

template <material::ConstitutiveModel Model>
requires(!Model::is_cosserat) struct Classical {
  using model_type = Model;
  static constexpr bool is_cosserat = false;

  template <int Dim>
  using particle_store = particle_store_with<Dim, Model>;

  template <int Dim>
  using rates_type = ParticleRates<Dim, false>;

  // Objective (Jaumann) stress update for a 2D plane-strain step with velocity gradient L:
  // rotate the old stress by the spin, then let the model integrate the strain increment.
  // Component by component: the engine runs this per particle inside its paired loop, where
  // (measured) whole-vector temporaries cost more than scalar updates in place.
  static void update_stress(const Model& model, const rates_type<2>& rates, double dt,
                            typename Model::stress_type& stress, typename Model::state_type& state,
                            typename Model::strain_type& accumulated_strain) {
    const typename Model::strain_type increment = rotate_and_increment(rates, dt, stress);
    model.update(stress, state, increment);
    accumulate_strain(accumulated_strain, increment);
  }

  // update_stress in parts, for callers that hand the model many points in one call
  // (material::update_batch): the rotation of the stress by the spin, returning the strain
  // increment the model then integrates, and the strain's accumulation.
  static typename Model::strain_type rotate_and_increment(const rates_type<2>& rates, double dt,
                                                          typename Model::stress_type& stress) {
    const Mat<2>& velocity_gradient = rates.velocity_gradient;
    rotate_by_spin(0.5 * (velocity_gradient(0, 1) - velocity_gradient(1, 0)) * dt, stress);
    typename Model::strain_type increment;
    increment[0] = velocity_gradient(0, 0) * dt;
    increment[1] = velocity_gradient(1, 1) * dt;
    increment[2] = 0.0;
    increment[3] = 0.5 * (velocity_gradient(0, 1) + velocity_gradient(1, 0)) * dt;
    return increment;
  }
  static void accumulate_strain(typename Model::strain_type& accumulated_strain,
                                const typename Model::strain_type& increment) {
    // Plane strain: the zz increment is zero, so the zz strain stays as it is.
    accumulated_strain[0] += increment[0];
    accumulated_strain[1] += increment[1];
    accumulated_strain[3] += increment[3];
  }

  // Whether the model updates several points at once on packs of their components
  // (update_values, for models without state such as LinearElastic): the engine's
  // grid-to-particle loop then runs the whole stress update side by side for W particles.
  template <class Value>
  static constexpr bool updates_values = requires(const Model& model, std::array<Value, 4>& stress,
                                                  const std::array<Value, 4>& de) {
    model.update_values(stress, de);
  };

  // update_stress for W particles at once: lane l of every value belongs to particle l, L the
  // velocity gradient, `strain` the accumulated [e_xx, e_yy, e_xy].
  template <class Value>
  requires updates_values<Value>
  static void update_stress_values(const Model& model, const std::array<std::array<Value, 2>, 2>& L,
                                   double dt, std::array<Value, 4>& stress,
                                   std::array<Value, 3>& strain) {
    // The same operations, in the same order, as update_stress: the same results.
    rotate_by_spin(0.5 * (L[0][1] - L[1][0]) * dt, stress);
    const std::array<Value, 4> increment{L[0][0] * dt, L[1][1] * dt, Value{},
                                         0.5 * (L[0][1] + L[1][0]) * dt};
    model.update_values(stress, increment);
    strain[0] += increment[0];
    strain[1] += increment[1];
    strain[2] += increment[3];
  }

  // The Jaumann rotation of the stress by the spin angle of a step, in place (an Eigen vector,
  // or an array of packs).
  template <class Value, class Stress>
  static void rotate_by_spin(const Value& spin, Stress& stress) {
    const Value sxx = stress[0];
    const Value syy = stress[1];
    const Value sxy = stress[3];
    stress[0] = sxx + 2.0 * spin * sxy;
    stress[1] = syy - 2.0 * spin * sxy;
    stress[3] = sxy + spin * (syy - sxx);
  }

  // A particle's nodal internal force -V sigma . grad N, written as sum_i dN/dx_i b[j][i] for
  // force component j (the transfers contract it one axis at a time).
  static std::array<std::array<double, 2>, 2> internal_force_coefficients(
      const typename Model::stress_type& stress, double volume) {
    const double sxy = -volume * stress[3];
    return {{{-volume * stress[0], sxy}, {sxy, -volume * stress[1]}}};
  }
};

}  // namespace cosmpm::continuum
