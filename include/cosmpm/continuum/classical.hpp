#pragma once
// The classical (nonpolar) continuum: which fields a particle carries and how its stress is
// updated from the velocity gradient of a step.
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
  static void update_stress(const Model& model, const rates_type<2>& rates, double dt,
                            typename Model::stress_type& stress, typename Model::state_type& state,
                            typename Model::strain_type& accumulated_strain) {
    const Mat<2>& velocity_gradient = rates.velocity_gradient;
    const double spin = 0.5 * (velocity_gradient(0, 1) - velocity_gradient(1, 0)) * dt;
    const double sxx = stress[0];
    const double syy = stress[1];
    const double sxy = stress[3];
    stress[0] = sxx + 2.0 * spin * sxy;
    stress[1] = syy - 2.0 * spin * sxy;
    stress[3] = sxy + spin * (syy - sxx);
    typename Model::strain_type increment;
    increment[0] = velocity_gradient(0, 0) * dt;
    increment[1] = velocity_gradient(1, 1) * dt;
    increment[2] = 0.0;
    increment[3] = 0.5 * (velocity_gradient(0, 1) + velocity_gradient(1, 0)) * dt;
    model.update(stress, state, increment);
    accumulated_strain += increment;
  }

  // Internal force density of a particle: -sigma . grad N (in-plane part of the stress).
  static Vec<2> stress_divergence_term(const typename Model::stress_type& stress,
                                       const Vec<2>& gradient) {
    return Vec<2>(stress[0] * gradient[0] + stress[3] * gradient[1],
                  stress[3] * gradient[0] + stress[1] * gradient[1]);
  }
};

}  // namespace cosmpm::continuum
