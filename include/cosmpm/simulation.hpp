#pragma once
// An explicit MPM simulation composed at compile time from a shape-function kernel, a
// continuum (which holds the constitutive model), a contact law and an update scheme:
//
//   using Sim = cosmpm::Simulation<2, shape::Linear,
//                                  continuum::Classical<material::LinearElastic<>>,
//                                  contact::SingleField, integrator::USL>;
//
// The class owns the state (simulation/engine_state.hpp) and is its public face: set-up, the
// stable step, the stages (stages/*.hpp), each callable on its own, and access. A step is the
// scheme's composition of the stages (integrator/*.hpp); each policy is checked by its
// concept where the composition is made, with a message naming what is missing.
#include <concepts>
#include <cstdint>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/single_field.hpp"
#include "cosmpm/continuum/concept.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/integrator/concept.hpp"
#include "cosmpm/integrator/schemes.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/simulation/block_scheduler.hpp"
#include "cosmpm/simulation/composition_checks.hpp"
#include "cosmpm/simulation/engine_state.hpp"
#include "cosmpm/simulation/free_surface_checks.hpp"
#include "cosmpm/simulation/parameters.hpp"
#include "cosmpm/stages/fused_pass.hpp"
#include "cosmpm/stages/grid_to_particle.hpp"
#include "cosmpm/stages/grid_update.hpp"
#include "cosmpm/stages/particle_to_grid.hpp"
#include "cosmpm/stages/remap.hpp"
#include "cosmpm/stages/stress_update.hpp"
#include "cosmpm/transfer/apic.hpp"
#include "cosmpm/transfer/concept.hpp"
#include "cosmpm/transfer/flip_blend.hpp"

namespace cosmpm {

template <int Dim, shape::Kernel Kernel, class Continuum, class Contact = contact::SingleField,
          class Scheme = integrator::USL, transfer::VelocityTransfer Transfer = transfer::FlipBlend>
class Simulation : detail::CompositionChecks<Dim, Kernel, Continuum, Contact, Scheme, Transfer> {
  using State = EngineState<Dim, Kernel, Continuum, Contact, Transfer>;

 public:
  using continuum_type = Continuum;
  using model_type = typename Continuum::model_type;
  using kernel_type = Kernel;
  using scheme_type = Scheme;
  using contact_type = Contact;
  using transfer_type = Transfer;
  using store_type = typename State::store_type;
  using stress_type = typename model_type::stress_type;
  using state_type = typename model_type::state_type;
  using rates_type = typename State::rates_type;
  using node_fields_type = NodeFields<Dim, State::rotational_dofs>;
  static constexpr int dim = Dim;
  static constexpr int rotational_dofs = State::rotational_dofs;
  static constexpr bool is_cosserat = Continuum::is_cosserat;

  Simulation(const grid::Grid<Dim>& background, const Continuum& continuum,
             const SimulationParameters<Dim>& parameters = {}, Contact contact_law = {})
      : state_(background, continuum, parameters, std::move(contact_law)) {
    validate(parameters);
    if (Transfer::affine && parameters.flip_fraction && *parameters.flip_fraction != 1.0) {
      throw Error("SimulationParameters: flip_fraction = " +
                  detail::format_number(*parameters.flip_fraction) + " blends FLIP into " +
                  Transfer::name() +
                  ", which has no FLIP part (valid: unset or 1; the blend applies to "
                  "transfer::FlipBlend)");
    }
    if (parameters.pic_where_separated && !material::records_separation<state_type>) {
      throw Error(
          "SimulationParameters: pic_where_separated = true, but the continuum's model keeps no "
          "separation state (valid: false, or a model whose state has one, e.g. "
          "material::MohrCoulomb)");
    }
    check_free_surface_flow<Kernel, Transfer>(parameters);
  }

  // A model where the continuum needs nothing else (continuum::Classical).
  template <std::same_as<model_type> Model>
  requires(!std::same_as<Model, Continuum>)
      Simulation(const grid::Grid<Dim>& background, const Model& model,
                 const SimulationParameters<Dim>& parameters = {}, Contact contact_law = {})
      : Simulation(background, continuum_from(model), parameters, std::move(contact_law)) {}

  // --- set-up -----------------------------------------------------------------------------

  // Adds particles at `positions`, each of volume `volume` and density `density`, with
  // half-width (in cell units) `half_width` for GIMP, belonging to `body`. Returns the index
  // of the first new particle. Stresses start at zero; set them through particles().
  Index add_particles(const std::vector<Vec<Dim>>& positions, double volume, double density,
                      const Vec<Dim>& half_width, std::int32_t body = 0) {
    require_positive("Simulation::add_particles", "volume", volume);
    require_positive("Simulation::add_particles", "density", density);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (!state_.grid.contains(positions[i])) {
        std::ostringstream message;
        message << "Simulation::add_particles: particle " << i << " at ("
                << positions[i].transpose() << ") lies outside the grid box ["
                << state_.grid.origin().transpose() << "] + [" << state_.grid.extent().transpose()
                << "]";
        throw Error(message.str());
      }
    }
    auto& store = state_.particles;
    state_.prescattered = false;
    const auto count = static_cast<Index>(positions.size());
    const Index first = store.append(count);
    namespace field = particles::field;
    for (Index i = 0; i < count; ++i) {
      const Index p = first + i;
      store.template get<field::Position<Dim>>()[p] = positions[static_cast<std::size_t>(i)];
      store.template get<field::InitialPosition<Dim>>()[p] = positions[static_cast<std::size_t>(i)];
      store.template get<field::Mass>()[p] = volume * density;
      store.template get<field::Volume>()[p] = volume;
      store.template get<field::InitialVolume>()[p] = volume;
      store.template get<field::HalfWidth<Dim>>()[p] = half_width;
      store.template get<field::DeformationGradient<Dim>>()[p].setIdentity();
      store.template get<field::Body>()[p] = body;
      store.template get<field::Stress<model_type>>()[p].setZero();
      store.template get<field::Strain<model_type>>()[p].setZero();
    }
    state_.continuum.initialise_particles(store, first, count);
    state_.typical_particle_mass = std::max(state_.typical_particle_mass, volume * density);
    state_.max_density = std::max(state_.max_density, density);
    return first;
  }

  // Largest stable step: the p-wave crosses the smallest cell at most once, and the
  // continuum's own bound holds (simulation/parameters.hpp).
  double stable_time_step() const {
    return cosmpm::stable_time_step(state_.continuum, state_.grid, state_.max_density);
  }
  // The step the run uses: the requested one, checked against the stable one.
  double time_step() const { return choose_time_step(state_.parameters, stable_time_step()); }

  // --- the step ---------------------------------------------------------------------------

  // Advances one step of size dt (the scheme's stages, then the contact law and the clock)
  // and returns the new time.
  double step(double dt) {
    static_assert(integrator::IntegratorFor<Scheme, Simulation>,
                  "Simulation: the scheme has no `template <class Sim> static void step(Sim&, "
                  "double dt)` this simulation can call (integrator/concept.hpp)");
    require_positive("Simulation::step", "dt", dt);
    Scheme::step(*this, dt);
    handle_stray_particles();
    state_.contact.advance(dt, state_.clock.time);
    state_.clock.time += dt;
    ++state_.clock.step_count;
    return state_.clock.time;
  }

  // --- the stages (stages/*.hpp), for schemes and for users who call them one by one -----

  // Particle mass and momentum (and, with_forces, internal and external forces) to the nodes;
  // keeps each particle's stencil for the later maps of the step.
  void map_to_grid(bool with_forces) { stages::map_to_grid(state_, with_forces); }
  // USF: the forces of the updated stresses (after map_to_grid(false)).
  void map_forces_to_grid() { stages::map_forces_to_grid(state_); }
  // USF: the start velocity from the mapped momentum, in nodes().momentum, corrected.
  void grid_velocity_from_momentum(double dt) { stages::grid_velocity_from_momentum(state_, dt); }
  // Momentum update, damping, contact and boundary conditions.
  void update_grid(double dt) { stages::update_grid(state_, dt); }
  // map_to_grid(true) then update_grid(dt), the same results with one node pass less.
  void map_and_update_grid(double dt) { stages::map_and_update_grid(state_, dt); }
  // Particle velocity and position (FLIP/PIC) from the grid; with_stress_update, also the
  // velocity gradient, deformation and stress at the same stencil (USL).
  void map_to_particles(double dt, bool with_stress_update = false) {
    stages::map_to_particles(state_, dt, with_stress_update);
  }
  // MUSL: the updated particle momenta back to the grid, into nodes().velocity (and spin).
  void remap_momentum(double dt) { stages::remap_momentum(state_, dt); }
  // Particle rates from a nodal velocity (and rotational-rate) field.
  void velocity_gradient_from_grid(const std::vector<Vec<Dim>>& node_velocity,
                                   const std::vector<double>& node_spin = {}) {
    stages::velocity_gradient_from_grid(state_, node_velocity, node_spin);
  }
  // Constitutive update, deformation gradient and volume from those rates.
  void update_stress(double dt) { stages::update_stress(state_, dt); }
  // velocity_gradient_from_grid(node_velocity, node_spin) and update_stress(dt) in one pass.
  void update_stress_from_grid(double dt, const std::vector<Vec<Dim>>& node_velocity,
                               const std::vector<double>& node_spin = {}) {
    stages::update_stress_from_grid(state_, dt, node_velocity, node_spin);
  }
  // Fused schemes (integrator/fused.hpp): as map_to_grid(true), in the fused pass's order, or
  // the node fields from the records the last step's fused pass scattered while they are valid.
  void map_to_grid_or_reuse() { stages::map_to_grid_or_reuse(state_); }
  // map_to_grid_or_reuse() then update_grid(dt), one node pass less (as map_and_update_grid).
  void map_or_reuse_and_update_grid(double dt) { stages::map_or_reuse_and_update_grid(state_, dt); }
  // Fused USL: map_to_particles(dt, true) and the next step's map_to_grid in one pass.
  void map_to_particles_and_grid(double dt) { stages::map_to_particles_and_grid(state_, dt); }
  // Fused MUSL: map_to_particles(dt) and remap_momentum(dt) in one pass.
  void map_to_particles_and_remap(double dt) { stages::map_to_particles_and_remap(state_, dt); }
  // Fused MUSL: update_stress(dt) and the next step's map_to_grid in one pass.
  void update_stress_and_map_to_grid(double dt) {
    stages::update_stress_and_map_to_grid(state_, dt);
  }
  // Fused MUSL: velocity_gradient_from_grid(node_velocity, node_spin) too, in the same pass.
  void update_stress_and_map_to_grid(double dt, const std::vector<Vec<Dim>>& node_velocity,
                                     const std::vector<double>& node_spin = {}) {
    stages::update_stress_and_map_to_grid(state_, dt, node_velocity, node_spin);
  }
  // Particles that left the grid box leave the simulation (SimulationParameters::
  // stray_particles); step() calls it last.
  void handle_stray_particles() { stages::handle_stray_particles(state_); }

  // --- access -----------------------------------------------------------------------------
  // Taking the particles, the continuum or the engine for writing drops the records a fused
  // scheme scattered for the next step (integrator/fused.hpp).
  store_type& particles() {
    state_.prescattered = false;
    return state_.particles;
  }
  const store_type& particles() const { return state_.particles; }
  const node_fields_type& nodes() const { return state_.nodes; }
  const grid::Grid<Dim>& grid() const { return state_.grid; }
  grid::BoundaryConditions<Dim>& boundary_conditions() { return state_.boundary; }
  const grid::BoundaryConditions<Dim>& boundary_conditions() const { return state_.boundary; }
  // The contact law: rigid-body positions, forces and traction records of the last step.
  Contact& contact() { return state_.contact; }
  const Contact& contact() const { return state_.contact; }
  // The continuum and its settings (Cosserat: micro-inertia, rotation conditions).
  Continuum& continuum() {
    state_.prescattered = false;
    return state_.continuum;
  }
  const Continuum& continuum() const { return state_.continuum; }
  const model_type& model() const { return state_.model(); }
  const SimulationParameters<Dim>& parameters() const { return state_.parameters; }
  double time() const { return state_.clock.time; }
  std::int64_t step_count() const { return state_.clock.step_count; }
  int threads() const { return state_.threads; }
  // Particles that left the grid under StrayParticles::freeze or ::remove, and the frozen ones.
  const StrayReport& stray_particles() const { return state_.strays; }
  const store_type& frozen_particles() const { return state_.frozen; }
  // Threads that ran the last coloured particle pass (1: serial).
  int last_team_size() const { return state_.blocks.last_team_size(); }
  // Everything the stages work on, for users who write stages of their own.
  State& engine() {
    state_.prescattered = false;
    return state_;
  }
  const State& engine() const { return state_; }

  // Local damping can change between phases (e.g. damped settling, then undamped cutting).
  void set_damping(double damping) {
    require_in_range("Simulation::set_damping", "damping", damping, 0.0, 1.0, Bounds::left_closed);
    state_.parameters.damping = damping;
  }
  // For restarts: the clock is part of the checkpointed state.
  void set_clock(double time, std::int64_t step_count) { state_.clock = {time, step_count}; }

 private:
  template <class Model>
  static Continuum continuum_from(const Model& model) {
    static_assert(std::is_constructible_v<Continuum, const Model&>,
                  "Simulation: this continuum needs settings besides its model; construct it "
                  "first, e.g. continuum::Cosserat<Model>(model, {.micro_inertia = ...}), and "
                  "pass the continuum instead of the model");
    if constexpr (std::is_constructible_v<Continuum, const Model&>) {
      return Continuum(model);
    } else {
      throw Error("Simulation: the continuum needs settings besides its model");
    }
  }

  State state_;
};

}  // namespace cosmpm
