#pragma once
// The continuum concept: what the engine asks of a continuum, one named requirement each, so
// a new continuum (a micropolar variant, a gradient continuum, a 3D Cosserat one) is one new
// type and a mistake is named where it is made (check_continuum). A continuum is a value: it
// holds its constitutive model and its own settings (continuum/cosserat.hpp), and it decides
//
//   particle fields   particle_store<Dim>: the particles::Store of its fields, the engine's
//                     own (particle_fields.hpp) plus any of its own;
//   rates             rates_type<Dim>: what its stress update needs from the grid (velocity
//                     gradient, and the rates of its rotational degrees of freedom and their
//                     gradients), and the update itself: update_stress for one particle,
//                     rotate_and_increment + accumulate_strain around a batched model call,
//                     updates_values<Value> (and update_stress_values) for packs;
//   nodal dofs        rotational_dofs R, the nodal degrees of freedom besides the translations
//                     (0: classical; 1: the 2D Cosserat rotation), with each particle's
//                     rotational_inertia and rotational_velocity, update_rotations from the
//                     grid, initialise_particles for new particles, and
//                     apply_rotation_conditions on the grid's faces;
//   forces            internal_force_coefficients (the stress divergence) and
//                     rotational_force_terms (moments on the rotational dofs);
//   stable time step  stable_time_step(grid, max_density): its own bound (infinity when the
//                     engine's p-wave bound is all there is).
#include <array>
#include <concepts>
#include <span>

#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::continuum {

template <class C>
concept HasConstitutiveModel = requires(const C& continuum) {
  typename C::model_type;
  { continuum.model() } -> std::convertible_to<const typename C::model_type&>;
}
&&material::ConstitutiveModel<typename C::model_type>;

template <class C, int Dim>
concept HasParticleFields = requires {
  typename C::template particle_store<Dim>;
}
&&requires(typename C::template particle_store<Dim>& store) {
  store.template get<particles::field::Position<Dim>>();
  store.template get<particles::field::Velocity<Dim>>();
  store.template get<particles::field::Mass>();
  store.template get<particles::field::Volume>();
  store.template get<particles::field::DeformationGradient<Dim>>();
  store.template get<particles::field::Stress<typename C::model_type>>();
  store.template get<particles::field::Strain<typename C::model_type>>();
  store.template get<particles::field::MaterialState<typename C::model_type>>();
};

template <class C, int Dim>
concept HasRates = requires(const typename C::model_type& model,
                            const typename C::template rates_type<Dim>& rates, double dt,
                            typename C::model_type::stress_type& stress,
                            typename C::model_type::state_type& state,
                            typename C::model_type::strain_type& strain) {
  { rates.velocity_gradient } -> std::convertible_to<Mat<Dim>>;
  C::update_stress(model, rates, dt, stress, state, strain);
  {
    C::rotate_and_increment(rates, dt, stress)
    } -> std::same_as<typename C::model_type::strain_type>;
  C::accumulate_strain(strain, strain);
  { C::template updates_values<double> } -> std::convertible_to<bool>;
};

template <class C, int Dim>
concept HasRotationalDofs = requires {
  { C::rotational_dofs } -> std::convertible_to<int>;
}
&&(C::rotational_dofs >= 0) &&
    requires(const C& continuum, typename C::template particle_store<Dim>& store,
             const grid::Grid<Dim>& grid, std::span<double> nodal_rates,
             const std::array<double, C::rotational_dofs>& values) {
  {
    C::rotational_inertia(store, Index{}, double{})
    } -> std::same_as<std::array<double, C::rotational_dofs>>;
  {
    C::rotational_velocity(store, Index{})
    } -> std::same_as<std::array<double, C::rotational_dofs>>;
  C::update_rotations(store, Index{}, double{}, double{}, values, values);
  continuum.initialise_particles(store, Index{}, Index{});
  continuum.apply_rotation_conditions(grid, nodal_rates);
};

template <class C, int Dim>
concept HasForceTerms = requires(const typename C::model_type::stress_type& stress, double volume,
                                 double* weighted, std::array<double, Dim>* by_gradient) {
  {
    C::internal_force_coefficients(stress, volume)
    } -> std::convertible_to<std::array<std::array<double, Dim>, Dim>>;
  C::rotational_force_terms(stress, volume, weighted, by_gradient);
};

template <class C, int Dim>
concept HasStableTimeStep = requires(const C& continuum, const grid::Grid<Dim>& grid) {
  { continuum.stable_time_step(grid, double{}) } -> std::convertible_to<double>;
};

template <class C, int Dim>
concept Continuum = HasConstitutiveModel<C> && HasParticleFields<C, Dim> && HasRates<C, Dim> &&
    HasRotationalDofs<C, Dim> && HasForceTerms<C, Dim> && HasStableTimeStep<C, Dim>;

// The requirements one by one, each failure with its own message; true when all hold.
template <class C, int Dim>
consteval bool check_continuum() {
  if constexpr (material::ConstitutiveModel<C>) {
    static_assert(!material::ConstitutiveModel<C>,
                  "Simulation: a material was given where a continuum belongs; wrap it, e.g. "
                  "continuum::Classical<material::MohrCoulomb<>> or "
                  "continuum::Cosserat<material::CosseratDruckerPrager<>>");
    return false;
  } else {
    static_assert(HasConstitutiveModel<C>,
                  "continuum: needs `using model_type = <a material::ConstitutiveModel>` and "
                  "`const model_type& model() const`");
    if constexpr (HasConstitutiveModel<C>) {
      static_assert(HasParticleFields<C, Dim>,
                    "continuum: `particle_store<Dim>` must be a particles::Store with the "
                    "engine's fields (continuum::particle_store_with)");
      static_assert(HasRates<C, Dim>,
                    "continuum: needs `rates_type<Dim>` (with velocity_gradient), "
                    "update_stress, rotate_and_increment, accumulate_strain and "
                    "updates_values<Value>");
      static_assert(HasRotationalDofs<C, Dim>,
                    "continuum: needs `rotational_dofs` (>= 0) with rotational_inertia, "
                    "rotational_velocity, update_rotations, initialise_particles and "
                    "apply_rotation_conditions (empty bodies when rotational_dofs = 0)");
      static_assert(HasForceTerms<C, Dim>,
                    "continuum: needs internal_force_coefficients(stress, volume) and "
                    "rotational_force_terms(stress, volume, weighted, by_gradient)");
      static_assert(HasStableTimeStep<C, Dim>,
                    "continuum: needs `double stable_time_step(const grid::Grid<Dim>&, double "
                    "max_density) const` (infinity when it adds no bound)");
    }
    return Continuum<C, Dim>;
  }
}

}  // namespace cosmpm::continuum
