#pragma once
// The one way every continuum updates a particle's stress in a step: its own objective
// rotation of the old stress and the strain increment (Continuum::rotate_and_increment),
// the model's update, and the accumulation of the increment (Continuum::accumulate_strain).
// The batched caller (stages/stress_update.hpp) runs the same three parts around one model
// call for many particles.

namespace cosmpm::continuum {

template <class Continuum, class Model, class Rates>
void objective_update(const Model& model, const Rates& rates, double dt,
                      typename Model::stress_type& stress, typename Model::state_type& state,
                      typename Model::strain_type& strain) {
  const typename Model::strain_type increment = Continuum::rotate_and_increment(rates, dt, stress);
  model.update(stress, state, increment);
  Continuum::accumulate_strain(strain, increment);
}

}  // namespace cosmpm::continuum
