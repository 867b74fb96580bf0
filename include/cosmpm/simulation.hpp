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
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/LU>  // determinant

#include "cosmpm/contact/single_field.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/integrator/schemes.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/separable.hpp"

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
  using stencil_type = shape::SeparableStencil<Dim, Kernel>;
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
    const auto scatter = [&] {
      return with_forces ? scatter_particles<true>() : scatter_particles<false>();
    };
    if (!scatter()) {
      // Particles were moved outside the engine since the last step (e.g. by the user):
      // the blocks no longer keep same-colour scatters apart. Sort again and redo.
      assign_blocks();
      sort_into_blocks();
      require(scatter(), "Simulation::map_to_grid: particle blocks inconsistent after sorting");
    }
    const Index count = grid_.node_count();
    const Index size = with_forces ? ScatterRecord::all : ScatterRecord::weighted;  // per node
    const double* const scattered = scatter_.data();
    for (Index n = 0; n < count; ++n) {
      const double* const record = scattered + n * size;
      nodes_.mass[n] = record[ScatterRecord::mass];
      for (int d = 0; d < Dim; ++d) {
        nodes_.momentum[n][d] = record[ScatterRecord::momentum + d];
        if (with_forces) nodes_.force[n][d] = record[ScatterRecord::force + d];
      }
      if constexpr (is_cosserat) {
        nodes_.rotational_inertia[n] = record[ScatterRecord::inertia];
        nodes_.spin_momentum[n] = record[ScatterRecord::spin_momentum];
        if (with_forces) nodes_.moment[n] = record[ScatterRecord::moment];
      }
    }
  }

  // USF only: forces after the stress update (mass and momentum are already on the grid).
  void map_forces_to_grid() {
    const Index count = grid_.node_count();
    for (Index n = 0; n < count; ++n) {
      // grid_velocity_from_momentum turned the momenta into velocities; restore them.
      nodes_.momentum[n] *= nodes_.mass[n];
      if constexpr (is_cosserat) nodes_.spin_momentum[n] *= nodes_.rotational_inertia[n];
    }
    constexpr int forces = Dim + (is_cosserat ? 1 : 0);
    std::fill(scatter_.begin(), scatter_.begin() + forces * count, 0.0);
    require_start_stencils("map_forces_to_grid");
    const auto& mass = particles_.template get<particles::field::Mass>();
    const auto& vol = particles_.template get<particles::field::Volume>();
    const auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    const Vec<Dim> gravity = parameters_.gravity;
    const shape::StencilGrid<Dim> stencil_grid(grid_);
    for_each_particle_coloured([&](Index p) {
      stencil_type s;
      start_stencil(p, stencil_grid, s);
      std::array<double, forces> weighted;
      std::array<std::array<double, Dim>, forces> by_gradient;
      force_contribution(mass[p], vol[p], stress[p], gravity, weighted.data(), by_gradient);
      shape::scatter<0>(s, scatter_.data(), weighted, by_gradient);
    });
    for (Index n = 0; n < count; ++n) {
      for (int d = 0; d < Dim; ++d) nodes_.force[n][d] = scatter_[n * forces + d];
      if constexpr (is_cosserat) nodes_.moment[n] = scatter_[n * forces + Dim];
    }
  }

  // Stage 2: nodal velocity and acceleration from momentum and force (lumped mass), local
  // damping, boundary conditions. Afterwards nodes_.momentum holds the start velocity v^t,
  // nodes_.velocity the end velocity v^{t+dt} and nodes_.acceleration (v^{t+dt} - v^t) / dt.
  void update_grid(double dt) {
    const double empty = empty_node_mass();
    const double damping = parameters_.damping;
    const Index count = grid_.node_count();
    COSMPM_OMP_PARALLEL_FOR(threads_, count, 512)
    for (Index n = 0; n < count; ++n) {
      const double m = nodes_.mass[n];
      if (m <= empty) {
        nodes_.momentum[n].setZero();
        nodes_.velocity[n].setZero();
        if constexpr (is_cosserat) nodes_.spin_momentum[n] = nodes_.spin[n] = 0.0;
        continue;
      }
      const double inverse_mass = 1.0 / m;  // one division per node instead of 2 Dim
      const Vec<Dim> v_start = nodes_.momentum[n] * inverse_mass;
      Vec<Dim> force = nodes_.force[n];
      if (damping > 0.0) {
        // Cundall: oppose the motion with a fraction of the unbalanced force, per component.
        for (int d = 0; d < Dim; ++d) {
          const double sign = v_start[d] > 0.0 ? 1.0 : (v_start[d] < 0.0 ? -1.0 : 0.0);
          force[d] -= damping * std::abs(force[d]) * sign;
        }
      }
      nodes_.momentum[n] = v_start;
      nodes_.velocity[n] = v_start + (dt * inverse_mass) * force;
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
    apply_boundary_conditions(nodes_.momentum);
    apply_boundary_conditions(nodes_.velocity);
    if constexpr (is_cosserat) {
      apply_rotation_conditions(nodes_.spin_momentum);
      apply_rotation_conditions(nodes_.spin);
    }
    // The grid-to-particle pass reads each node's velocity and acceleration as one record.
    gather_.resize(static_cast<std::size_t>(GatherRecord::all * count));
    double* const gathered = gather_.data();
    const double inverse_dt = 1.0 / dt;
    COSMPM_OMP_PARALLEL_FOR(threads_, count, 512)
    for (Index n = 0; n < count; ++n) {
      nodes_.acceleration[n] = (nodes_.velocity[n] - nodes_.momentum[n]) * inverse_dt;
      double* const record = gathered + n * GatherRecord::all;
      for (int d = 0; d < Dim; ++d) {
        record[GatherRecord::velocity + d] = nodes_.velocity[n][d];
        record[GatherRecord::acceleration + d] = nodes_.acceleration[n][d];
      }
      if constexpr (is_cosserat) {
        nodes_.spin_acceleration[n] = (nodes_.spin[n] - nodes_.spin_momentum[n]) * inverse_dt;
        record[GatherRecord::spin] = nodes_.spin[n];
        record[GatherRecord::spin_acceleration] = nodes_.spin_acceleration[n];
      }
    }
  }

  // Stage 3: particle velocity (PIC/FLIP blend) and position from the grid.
  // USL fuses the velocity gradient and the stress update into this pass: one sweep over the
  // particles instead of three, at the same (start-of-step) stencil.
  void map_to_particles(double dt, bool with_stress_update = false) {
    if (with_stress_update) {
      dispatch_flip<true>(dt);
    } else {
      dispatch_flip<false>(dt);
    }
  }

 private:
  // Pure FLIP (the default) is its own instantiation: its update needs no blend.
  template <bool with_stress_update>
  void dispatch_flip(double dt) {
    if (parameters_.flip_fraction == 1.0) {
      map_to_particles_impl<with_stress_update, true>(dt);
    } else {
      map_to_particles_impl<with_stress_update, false>(dt);
    }
  }

  template <bool with_stress_update, bool pure_flip>
  void map_to_particles_impl(double dt) {
    require_start_stencils("map_to_particles");
    const Index count = particles_.size();
    const ParticleMapPass pass{dt, parameters_.flip_fraction, gather_.data(),
                               shape::StencilGrid<Dim>(grid_)};
    Index first_outside = count;
    Index first_bad = count;
    Index first_moved = count;
    // pack_width particles at a time, then the rest one by one.
    constexpr int W = pack_width;
    const Index packs = count / W;
    COSMPM_OMP_PARALLEL_FOR_MIN(threads_, count, 128, first_outside, first_bad, first_moved)
    for (Index b = 0; b < packs; ++b) {
      map_from_grid<W, with_stress_update, pure_flip>(b * W, pass, first_outside, first_bad,
                                                      first_moved);
    }
    for (Index p = packs * W; p < count; ++p) {
      map_from_grid<1, with_stress_update, pure_flip>(p, pass, first_outside, first_bad,
                                                      first_moved);
    }
    if (first_moved < count) blocks_changed_ = true;
    // A particle that left the grid usually also tore its neighbourhood: name the cause.
    if (first_outside < count) throw_outside(first_outside);
    if (first_bad < count) throw_unstable_stress(first_bad);
  }

  // What every particle of a grid-to-particle map shares.
  struct ParticleMapPass {
    double dt;
    double flip;
    const double* records;  // gather_
    shape::StencilGrid<Dim> stencil_grid;
  };

  // Grid to particles p, ..., p + W - 1: stencils, node sums, velocity, position and
  // deformation run side by side in packs; the constitutive update too for models that update
  // packs (packed_stress_update), per particle for the others.
  template <int W, bool with_stress_update, bool pure_flip>
  COSMPM_ALWAYS_INLINE void map_from_grid(Index p, const ParticleMapPass& pass,
                                          Index& first_outside, Index& first_bad,
                                          Index& first_moved) {
    using P = Pack<W>;
    auto& x = particles_.template get<particles::field::Position<Dim>>();
    auto& v = particles_.template get<particles::field::Velocity<Dim>>();
    const auto& half = particles_.template get<particles::field::HalfWidth<Dim>>();
    const auto& start = stencil_cells_;
    const double dt = pass.dt;
    const double flip = pass.flip;
    // Velocity (and Cosserat spin) with gradients when the stress is updated here, then the
    // accelerations.
    constexpr int with_gradient = with_stress_update ? GatherRecord::with_gradient : 0;
    shape::PackedStencil<Dim, Kernel, W> s;
    s.compute_from_cell_units(
        pass.stencil_grid, [&](int l) -> const Vec<Dim>& { return start[p + l]; },
        [&](int l) -> const Vec<Dim>& { return half[p + l]; });
    const auto grid_values = shape::gather<GatherRecord::all, with_gradient>(s, pass.records);
    // New positions in cell units, for the box test and the particles' blocks.
    std::array<P, Dim> xi;
    for (int d = 0; d < Dim; ++d) {
      const P v_grid = grid_values.value[GatherRecord::velocity + d];
      const P a_grid = grid_values.value[GatherRecord::acceleration + d];
      const P v_old = make_pack<W>([&](int l) { return v[p + l][d]; });
      const P x_old = make_pack<W>([&](int l) { return x[p + l][d]; });
      P v_new = v_old + dt * a_grid;
      if constexpr (!pure_flip) v_new = flip * v_new + (1.0 - flip) * v_grid;
      const P x_new = x_old + dt * v_grid;
      xi[d] = (x_new - pass.stencil_grid.origin[d]) * pass.stencil_grid.inverse_cell_size[d];
      for (int l = 0; l < W; ++l) {
        v[p + l][d] = lane<W>(v_new, l);
        x[p + l][d] = lane<W>(x_new, l);
      }
    }
    [[maybe_unused]] P volume_ratio;
    [[maybe_unused]] std::array<std::array<P, Dim>, Dim> L;
    [[maybe_unused]] P stress_sum;  // the packed stress update's finiteness check
    if constexpr (with_stress_update) {
      for (int i = 0; i < Dim; ++i) L[i] = grid_values.gradient[GatherRecord::velocity + i];
      volume_ratio = update_deformation<W>(p, L, dt);
      if constexpr (packed_stress_update<W>) stress_sum = update_stress_packed<W>(p, L, dt);
    }
    // The packed update checks all lanes with one comparison: s * 0 is 0 for a finite s and
    // NaN otherwise, so s * 0 + J > 0 holds exactly when s is finite and J > 0.
    [[maybe_unused]] bool pack_sound = true;
    if constexpr (with_stress_update && packed_stress_update<W>) {
      pack_sound = all_lanes<W>(stress_sum * 0.0 + volume_ratio > 0.0);
    }
    // 0 < xi < last exactly when xi (last - xi) > 0 (false for NaN): one comparison per axis
    // for the whole pack.
    bool all_inside = true;
    for (int d = 0; d < Dim; ++d) {
      all_inside &= all_lanes<W>(xi[d] * (pass.stencil_grid.last[d] - xi[d]) > 0.0);
    }
    for (int l = 0; l < W; ++l) {
      const Index q = p + l;
      if constexpr (is_cosserat) {
        update_particle_rotation(q, dt, flip, lane<W>(grid_values.value[GatherRecord::spin], l),
                                 lane<W>(grid_values.value[GatherRecord::spin_acceleration], l));
      }
      if constexpr (with_stress_update) {
        auto& velocity_gradient =
            particles_.template get<particles::field::VelocityGradient<Dim>>()[q];
        if constexpr (packed_stress_update<W>) {
          for (int i = 0; i < Dim; ++i) {
            for (int j = 0; j < Dim; ++j) velocity_gradient(i, j) = lane<W>(L[i][j], l);
          }
          if (!pack_sound && !(std::isfinite(lane<W>(stress_sum, l)) &&
                               lane<W>(volume_ratio, l) > 0.0)) [[unlikely]]
            record_first(first_bad, q);
        } else {
          const rates_type rates = rates_from<W>(grid_values, l);
          store_components(velocity_gradient, rates.velocity_gradient);
          const bool finite = update_constitutive(q, rates, dt);
          if (!(finite && lane<W>(volume_ratio, l) > 0.0)) [[unlikely]]
            record_first(first_bad, q);
        }
      }
      bool inside = all_inside;
      if (!all_inside) [[unlikely]] {
        for (int d = 0; d < Dim; ++d) {
          inside = inside && pass.stencil_grid.inside(d, lane<W>(xi[d], l));
        }
      }
      if (!inside) [[unlikely]] {
        record_first(first_outside, q);
        continue;
      }
      // Inside, xi < cells, so the floor is already what cell_of gives (its clamp to the last
      // cell cost 13 instructions per particle here, from reloading the node counts).
      std::array<Index, Dim> cell;
      for (int d = 0; d < Dim; ++d) cell[d] = static_cast<Index>(lane<W>(xi[d], l));
      if (const Index block = block_of_cell(cell); block != particle_block_[q]) {
        particle_block_[q] = block;  // sorted again at the next particle-to-grid map
        record_first(first_moved, q);
      }
    }
  }

  // Whether the stress update of the grid-to-particle loop runs on packs of W particles: for
  // models that update packs of components (Continuum::updates_values, e.g. LinearElastic).
  template <int W>
  static constexpr bool packed_stress_update = [] {
    if constexpr (is_cosserat || Dim != 2) {
      return false;
    } else {
      return Continuum::template updates_values<Pack<W>>;
    }
  }();

  // The stress update of particles p, ..., p + W - 1 on packs, with their velocity gradient L;
  // returns the sum of each new stress's components (non-finite when one is).
  template <int W>
  COSMPM_ALWAYS_INLINE Pack<W> update_stress_packed(
      Index p, const std::array<std::array<Pack<W>, Dim>, Dim>& L, double dt) {
    using P = Pack<W>;
    auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    auto& strain = particles_.template get<particles::field::Strain<model_type>>();
    static constexpr std::array<int, 3> strain_components{0, 1, 3};  // zz stays (plane strain)
    std::array<P, 4> s;
    std::array<P, 3> e;
    for (int c = 0; c < 4; ++c) s[c] = make_pack<W>([&](int l) { return stress[p + l][c]; });
    for (int k = 0; k < 3; ++k) {
      e[k] = make_pack<W>([&](int l) { return strain[p + l][strain_components[k]]; });
    }
    Continuum::update_stress_values(model_, L, dt, s, e);
    for (int l = 0; l < W; ++l) {
      for (int c = 0; c < 4; ++c) stress[p + l][c] = lane<W>(s[c], l);
      for (int k = 0; k < 3; ++k) strain[p + l][strain_components[k]] = lane<W>(e[k], l);
    }
    return (s[0] + s[1]) + (s[2] + s[3]);
  }

  // F <- (I + dt L) F and V = det(F) V0 for particles p, ..., p + W - 1; returns det(F).
  template <int W>
  COSMPM_ALWAYS_INLINE Pack<W> update_deformation(
      Index p, const std::array<std::array<Pack<W>, Dim>, Dim>& L, double dt) {
    using P = Pack<W>;
    auto& F = particles_.template get<particles::field::DeformationGradient<Dim>>();
    std::array<std::array<P, Dim>, Dim> old, updated;
    for (int i = 0; i < Dim; ++i) {
      for (int j = 0; j < Dim; ++j) old[i][j] = make_pack<W>([&](int l) { return F[p + l](i, j); });
    }
    for (int i = 0; i < Dim; ++i) {
      for (int j = 0; j < Dim; ++j) {
        P lf = L[i][0] * old[0][j];
        for (int k = 1; k < Dim; ++k) lf += L[i][k] * old[k][j];
        updated[i][j] = old[i][j] + dt * lf;
        for (int l = 0; l < W; ++l) F[p + l](i, j) = lane<W>(updated[i][j], l);
      }
    }
    const P J = determinant(updated);
    const auto& initial_volume = particles_.template get<particles::field::InitialVolume>();
    auto& volume = particles_.template get<particles::field::Volume>();
    const P V = J * make_pack<W>([&](int l) { return initial_volume[p + l]; });
    for (int l = 0; l < W; ++l) volume[p + l] = lane<W>(V, l);
    return J;
  }

  template <class T>
  static T determinant(const std::array<std::array<T, Dim>, Dim>& a) {
    static_assert(Dim == 2 || Dim == 3, "Simulation: determinant for 2D and 3D only");
    if constexpr (Dim == 2) {
      return a[0][0] * a[1][1] - a[0][1] * a[1][0];
    } else {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
  }

  // The constitutive update of one particle; false if the stress came out non-finite.
  COSMPM_ALWAYS_INLINE bool update_constitutive(Index q, const rates_type& rates, double dt) {
    auto& stress = particles_.template get<particles::field::Stress<model_type>>()[q];
    Continuum::update_stress(
        model_, rates, dt, stress,
        particles_.template get<particles::field::MaterialState<model_type>>()[q],
        particles_.template get<particles::field::Strain<model_type>>()[q]);
    // A non-finite component makes the sum non-finite (finite stresses near 1e308 that would
    // overflow it do not occur in soil).
    return std::isfinite(stress.sum());
  }

  // Particle l's rates from a gather whose first fields carry gradients.
  template <int W, class GridValues>
  static rates_type rates_from(const GridValues& grid_values, int l) {
    rates_type rates;
    for (int i = 0; i < Dim; ++i) {
      for (int j = 0; j < Dim; ++j) {
        rates.velocity_gradient(i, j) =
            lane<W>(grid_values.gradient[GatherRecord::velocity + i][j], l);
      }
    }
    if constexpr (is_cosserat) {
      rates.spin = lane<W>(grid_values.value[GatherRecord::spin], l);
      for (int d = 0; d < Dim; ++d) {
        rates.spin_gradient[d] = lane<W>(grid_values.gradient[GatherRecord::spin][d], l);
      }
    }
    return rates;
  }

  // to = from, component by component: Eigen's packet stores are may-alias vector types,
  // after which the compiler reloads every array pointer in the loop.
  template <class Matrix>
  COSMPM_ALWAYS_INLINE static void store_components(Matrix& to, const Matrix& from) {
    for (Index i = 0; i < Matrix::SizeAtCompileTime; ++i) to.data()[i] = from.data()[i];
  }

  // Keeps the lowest index, so messages do not depend on the thread count. `first` is the
  // thread's own copy (COSMPM_OMP_PARALLEL_FOR_MIN combines the copies).
  static void record_first(Index& first, Index p) { first = std::min(first, p); }

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
    const Index count = grid_.node_count();
    require_start_stencils("remap_momentum");
    constexpr int momenta = Dim + (is_cosserat ? 1 : 0);
    std::fill(scatter_.begin(), scatter_.begin() + momenta * count, 0.0);
    const shape::StencilGrid<Dim> stencil_grid(grid_);
    for_each_particle_coloured([&](Index p) {
      stencil_type s;
      start_stencil(p, stencil_grid, s);
      std::array<double, momenta> weighted;
      for (int d = 0; d < Dim; ++d) weighted[d] = mass[p] * v[p][d];
      if constexpr (is_cosserat) {
        weighted[Dim] = mass[p] * particles_.template get<particles::field::MicroInertia>()[p] *
                        particles_.template get<particles::field::MicroSpin>()[p];
      }
      shape::scatter<momenta>(s, scatter_.data(), weighted, {});
    });
    const double empty = empty_node_mass();
    for (Index n = 0; n < count; ++n) {
      if (nodes_.mass[n] <= empty) {
        nodes_.velocity[n].setZero();
        if constexpr (is_cosserat) nodes_.spin[n] = 0.0;
        continue;
      }
      for (int d = 0; d < Dim; ++d) {
        nodes_.velocity[n][d] = scatter_[n * momenta + d] / nodes_.mass[n];
      }
      if constexpr (is_cosserat) {
        nodes_.spin[n] = scatter_[n * momenta + Dim] / nodes_.rotational_inertia[n];
      }
    }
    correct_contact(nodes_.velocity, spin_field(nodes_.spin), current_dt_,
                    contact::Phase::remapped_velocity);
    apply_boundary_conditions(nodes_.velocity);
    if constexpr (is_cosserat) apply_rotation_conditions(nodes_.spin);
  }

  // Stage 4a: particle rates (velocity gradient; Cosserat: spin and its gradient) from a
  // nodal field, at the stencils of the start of the step. The spin field is ignored by a
  // classical continuum.
  void velocity_gradient_from_grid(const std::vector<Vec<Dim>>& node_velocity,
                                   const std::vector<double>& node_spin = {}) {
    const Index nodes = grid_.node_count();
    require(static_cast<Index>(node_velocity.size()) == nodes &&
                (!is_cosserat || static_cast<Index>(node_spin.size()) == nodes),
            "Simulation::velocity_gradient_from_grid: a nodal field does not match the grid's " +
                std::to_string(nodes) + " nodes");
    gather_.resize(static_cast<std::size_t>(GatherRecord::all * nodes));
    constexpr int size = GatherRecord::with_gradient;  // per node: velocity (, spin)
    for (Index n = 0; n < nodes; ++n) {
      for (int d = 0; d < Dim; ++d)
        gather_[n * size + GatherRecord::velocity + d] = node_velocity[n][d];
      if constexpr (is_cosserat) gather_[n * size + GatherRecord::spin] = node_spin[n];
    }
    const double* const records = gather_.data();
    const shape::StencilGrid<Dim> stencil_grid(grid_);
    require_start_stencils("velocity_gradient_from_grid");
    auto& L = particles_.template get<particles::field::VelocityGradient<Dim>>();
    const Index count = particles_.size();
    particle_rates_.resize(count);
    COSMPM_OMP_PARALLEL_FOR(threads_, count, 256)
    for (Index p = 0; p < count; ++p) {
      stencil_type s;
      start_stencil(p, stencil_grid, s);
      const rates_type rates = rates_from<1>(shape::gather<size, size>(s, records), 0);
      L[p] = rates.velocity_gradient;
      particle_rates_[p] = rates;
    }
  }

  // Stage 4b: constitutive update, deformation gradient and volume.
  void update_stress(double dt) {
    require(static_cast<Index>(particle_rates_.size()) == particles_.size(),
            "Simulation::update_stress: call velocity_gradient_from_grid first");
    using strain_type = typename model_type::strain_type;
    const Index count = particles_.size();
    auto& stress = particles_.template get<particles::field::Stress<model_type>>();
    auto& state = particles_.template get<particles::field::MaterialState<model_type>>();
    auto& strain = particles_.template get<particles::field::Strain<model_type>>();
    // The model takes the particles in runs of fixed length, one call each
    // (material::update_batch): a model with a batched return (CosseratDruckerPrager) is
    // faster so, and the runs do not depend on the thread count.
    constexpr Index run = 64;
    const Index runs = (count + run - 1) / run;
    Index first_bad = count;
    COSMPM_OMP_PARALLEL_FOR_MIN(threads_, count, 4, first_bad)
    for (Index r = 0; r < runs; ++r) {
      const Index begin = r * run;
      const Index size = std::min(run, count - begin);
      const auto points = static_cast<std::size_t>(size);
      std::array<strain_type, run> increment;
      for (Index k = 0; k < size; ++k) {
        increment[k] =
            Continuum::rotate_and_increment(particle_rates_[begin + k], dt, stress[begin + k]);
      }
      material::update_batch(model_, std::span(stress.data() + begin, points),
                             std::span(state.data() + begin, points),
                             std::span<const strain_type>(increment.data(), points));
      for (Index k = 0; k < size; ++k) {
        const Index p = begin + k;
        Continuum::accumulate_strain(strain[p], increment[k]);
        std::array<std::array<double, Dim>, Dim> L;
        for (int i = 0; i < Dim; ++i) {
          for (int j = 0; j < Dim; ++j) L[i][j] = particle_rates_[p].velocity_gradient(i, j);
        }
        const double volume_ratio = update_deformation<1>(p, L, dt);
        if (!(std::isfinite(stress[p].sum()) && volume_ratio > 0.0)) record_first(first_bad, p);
      }
    }
    if (first_bad < count) throw_unstable_stress(first_bad);
  }

  // --- access -----------------------------------------------------------------------------
  store_type& particles() { return particles_; }
  const store_type& particles() const { return particles_; }
  const NodeFields& nodes() const { return nodes_; }
  const grid::Grid<Dim>& grid() const { return grid_; }
  grid::BoundaryConditions<Dim>& boundary_conditions() { return boundary_; }
  const grid::BoundaryConditions<Dim>& boundary_conditions() const { return boundary_; }
  // The contact law: rigid-body positions, forces and traction records of the last step.
  Contact& contact() { return contact_; }
  const Contact& contact() const { return contact_; }
  const model_type& model() const { return model_; }
  const SimulationParameters<Dim>& parameters() const { return parameters_; }
  double time() const { return time_; }
  std::int64_t step_count() const { return step_count_; }
  int threads() const { return threads_; }
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
  // The stencil of particle p at the start of the step (the last map_to_grid).
  COSMPM_ALWAYS_INLINE void start_stencil(Index p, const shape::StencilGrid<Dim>& stencil_grid,
                                          stencil_type& s) const {
    s.compute_from_cell_units(stencil_grid, stencil_cells_[p],
                              particles_.template get<particles::field::HalfWidth<Dim>>()[p]);
  }

  void require_start_stencils(const char* where) const {
    require(static_cast<Index>(stencil_cells_.size()) == particles_.size(),
            std::string("Simulation::") + where +
                ": no stencils for this step's particles; call map_to_grid first");
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
    apply_boundary_conditions(nodes_.momentum);
    if constexpr (is_cosserat) apply_rotation_conditions(nodes_.spin_momentum);
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

  // Zero spin on the faces whose rotation is fixed.
  void apply_rotation_conditions(std::vector<double>& spin) const {
    for (int face = 0; face < 2 * Dim; ++face) {
      if (!boundary_.rotation_fixed(face)) continue;
      for_each_face_node(face / 2, face % 2 == 1, [&](Index n) { spin[n] = 0.0; });
    }
  }

  // Cosserat grid-to-particle: spin (PIC/FLIP blend, as the velocity) and micro-rotation.
  void update_particle_rotation(Index p, double dt, double flip, double spin_grid,
                                double spin_acceleration) {
    double& spin = particles_.template get<particles::field::MicroSpin>()[p];
    spin = flip * (spin + dt * spin_acceleration) + (1.0 - flip) * spin_grid;
    particles_.template get<particles::field::MicroRotation>()[p] += dt * spin_grid;
  }

  // The face conditions on a nodal velocity field, face by face in face order, so a node on
  // several faces (a corner) takes them in the order of the faces.
  void apply_boundary_conditions(std::vector<Vec<Dim>>& velocity) const {
    for (int face = 0; face < 2 * Dim; ++face) {
      const auto& condition = boundary_[face];
      if (condition.kind == grid::BoundaryKind::free) continue;
      const int axis = face / 2;
      const bool upper = face % 2 == 1;
      for_each_face_node(axis, upper, [&](Index n) {
        grid::BoundaryConditions<Dim>::apply(condition, axis, upper, velocity[n]);
      });
    }
  }

  // f(n) for every node n on the lower (upper = false) or upper face normal to `axis`.
  template <class F>
  void for_each_face_node(int axis, bool upper, F&& f) const {
    std::array<Index, Dim> ijk{};
    ijk[axis] = upper ? grid_.nodes(axis) - 1 : 0;
    Index total = 1;
    for (int d = 0; d < Dim; ++d) {
      if (d != axis) total *= grid_.nodes(d);
    }
    for (Index k = 0; k < total; ++k) {
      Index rest = k;
      for (int d = 0; d < Dim; ++d) {
        if (d == axis) continue;
        ijk[d] = rest % grid_.nodes(d);
        rest /= grid_.nodes(d);
      }
      f(grid_.node_index(ijk));
    }
  }

  // Components of the node records the transfers work on (shape/separable.hpp: C doubles per
  // node). A particle scatters weighted-only components first, then those that also take a
  // gradient term.
  struct ScatterRecord {
    static constexpr int cosserat = is_cosserat ? 1 : 0;
    static constexpr int mass = 0;
    static constexpr int momentum = 1;  // Dim components
    static constexpr int inertia = 1 + Dim;
    static constexpr int spin_momentum = 2 + Dim;
    static constexpr int weighted = 1 + Dim + 2 * cosserat;
    static constexpr int force = weighted;  // Dim components
    static constexpr int moment = weighted + Dim;
    static constexpr int all = weighted + Dim + cosserat;
  };
  // Grid-to-particle: the fields with gradients (velocity, spin) first, then accelerations.
  struct GatherRecord {
    static constexpr int cosserat = is_cosserat ? 1 : 0;
    static constexpr int velocity = 0;  // Dim components
    static constexpr int spin = Dim;
    static constexpr int with_gradient = Dim + cosserat;
    static constexpr int acceleration = with_gradient;  // Dim components
    static constexpr int spin_acceleration = with_gradient + Dim;
    static constexpr int all = 2 * with_gradient;
  };

  // The particle-to-grid pass of map_to_grid into scatter_. False (and nothing usable) if a
  // particle no longer lies in the block it was sorted into.
  template <bool with_forces>
  bool scatter_particles() {
    constexpr int W = ScatterRecord::weighted;
    constexpr int C = with_forces ? ScatterRecord::all : W;
    const Index nodes = grid_.node_count();
    scatter_.resize(static_cast<std::size_t>(ScatterRecord::all * nodes));
    std::fill(scatter_.begin(), scatter_.begin() + C * nodes, 0.0);
    // Array addresses, captured by value below: the loop runs short of registers, and a
    // pointer in the closure is one load where a captured vector is two.
    const auto* const x = particles_.template get<particles::field::Position<Dim>>().data();
    const auto* const v = particles_.template get<particles::field::Velocity<Dim>>().data();
    const double* const mass = particles_.template get<particles::field::Mass>().data();
    const double* const vol = particles_.template get<particles::field::Volume>().data();
    const auto* const half = particles_.template get<particles::field::HalfWidth<Dim>>().data();
    const auto* const stress =
        particles_.template get<particles::field::Stress<model_type>>().data();
    const Index* const particle_block = particle_block_.data();
    const Vec<Dim> gravity = parameters_.gravity;
    const Index count = particles_.size();
    const shape::StencilGrid<Dim> stencil_grid(grid_);
    stencil_cells_.resize(count);
    Vec<Dim>* const stencil_cells = stencil_cells_.data();
    double* const records = scatter_.data();
    // Named outside the lambda: GCC 12 fails on C - W inside it.
    using Weighted = std::array<double, C>;
    using ByGradient = std::array<std::array<double, Dim>, C - W>;
    // Inlined into the block loop.
    const auto [first_invalid, first_misplaced] =
        for_each_particle_coloured([&, x, v, mass, vol, half, stress, particle_block, stencil_cells,
                                    records](Index p) COSMPM_INLINE_LAMBDA {
          stencil_type s;
          // Reported after the (possibly parallel) loop.
          if (!s.try_compute(stencil_grid, x[p], half[p])) [[unlikely]]
            return Visit::invalid_stencil;
          if (block_of_cell(s.cell) != particle_block[p]) [[unlikely]]
            return Visit::misplaced;
          store_components(stencil_cells[p], s.position_in_cells);
          const double mp = mass[p];
          Weighted weighted;
          ByGradient by_gradient;
          weighted[ScatterRecord::mass] = mp;
          for (int d = 0; d < Dim; ++d) weighted[ScatterRecord::momentum + d] = mp * v[p][d];
          if constexpr (is_cosserat) {
            const double inertia =
                mp * particles_.template get<particles::field::MicroInertia>()[p];
            weighted[ScatterRecord::inertia] = inertia;
            weighted[ScatterRecord::spin_momentum] =
                inertia * particles_.template get<particles::field::MicroSpin>()[p];
          }
          if constexpr (with_forces) {
            force_contribution(mp, vol[p], stress[p], gravity,
                               weighted.data() + ScatterRecord::force, by_gradient);
          }
          shape::scatter<W>(s, records, weighted, by_gradient);
          return Visit::done;
        });
    if (first_invalid < count) {
      stencil_type s;
      s.compute(stencil_grid, x[first_invalid], half[first_invalid]);  // throws, naming it
    }
    return first_misplaced == count;
  }

  // A particle's force (and Cosserat moment) on the nodes as N weighted + grad N . by_gradient:
  // weight m g and the stress divergence (Continuum::internal_force_coefficients), then the
  // moment. weighted points at the force's first component.
  template <std::size_t F>
  static void force_contribution(double mass, double volume, const stress_type& stress,
                                 const Vec<Dim>& gravity, double* weighted,
                                 std::array<std::array<double, Dim>, F>& by_gradient) {
    static_assert(F == Dim + (is_cosserat ? 1 : 0), "force and moment components");
    const auto b = Continuum::internal_force_coefficients(stress, volume);
    for (int d = 0; d < Dim; ++d) {
      weighted[d] = mass * gravity[d];
      for (int e = 0; e < Dim; ++e) by_gradient[d][e] = b[d][e];
    }
    if constexpr (is_cosserat) {
      Continuum::moment_coefficients(stress, volume, weighted[Dim], by_gradient[Dim]);
    }
  }

  // The block of cells a particle belongs to, from the cell that holds it.
  Index block_of_cell(const std::array<Index, Dim>& cell) const {
    Index block = 0;
    for (int d = Dim - 1; d >= 0; --d) {
      // cell >= 0: unsigned division is a shift
      const auto b = static_cast<std::size_t>(cell[d]) /
                     static_cast<std::size_t>(detail::ParticleBlocks::block_cells(d));
      block = block * blocks_per_axis_[d] + static_cast<Index>(b);
    }
    return block;
  }

  // Sorts particles into blocks when any changed block. The engine notes the particles it
  // moves (map_to_particles); the scatter finds any other move and sorts again.
  void bucket_particles() {
    if (static_cast<Index>(particle_block_.size()) != particles_.size()) {
      assign_blocks();
    } else if (!blocks_changed_) {
      return;
    }
    sort_into_blocks();
  }

  // Every particle's block from its position (a particle outside the grid is reported by
  // the stencil that follows; here it goes to the nearest block).
  void assign_blocks() {
    const auto& x = particles_.template get<particles::field::Position<Dim>>();
    const Index count = particles_.size();
    const shape::StencilGrid<Dim> stencil_grid(grid_);
    particle_block_.resize(count);
    for (Index p = 0; p < count; ++p) {
      std::array<Index, Dim> cell;
      for (int d = 0; d < Dim; ++d) {
        const double xi = (x[p][d] - stencil_grid.origin[d]) * stencil_grid.inverse_cell_size[d];
        // Clamped into the grid (NaN to 0): the stencil reports a particle outside.
        const double clamped =
            xi >= 0.0 ? (xi < stencil_grid.last[d] ? xi : stencil_grid.last[d]) : 0.0;
        cell[d] = stencil_grid.cell_of(d, clamped);
      }
      particle_block_[p] = block_of_cell(cell);
    }
  }

  // Counting sort by block; within a block particles keep index order, so the order (and with
  // it every nodal sum) is a function of the blocks alone.
  void sort_into_blocks() {
    const Index count = particles_.size();
    order_.resize(count);
    std::fill(block_start_.begin(), block_start_.end(), 0);
    for (Index p = 0; p < count; ++p) ++block_start_[particle_block_[p] + 1];
    for (std::size_t b = 1; b < block_start_.size(); ++b) block_start_[b] += block_start_[b - 1];
    block_fill_.assign(block_start_.begin(), block_start_.end() - 1);
    for (Index p = 0; p < count; ++p) order_[block_fill_[particle_block_[p]]++] = p;
    blocks_changed_ = false;
  }

  // What a particle visit of for_each_particle_coloured reports.
  enum class Visit { done, invalid_stencil, misplaced };

  // Runs f(p) over all particles; blocks of one colour run in parallel, colours in order,
  // particles within a block in index order: the sum at every node is taken in the same
  // order whatever the thread count. Returns the first particle whose visit reported an
  // invalid stencil and the first misplaced one (the particle count for none); f may also
  // return nothing.
  template <class F>
  std::array<Index, 2> for_each_particle_coloured(F&& f) {
    const Index* start = block_start_.data();
    const Index* order = order_.data();
    Index first_invalid = particles_.size();
    Index first_misplaced = particles_.size();
    for (const auto& blocks : colour_blocks_) {
      const Index block_count = static_cast<Index>(blocks.size());
      const Index* block_list = blocks.data();
      COSMPM_OMP_PARALLEL_FOR_MIN(threads_, particles_.size(), 1, first_invalid, first_misplaced)
      for (Index b = 0; b < block_count; ++b) {
        const Index block = block_list[b];
        for (Index i = start[block]; i < start[block + 1]; ++i) {
          const Index p = order[i];
          if constexpr (std::is_void_v<std::invoke_result_t<F&, Index>>) {
            f(p);
          } else {
            const Visit visit = f(p);
            if (visit == Visit::invalid_stencil) [[unlikely]]
              record_first(first_invalid, p);
            if (visit == Visit::misplaced) [[unlikely]]
              record_first(first_misplaced, p);
          }
        }
      }
    }
    return {first_invalid, first_misplaced};
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
  bool blocks_changed_ = false;
  std::vector<double> scatter_;  // node records of the particle-to-grid maps
  std::vector<double> gather_;   // node records of the grid-to-particle maps
  // Particle positions in cell units at the last map_to_grid: the stencils of the step.
  std::vector<Vec<Dim>> stencil_cells_;
  std::vector<rates_type> particle_rates_;  // MUSL/USF: between rates and stress update
};

}  // namespace cosmpm
