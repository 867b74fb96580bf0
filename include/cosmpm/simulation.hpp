#pragma once
// An explicit MPM simulation composed at compile time from a shape-function kernel, a
// continuum (which carries the constitutive model), a contact law and an update scheme:
//
//   using Sim = cosmpm::Simulation<2, shape::Linear,
//   continuum::Classical<material::LinearElastic<>>,
//                                  contact::SingleField, integrator::USL>;
//
// The step is a sequence of named stages over SoA arrays (map_to_grid, update_grid,
// map_to_particles, update_stress), each public so a benchmark can time it on its own.
// Scatter to the grid is deterministic whatever the thread count: particles are bucketed
// into blocks of cells and blocks of one colour (parity per axis) never share a node.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/LU>  // determinant

#include "cosmpm/contact/single_field.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/integrator/schemes.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/stencil.hpp"

namespace cosmpm {

template <int Dim>
struct SimulationParameters {
  Vec<Dim> gravity = Vec<Dim>::Zero();
  // Fraction of FLIP in the particle velocity update: 1 = FLIP (the paper's Eq. 18), 0 = PIC.
  double flip_fraction = 1.0;
  // Cundall local non-viscous damping coefficient on the nodal unbalanced force, in [0, 1).
  double damping = 0.0;
  // Time step; 0 means cfl * stable_time_step().
  double time_step = 0.0;
  double cfl = 0.5;
  // A requested time step above the stable one is an error unless this is set.
  bool allow_unstable_time_step = false;
  // OpenMP threads; 0 means OpenMP's default. Results do not depend on it.
  int threads = 0;
  // Nodes lighter than this fraction of a typical particle mass are treated as empty.
  double empty_node_mass_fraction = 1e-12;
  // Cosserat continua only: micro-inertia J per unit mass of new particles, m^2 (the
  // paper's corn: 0.5 (0.5 l)^2 = 12.5e-6 m^2 for l = 10 mm).
  double micro_inertia = 0.0;
};

namespace detail {
struct ParticleBlocks {
  // Cells per block along each axis: >= the widest kernel support, so same-colour blocks two
  // apart never share a node. Longer along x, the fastest axis of seeded particle indices, so
  // a block's particles sit in longer runs of memory (fewer jumps in the scatter).
  static constexpr Index block_cells(int axis) { return axis == 0 ? 16 : 4; }
};
}  // namespace detail

template <int Dim, shape::Kernel Kernel, class Continuum, class Contact = contact::SingleField,
          integrator::Integrator Scheme = integrator::USL>
class Simulation {
 public:
  using model_type = typename Continuum::model_type;
  using continuum_type = Continuum;
  using kernel_type = Kernel;
  using scheme_type = Scheme;
  using contact_type = Contact;
  using store_type = typename Continuum::template particle_store<Dim>;
  using stress_type = typename model_type::stress_type;
  using state_type = typename model_type::state_type;
  using stencil_type = shape::Stencil<Dim, Kernel>;
  using rates_type = typename Continuum::template rates_type<Dim>;
  static constexpr int dim = Dim;
  static constexpr bool is_cosserat = Continuum::is_cosserat;

  struct NodeFields {
    std::vector<double> mass;
    std::vector<Vec<Dim>> momentum;  // momentum, then velocity at the start of the step
    std::vector<Vec<Dim>> force;
    std::vector<Vec<Dim>> velocity;  // updated velocity (end of the step)
    std::vector<Vec<Dim>> acceleration;
    // Cosserat only (empty otherwise): lumped rotational inertia sum N m J, spin momentum
    // then start spin, moment, end spin and spin acceleration.
    std::vector<double> rotational_inertia;
    std::vector<double> spin_momentum;
    std::vector<double> moment;
    std::vector<double> spin;
    std::vector<double> spin_acceleration;
  };

  Simulation(const grid::Grid<Dim>& background, const model_type& model,
             const SimulationParameters<Dim>& parameters = {}, Contact contact_law = {})
      : grid_(background),
        model_(model),
        parameters_(parameters),
        contact_(std::move(contact_law)) {
    require_in_range("SimulationParameters", "flip_fraction", parameters.flip_fraction, 0.0, 1.0,
                     Bounds::closed);
    require_in_range("SimulationParameters", "damping", parameters.damping, 0.0, 1.0,
                     Bounds::left_closed);
    require_in_range("SimulationParameters", "cfl", parameters.cfl, 0.0, 1.0, Bounds::right_closed);
    require_non_negative("SimulationParameters", "time_step", parameters.time_step);
    require_in_range("SimulationParameters", "threads", parameters.threads, 0, 4096,
                     Bounds::closed);
    for (int d = 0; d < Dim; ++d) {
      require(std::isfinite(parameters.gravity[d]),
              "SimulationParameters: gravity has a non-finite component");
    }
    threads_ = resolve_thread_count(parameters.threads);
    const Index nodes = grid_.node_count();
    nodes_.mass.assign(nodes, 0.0);
    nodes_.momentum.assign(nodes, Vec<Dim>::Zero());
    nodes_.force.assign(nodes, Vec<Dim>::Zero());
    nodes_.velocity.assign(nodes, Vec<Dim>::Zero());
    nodes_.acceleration.assign(nodes, Vec<Dim>::Zero());
    if constexpr (is_cosserat) {
      require_positive("SimulationParameters", "micro_inertia (Cosserat continuum)",
                       parameters.micro_inertia);
      nodes_.rotational_inertia.assign(nodes, 0.0);
      nodes_.spin_momentum.assign(nodes, 0.0);
      nodes_.moment.assign(nodes, 0.0);
      nodes_.spin.assign(nodes, 0.0);
      nodes_.spin_acceleration.assign(nodes, 0.0);
    }
    for (int d = 0; d < Dim; ++d) {
      blocks_per_axis_[d] = (grid_.cells(d) + detail::ParticleBlocks::block_cells(d) - 1) /
                            detail::ParticleBlocks::block_cells(d);
    }
    Index block_total = 1;
    for (int d = 0; d < Dim; ++d) block_total *= blocks_per_axis_[d];
    block_start_.assign(block_total + 1, 0);
    for (Index block = 0; block < block_total; ++block) {
      colour_blocks_[block_colour(block)].push_back(block);
    }
  }

  // --- set-up -----------------------------------------------------------------------------

  // Adds particles at `positions`, each of volume `volume` and density `density`, with
  // half-width (in cell units) `half_width` for GIMP, belonging to `body`. Returns the index
  // of the first new particle. Stresses start at zero; set them through particles().
  Index add_particles(const std::vector<Vec<Dim>>& positions, double volume, double density,
                      const Vec<Dim>& half_width, std::int32_t body = 0) {
    require_positive("Simulation::add_particles", "volume", volume);
    require_positive("Simulation::add_particles", "density", density);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (!grid_.contains(positions[i])) {
        std::ostringstream message;
        message << "Simulation::add_particles: particle " << i << " at ("
                << positions[i].transpose() << ") lies outside the grid box ["
                << grid_.origin().transpose() << "] + [" << grid_.extent().transpose() << "]";
        throw Error(message.str());
      }
    }
    const Index first = particles_.append(static_cast<Index>(positions.size()));
    auto& x = particles_.template get<particles::field::Position<Dim>>();
    auto& x0 = particles_.template get<particles::field::InitialPosition<Dim>>();
    auto& mass = particles_.template get<particles::field::Mass>();
    auto& vol = particles_.template get<particles::field::Volume>();
    auto& vol0 = particles_.template get<particles::field::InitialVolume>();
    auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    auto& F = particles_.template get<particles::field::DeformationGradient<Dim>>();
    auto& owner = particles_.template get<particles::field::Body>();
    auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    auto& strain = particles_.template get<particles::field::Strain<model_type>>();
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const Index p = first + static_cast<Index>(i);
      x[p] = positions[i];
      x0[p] = positions[i];
      mass[p] = volume * density;
      vol[p] = volume;
      vol0[p] = volume;
      half[p] = half_width;
      F[p].setIdentity();
      owner[p] = body;
      stress[p].setZero();
      strain[p].setZero();
      if constexpr (is_cosserat) {
        particles_.template get<particles::field::MicroInertia>()[p] = parameters_.micro_inertia;
      }
    }
    typical_particle_mass_ = std::max(typical_particle_mass_, volume * density);
    max_density_ = std::max(max_density_, density);
    return first;
  }

  // Largest stable step: the p-wave crosses the smallest cell at most once. A Cosserat
  // continuum also bounds it by its highest rotational frequency,
  //   omega^2 = (4 Gc + 8 G l^2 sum_d 1 / h_d^2) / (rho J),  dt <= 2 / omega,
  // the local (s_xy - s_yx) stiffness plus the couple-stress "Laplacian" on the grid.
  double stable_time_step() const {
    require(max_density_ > 0.0, "Simulation::stable_time_step: no particles have been added");
    const double wave_speed = std::sqrt(model_.p_wave_modulus() / max_density_);
    double stable = grid_.min_cell_size() / wave_speed;
    if constexpr (is_cosserat) {
      double inverse_h2 = 0.0;
      for (int d = 0; d < Dim; ++d)
        inverse_h2 += 1.0 / (grid_.cell_size()[d] * grid_.cell_size()[d]);
      const double stiffness =
          4.0 * model_.cosserat_shear_modulus() + 4.0 * model_.bending_modulus() * inverse_h2;
      const double omega = std::sqrt(stiffness / (max_density_ * parameters_.micro_inertia));
      stable = std::min(stable, 2.0 / omega);
    }
    return stable;
  }

  // The step the run uses: the requested one, checked against the stable one.
  double time_step() const {
    const double stable = stable_time_step();
    if (parameters_.time_step == 0.0) return parameters_.cfl * stable;
    if (parameters_.time_step > stable && !parameters_.allow_unstable_time_step) {
      throw Error(
          "SimulationParameters: time_step = " + detail::format_number(parameters_.time_step) +
          " s is above the stable time step " + detail::format_number(stable) +
          " s (valid range (0, " + detail::format_number(stable) +
          "]; set allow_unstable_time_step to override)");
    }
    return parameters_.time_step;
  }

  // --- the step ---------------------------------------------------------------------------

  // Advances one step of size dt and returns the new time.
  double step(double dt) {
    require_positive("Simulation::step", "dt", dt);
    current_dt_ = dt;
    if constexpr (Scheme::scheme == integrator::Scheme::usf) {
      map_to_grid(/*with_forces=*/false);
      grid_velocity_from_momentum();
      // momentum holds the start velocity, spin_momentum the start spin
      velocity_gradient_from_grid(nodes_.momentum, nodes_.spin_momentum);
      update_stress(dt);
      map_forces_to_grid();
      update_grid(dt);
      map_to_particles(dt);
    } else if constexpr (Scheme::scheme == integrator::Scheme::usl) {
      map_to_grid(/*with_forces=*/true);
      update_grid(dt);
      map_to_particles(dt, /*with_stress_update=*/true);
    } else {
      map_to_grid(/*with_forces=*/true);
      update_grid(dt);
      map_to_particles(dt);
      remap_momentum();
      velocity_gradient_from_grid(nodes_.velocity, nodes_.spin);
      update_stress(dt);
    }
    contact_.advance(dt, time_);
    time_ += dt;
    ++step_count_;
    return time_;
  }

  // Stage 1: particle mass and momentum (and, with_forces, internal and external forces) to
  // the nodes. Buckets particles into coloured blocks first.
  void map_to_grid(bool with_forces) {
    bucket_particles();
    const auto& x = particles_.template get<particles::field::Position<Dim>>();
    const auto& v = particles_.template get<particles::field::Velocity<Dim>>();
    const auto& mass = particles_.template get<particles::field::Mass>();
    const auto& vol = particles_.template get<particles::field::Volume>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    const auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    clear_nodes(with_forces);
    const Vec<Dim> gravity = parameters_.gravity;
    // Raw pointers: the compiler need not reload the vectors' data after each node store.
    double* const node_mass = nodes_.mass.data();
    Vec<Dim>* const node_momentum = nodes_.momentum.data();
    Vec<Dim>* const node_force = nodes_.force.data();
    for_each_particle_coloured([&](Index p) {
      stencil_type s;
      s.compute(grid_, x[p], half[p]);
      const double mp = mass[p];
      const Vec<Dim> momentum = mp * v[p];
      if (with_forces) {
        // A local copy: node stores could alias the particle arrays, forcing reloads.
        const stress_type volume_stress = vol[p] * stress[p];
        const Vec<Dim> weight_force = mp * gravity;
        [[maybe_unused]] double inertia = 0.0, spin_momentum = 0.0;
        if constexpr (is_cosserat) {
          inertia = mp * particles_.template get<particles::field::MicroInertia>()[p];
          spin_momentum = inertia * particles_.template get<particles::field::MicroSpin>()[p];
        }
        for (int k = 0; k < stencil_type::size; ++k) {
          const Index n = s.node[k];
          const double w = s.weight[k];
          node_mass[n] += w * mp;
          node_momentum[n] += w * momentum;
          node_force[n] +=
              w * weight_force - Continuum::stress_divergence_term(volume_stress, s.gradient[k]);
          if constexpr (is_cosserat) {
            // The rotational balance shares the stencil loop (one pass over the nodes).
            nodes_.rotational_inertia[n] += w * inertia;
            nodes_.spin_momentum[n] += w * spin_momentum;
            nodes_.moment[n] += Continuum::moment_term(volume_stress, w, s.gradient[k]);
          }
        }
      } else {
        if constexpr (is_cosserat) map_rotation_to_grid(p, s);
        for (int k = 0; k < stencil_type::size; ++k) {
          const Index n = s.node[k];
          const double w = s.weight[k];
          node_mass[n] += w * mp;
          node_momentum[n] += w * momentum;
        }
      }
    });
  }

  // USF only: forces after the stress update (mass and momentum are already on the grid).
  void map_forces_to_grid() {
    if constexpr (is_cosserat) {
      for (Index n = 0; n < grid_.node_count(); ++n) {
        nodes_.spin_momentum[n] *= nodes_.rotational_inertia[n];
        nodes_.moment[n] = 0.0;
      }
    }
    const auto& x = particles_.template get<particles::field::Position<Dim>>();
    const auto& mass = particles_.template get<particles::field::Mass>();
    const auto& vol = particles_.template get<particles::field::Volume>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    const auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    const Vec<Dim> gravity = parameters_.gravity;
    // Grid momenta were turned into velocities by grid_velocity_from_momentum; restore them.
    for (Index n = 0; n < grid_.node_count(); ++n) {
      nodes_.momentum[n] *= nodes_.mass[n];
      nodes_.force[n].setZero();
    }
    for_each_particle_coloured([&](Index p) {
      stencil_type s;
      s.compute(grid_, x[p], half[p]);
      if constexpr (is_cosserat) map_moment_to_grid(p, s);
      const Vec<Dim> weight_force = mass[p] * gravity;
      for (int k = 0; k < stencil_type::size; ++k) {
        nodes_.force[s.node[k]] +=
            s.weight[k] * weight_force -
            vol[p] * Continuum::stress_divergence_term(stress[p], s.gradient[k]);
      }
    });
  }

  // Stage 2: nodal velocity and acceleration from momentum and force (lumped mass), local
  // damping, boundary conditions. Afterwards nodes_.momentum holds the start velocity v^t,
  // nodes_.velocity the end velocity v^{t+dt} and nodes_.acceleration (v^{t+dt} - v^t) / dt.
  void update_grid(double dt) {
    const double empty = empty_node_mass();
    const double damping = parameters_.damping;
    const Index count = grid_.node_count();
    COSMPM_OMP_PARALLEL_FOR(threads_, count)
    for (Index n = 0; n < count; ++n) {
      const double m = nodes_.mass[n];
      if (m <= empty) {
        nodes_.momentum[n].setZero();
        nodes_.velocity[n].setZero();
        if constexpr (is_cosserat) nodes_.spin_momentum[n] = nodes_.spin[n] = 0.0;
        continue;
      }
      const Vec<Dim> v_start = nodes_.momentum[n] / m;
      Vec<Dim> force = nodes_.force[n];
      if (damping > 0.0) {
        // Cundall: oppose the motion with a fraction of the unbalanced force, per component.
        for (int d = 0; d < Dim; ++d) {
          const double sign = v_start[d] > 0.0 ? 1.0 : (v_start[d] < 0.0 ? -1.0 : 0.0);
          force[d] -= damping * std::abs(force[d]) * sign;
        }
      }
      nodes_.momentum[n] = v_start;
      nodes_.velocity[n] = v_start + dt * force / m;
      if constexpr (is_cosserat) {
        const double inertia = nodes_.rotational_inertia[n];
        const double spin_start = nodes_.spin_momentum[n] / inertia;
        double moment = nodes_.moment[n];
        if (damping > 0.0) {
          const double sign = spin_start > 0.0 ? 1.0 : (spin_start < 0.0 ? -1.0 : 0.0);
          moment -= damping * std::abs(moment) * sign;
        }
        nodes_.spin_momentum[n] = spin_start;
        nodes_.spin[n] = spin_start + dt * moment / inertia;
      }
    }
    // Contact acts on the updated velocity only, so the acceleration (and through FLIP the
    // particles) carries its impulse; boundary conditions come last and win.
    correct_contact(nodes_.velocity, spin_field(nodes_.spin), dt, contact::Phase::end_velocity);
    COSMPM_OMP_PARALLEL_FOR(threads_, count)
    for (Index n = 0; n < count; ++n) {
      apply_boundary_conditions(n, nodes_.momentum[n]);
      apply_boundary_conditions(n, nodes_.velocity[n]);
      nodes_.acceleration[n] = (nodes_.velocity[n] - nodes_.momentum[n]) / dt;
      if constexpr (is_cosserat) {
        apply_rotation_conditions(n, nodes_.spin_momentum[n]);
        apply_rotation_conditions(n, nodes_.spin[n]);
        nodes_.spin_acceleration[n] = (nodes_.spin[n] - nodes_.spin_momentum[n]) / dt;
      }
    }
  }

  // Stage 3: particle velocity (PIC/FLIP blend) and position from the grid.
  // USL fuses the velocity gradient and the stress update into this pass: one sweep over the
  // particles instead of three, at the same (start-of-step) stencil.
  void map_to_particles(double dt, bool with_stress_update = false) {
    if (with_stress_update) {
      map_to_particles_impl<true>(dt);
    } else {
      map_to_particles_impl<false>(dt);
    }
  }

 private:
  template <bool with_stress_update>
  void map_to_particles_impl(double dt) {
    auto& L = particles_.template get<particles::field::VelocityGradient<Dim>>();
    auto& x = particles_.template get<particles::field::Position<Dim>>();
    auto& v = particles_.template get<particles::field::Velocity<Dim>>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    const double flip = parameters_.flip_fraction;
    const Index count = particles_.size();
    const Vec<Dim>* const node_velocity = nodes_.velocity.data();
    const Vec<Dim>* const node_acceleration = nodes_.acceleration.data();
    const GridBox box(grid_);
    Index first_outside = count;
    Index first_bad = count;
    COSMPM_OMP_PARALLEL_FOR(threads_, count)
    for (Index p = 0; p < count; ++p) {
      stencil_type s;
      s.compute(grid_, x[p], half[p]);
      Vec<Dim> v_grid = Vec<Dim>::Zero();
      Vec<Dim> a_grid = Vec<Dim>::Zero();
      rates_type rates;
      [[maybe_unused]] double spin_grid = 0.0, spin_acceleration = 0.0;
      [[maybe_unused]] Vec<Dim> spin_gradient = Vec<Dim>::Zero();
      for (int k = 0; k < stencil_type::size; ++k) {
        const Vec<Dim>& v_node = node_velocity[s.node[k]];
        v_grid += s.weight[k] * v_node;
        a_grid += s.weight[k] * node_acceleration[s.node[k]];
        if constexpr (with_stress_update) {
          rates.velocity_gradient.noalias() += v_node * s.gradient[k].transpose();
        }
        if constexpr (is_cosserat) {  // the micro-spin shares the stencil loop
          const double spin_node = nodes_.spin[s.node[k]];
          spin_grid += s.weight[k] * spin_node;
          spin_acceleration += s.weight[k] * nodes_.spin_acceleration[s.node[k]];
          spin_gradient += spin_node * s.gradient[k];
        }
      }
      if constexpr (is_cosserat) {
        update_particle_rotation(p, dt, flip, spin_grid, spin_acceleration);
        rates.spin = spin_grid;
        rates.spin_gradient = spin_gradient;
      }
      if constexpr (with_stress_update) {
        L[p] = rates.velocity_gradient;
        if (!update_particle_stress(p, rates, dt)) record_first(first_bad, p);
      }
      v[p] = flip * (v[p] + dt * a_grid) + (1.0 - flip) * v_grid;
      x[p] += dt * v_grid;
      if (!box.contains(x[p])) [[unlikely]]
        record_first(first_outside, p);
    }
    // A particle that left the grid usually also tore its neighbourhood: name the cause.
    if (first_outside < count) throw_outside(first_outside);
    if (first_bad < count) throw_unstable_stress(first_bad);
  }

  // Grid::contains with the grid's constants in registers (same arithmetic, same answer).
  struct GridBox {
    Vec<Dim> origin, inverse_cell_size, cells;
    explicit GridBox(const grid::Grid<Dim>& grid)
        : origin(grid.origin()), inverse_cell_size(grid.inverse_cell_size()) {
      for (int d = 0; d < Dim; ++d) cells[d] = static_cast<double>(grid.cells(d));
    }
    bool contains(const Vec<Dim>& x) const {
      bool inside = true;
      for (int d = 0; d < Dim; ++d) {
        const double xi = (x[d] - origin[d]) * inverse_cell_size[d];
        inside = inside && xi > 0.0 && xi < cells[d];
      }
      return inside;
    }
  };

  // Keeps the lowest index, so messages do not depend on the thread count.
  static void record_first(Index& first, Index p) {
#if defined(_OPENMP)
#pragma omp critical(cosmpm_record_first)
#endif
    first = std::min(first, p);
  }

  // Constitutive update, deformation gradient and volume of one particle; false when the
  // result is not physical (inverted volume or non-finite stress).
  bool update_particle_stress(Index p, const rates_type& rates, double dt) {
    const Mat<Dim> L = rates.velocity_gradient;
    auto& F = particles_.template get<particles::field::DeformationGradient<Dim>>()[p];
    auto& stress = particles_.template get<particles::field::Stress<model_type>>()[p];
    Continuum::update_stress(
        model_, rates, dt, stress,
        particles_.template get<particles::field::MaterialState<model_type>>()[p],
        particles_.template get<particles::field::Strain<model_type>>()[p]);
    F = (Mat<Dim>::Identity() + dt * L) * F;
    const double J = F.determinant();
    particles_.template get<particles::field::Volume>()[p] =
        J * particles_.template get<particles::field::InitialVolume>()[p];
    // x * 0 is 0 for finite x and NaN otherwise: one sum instead of a test per component.
    return J > 0.0 && (stress.array() * 0.0).sum() == 0.0;
  }

  void throw_unstable_stress(Index p) const {
    const auto& F = particles_.template get<particles::field::DeformationGradient<Dim>>();
    const auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    std::ostringstream message;
    message << "Simulation: the run went unstable at step " << step_count_ << " (t = " << time_
            << " s): particle " << p << " has volume ratio det(F) = " << F[p].determinant()
            << " (valid range (0, inf)) and stress (" << stress[p].transpose()
            << ") (must be finite); reduce the time step or check the set-up";
    throw Error(message.str());
  }

  void throw_outside(Index p) const {
    const auto& x = particles_.template get<particles::field::Position<Dim>>();
    const auto& v = particles_.template get<particles::field::Velocity<Dim>>();
    std::ostringstream message;
    if (!x[p].allFinite() || !v[p].allFinite()) {
      message << "Simulation: the run went unstable at step " << step_count_ << " (t = " << time_
              << " s): particle " << p << " has position (" << x[p].transpose()
              << ") and velocity (" << v[p].transpose()
              << ") (must be finite); reduce the time step or check the set-up";
    } else {
      message << "Simulation: particle " << p << " at (" << x[p].transpose()
              << ") left the grid box [" << grid_.origin().transpose() << "] + ["
              << grid_.extent().transpose() << "] at step " << step_count_ << " (t = " << time_
              << " s); the valid region is the open grid box";
    }
    throw Error(message.str());
  }

 public:
  // MUSL: map the updated particle momenta back to the grid (with the start-of-step stencils,
  // as the grid mass was) and use that velocity field for the strain rate.
  void remap_momentum() {
    const auto& v = particles_.template get<particles::field::Velocity<Dim>>();
    const auto& mass = particles_.template get<particles::field::Mass>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    std::fill(nodes_.velocity.begin(), nodes_.velocity.end(), Vec<Dim>::Zero());
    if constexpr (is_cosserat) std::fill(nodes_.spin.begin(), nodes_.spin.end(), 0.0);
    const auto& start = start_positions();
    for_each_particle_coloured([&](Index p) {
      stencil_type s;
      s.compute(grid_, start[p], half[p]);
      const Vec<Dim> momentum = mass[p] * v[p];
      for (int k = 0; k < stencil_type::size; ++k) {
        nodes_.velocity[s.node[k]] += s.weight[k] * momentum;
      }
      if constexpr (is_cosserat) {
        const double spin_momentum = mass[p] *
                                     particles_.template get<particles::field::MicroInertia>()[p] *
                                     particles_.template get<particles::field::MicroSpin>()[p];
        for (int k = 0; k < stencil_type::size; ++k) {
          nodes_.spin[s.node[k]] += s.weight[k] * spin_momentum;
        }
      }
    });
    const double empty = empty_node_mass();
    for (Index n = 0; n < grid_.node_count(); ++n) {
      if (nodes_.mass[n] <= empty) {
        nodes_.velocity[n].setZero();
        if constexpr (is_cosserat) nodes_.spin[n] = 0.0;
        continue;
      }
      nodes_.velocity[n] /= nodes_.mass[n];
      if constexpr (is_cosserat) nodes_.spin[n] /= nodes_.rotational_inertia[n];
    }
    correct_contact(nodes_.velocity, spin_field(nodes_.spin), current_dt_,
                    contact::Phase::remapped_velocity);
    for (Index n = 0; n < grid_.node_count(); ++n) {
      apply_boundary_conditions(n, nodes_.velocity[n]);
      if constexpr (is_cosserat) apply_rotation_conditions(n, nodes_.spin[n]);
    }
  }

  // Stage 4a: particle rates (velocity gradient; Cosserat: spin and its gradient) from a
  // nodal field, at the stencils of the start of the step. The spin field is ignored by a
  // classical continuum.
  void velocity_gradient_from_grid(const std::vector<Vec<Dim>>& node_velocity,
                                   const std::vector<double>& node_spin = {}) {
    const auto& start = start_positions();
    auto& L = particles_.template get<particles::field::VelocityGradient<Dim>>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    const Index count = particles_.size();
    particle_rates_.resize(count);
    COSMPM_OMP_PARALLEL_FOR(threads_, count)
    for (Index p = 0; p < count; ++p) {
      stencil_type s;
      s.compute(grid_, start[p], half[p]);
      rates_type rates;
      for (int k = 0; k < stencil_type::size; ++k) {
        rates.velocity_gradient.noalias() += node_velocity[s.node[k]] * s.gradient[k].transpose();
        if constexpr (is_cosserat) {
          rates.spin += s.weight[k] * node_spin[s.node[k]];
          rates.spin_gradient += node_spin[s.node[k]] * s.gradient[k];
        }
      }
      L[p] = rates.velocity_gradient;
      particle_rates_[p] = rates;
    }
  }

  // Stage 4b: constitutive update, deformation gradient and volume.
  void update_stress(double dt) {
    require(static_cast<Index>(particle_rates_.size()) == particles_.size(),
            "Simulation::update_stress: call velocity_gradient_from_grid first");
    const Index count = particles_.size();
    Index first_bad = count;
    COSMPM_OMP_PARALLEL_FOR(threads_, count)
    for (Index p = 0; p < count; ++p) {
      if (!update_particle_stress(p, particle_rates_[p], dt)) record_first(first_bad, p);
    }
    if (first_bad < count) throw_unstable_stress(first_bad);
  }

  // --- access -----------------------------------------------------------------------------
  store_type& particles() {
    return particles_;
  }
  const store_type& particles() const {
    return particles_;
  }
  const NodeFields& nodes() const {
    return nodes_;
  }
  const grid::Grid<Dim>& grid() const {
    return grid_;
  }
  grid::BoundaryConditions<Dim>& boundary_conditions() {
    return boundary_;
  }
  const grid::BoundaryConditions<Dim>& boundary_conditions() const {
    return boundary_;
  }
  // The contact law: rigid-body positions, forces and traction records of the last step.
  Contact& contact() {
    return contact_;
  }
  const Contact& contact() const {
    return contact_;
  }
  const model_type& model() const {
    return model_;
  }
  const SimulationParameters<Dim>& parameters() const {
    return parameters_;
  }
  double time() const {
    return time_;
  }
  std::int64_t step_count() const {
    return step_count_;
  }
  int threads() const {
    return threads_;
  }
  // Local damping can change between phases (e.g. damped settling, then undamped cutting).
  void set_damping(double damping) {
    require_in_range("Simulation::set_damping", "damping", damping, 0.0, 1.0, Bounds::left_closed);
    parameters_.damping = damping;
  }
  // For restarts: the clock is part of the checkpointed state.
  void set_clock(double time, std::int64_t step_count) {
    time_ = time;
    step_count_ = step_count;
  }

 private:
  // Where the stencils of this step were evaluated: USL needs no copy, it maps before moving.
  const std::vector<Vec<Dim>>& start_positions() const {
    if constexpr (Scheme::scheme == integrator::Scheme::usl) {
      return particles_.template get<particles::field::Position<Dim>>();
    } else {
      return stencil_positions_;
    }
  }

  void clear_nodes(bool with_forces) {
    std::fill(nodes_.mass.begin(), nodes_.mass.end(), 0.0);
    std::fill(nodes_.momentum.begin(), nodes_.momentum.end(), Vec<Dim>::Zero());
    if (with_forces) std::fill(nodes_.force.begin(), nodes_.force.end(), Vec<Dim>::Zero());
    if constexpr (is_cosserat) {
      std::fill(nodes_.rotational_inertia.begin(), nodes_.rotational_inertia.end(), 0.0);
      std::fill(nodes_.spin_momentum.begin(), nodes_.spin_momentum.end(), 0.0);
      if (with_forces) std::fill(nodes_.moment.begin(), nodes_.moment.end(), 0.0);
    }
  }

  double empty_node_mass() const {
    return parameters_.empty_node_mass_fraction * typical_particle_mass_;
  }

  void grid_velocity_from_momentum() {
    const double empty = empty_node_mass();
    for (Index n = 0; n < grid_.node_count(); ++n) {
      if (nodes_.mass[n] <= empty) {
        nodes_.momentum[n].setZero();
        if constexpr (is_cosserat) nodes_.spin_momentum[n] = 0.0;
        continue;
      }
      nodes_.momentum[n] /= nodes_.mass[n];
      if constexpr (is_cosserat) nodes_.spin_momentum[n] /= nodes_.rotational_inertia[n];
    }
    correct_contact(nodes_.momentum, spin_field(nodes_.spin_momentum), current_dt_,
                    contact::Phase::start_velocity);
    for (Index n = 0; n < grid_.node_count(); ++n) {
      apply_boundary_conditions(n, nodes_.momentum[n]);
      if constexpr (is_cosserat) apply_rotation_conditions(n, nodes_.spin_momentum[n]);
    }
  }

  std::vector<double>* spin_field(std::vector<double>& spin) {
    if constexpr (is_cosserat) {
      return &spin;
    } else {
      return nullptr;
    }
  }

  void correct_contact(std::vector<Vec<Dim>>& velocity, std::vector<double>* spin, double dt,
                       contact::Phase phase) {
    contact::GridView<Dim> view{grid_,
                                nodes_.mass,
                                velocity,
                                empty_node_mass(),
                                dt,
                                time_,
                                phase,
                                spin,
                                contact::node_reach<Kernel>()};
    contact_.correct(view);
  }

  void apply_rotation_conditions(Index node, double& spin) const {
    const auto ijk = grid_.node_ijk(node);
    for (int axis = 0; axis < Dim; ++axis) {
      if ((ijk[axis] == 0 && boundary_.rotation_fixed(2 * axis)) ||
          (ijk[axis] == grid_.nodes(axis) - 1 && boundary_.rotation_fixed(2 * axis + 1))) {
        spin = 0.0;
      }
    }
  }

  // Cosserat particle-to-grid without forces (USF's first map): inertia and spin momentum.
  void map_rotation_to_grid(Index p, const stencil_type& s) {
    const double mp = particles_.template get<particles::field::Mass>()[p];
    const double inertia = mp * particles_.template get<particles::field::MicroInertia>()[p];
    const double spin_momentum =
        inertia * particles_.template get<particles::field::MicroSpin>()[p];
    for (int k = 0; k < stencil_type::size; ++k) {
      nodes_.rotational_inertia[s.node[k]] += s.weight[k] * inertia;
      nodes_.spin_momentum[s.node[k]] += s.weight[k] * spin_momentum;
    }
  }

  void map_moment_to_grid(Index p, const stencil_type& s) {
    const stress_type volume_stress =
        particles_.template get<particles::field::Volume>()[p] *
        particles_.template get<particles::field::Stress<model_type>>()[p];
    for (int k = 0; k < stencil_type::size; ++k) {
      nodes_.moment[s.node[k]] += Continuum::moment_term(volume_stress, s.weight[k], s.gradient[k]);
    }
  }

  // Cosserat grid-to-particle: spin (PIC/FLIP blend, as the velocity) and micro-rotation.
  void update_particle_rotation(Index p, double dt, double flip, double spin_grid,
                                double spin_acceleration) {
    double& spin = particles_.template get<particles::field::MicroSpin>()[p];
    spin = flip * (spin + dt * spin_acceleration) + (1.0 - flip) * spin_grid;
    particles_.template get<particles::field::MicroRotation>()[p] += dt * spin_grid;
  }

  void apply_boundary_conditions(Index node, Vec<Dim>& velocity) const {
    const auto ijk = grid_.node_ijk(node);
    for (int axis = 0; axis < Dim; ++axis) {
      if (ijk[axis] == 0) {
        grid::BoundaryConditions<Dim>::apply(boundary_[2 * axis], axis, false, velocity);
      }
      if (ijk[axis] == grid_.nodes(axis) - 1) {
        grid::BoundaryConditions<Dim>::apply(boundary_[2 * axis + 1], axis, true, velocity);
      }
    }
  }

  // Counting sort of particles into blocks of cells; remembers the stencil positions of the
  // start of the step (MUSL and USF evaluate gradients there).
  void bucket_particles() {
    const auto& x = particles_.template get<particles::field::Position<Dim>>();
    const Index count = particles_.size();
    if constexpr (Scheme::scheme != integrator::Scheme::usl) stencil_positions_ = x;
    // The order is a function of the particles' blocks alone: when no particle changed block
    // (most steps), last step's order is the one a fresh sort would give.
    bool changed = static_cast<Index>(particle_block_.size()) != count;
    particle_block_.resize(count);
    order_.resize(count);
    Index* const particle_block = particle_block_.data();
    for (Index p = 0; p < count; ++p) {
      const Vec<Dim> xi = grid_.to_cell_units(x[p]);
      Index block = 0;
      for (int d = Dim - 1; d >= 0; --d) {
        Index b = static_cast<Index>(xi[d]) / detail::ParticleBlocks::block_cells(d);
        b = std::clamp<Index>(b, 0, blocks_per_axis_[d] - 1);
        block = block * blocks_per_axis_[d] + b;
      }
      changed = changed || particle_block[p] != block;
      particle_block[p] = block;
    }
    if (!changed) return;
    std::fill(block_start_.begin(), block_start_.end(), 0);
    for (Index p = 0; p < count; ++p) ++block_start_[particle_block[p] + 1];
    for (std::size_t b = 1; b < block_start_.size(); ++b) block_start_[b] += block_start_[b - 1];
    block_fill_.assign(block_start_.begin(), block_start_.end() - 1);
    for (Index p = 0; p < count; ++p) order_[block_fill_[particle_block_[p]]++] = p;
  }

  // Runs f(p) over all particles; blocks of one colour run in parallel, colours in order,
  // particles within a block in index order: the sum at every node is taken in the same
  // order whatever the thread count.
  template <class F>
  void for_each_particle_coloured(F&& f) {
    const Index* start = block_start_.data();
    const Index* order = order_.data();
    for (const auto& blocks : colour_blocks_) {
      const Index block_count = static_cast<Index>(blocks.size());
      const Index* block_list = blocks.data();
      COSMPM_OMP_PARALLEL_FOR(threads_, particles_.size())
      for (Index b = 0; b < block_count; ++b) {
        const Index block = block_list[b];
        for (Index i = start[block]; i < start[block + 1]; ++i) f(order[i]);
      }
    }
  }

  int block_colour(Index block) const {
    int colour = 0;
    for (int d = 0; d < Dim; ++d) {
      colour |= static_cast<int>((block % blocks_per_axis_[d]) & 1) << d;
      block /= blocks_per_axis_[d];
    }
    return colour;
  }

  grid::Grid<Dim> grid_;
  model_type model_;
  SimulationParameters<Dim> parameters_;
  grid::BoundaryConditions<Dim> boundary_;
  Contact contact_;
  double current_dt_ = 0.0;
  store_type particles_;
  NodeFields nodes_;
  int threads_ = 1;
  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  double typical_particle_mass_ = 0.0;
  double max_density_ = 0.0;
  std::array<Index, Dim> blocks_per_axis_{};
  std::vector<Index> block_start_;
  std::array<std::vector<Index>, (1 << Dim)> colour_blocks_;  // the blocks of each colour
  std::vector<Index> block_fill_;
  std::vector<Index> particle_block_;
  std::vector<Index> order_;
  std::vector<Vec<Dim>> stencil_positions_;
  std::vector<rates_type> particle_rates_;  // MUSL/USF: between rates and stress update
};

}  // namespace cosmpm
