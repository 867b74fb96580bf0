#pragma once
// Stage 1, particle to grid: mass, momentum (and the rotational degrees of freedom's inertia
// and momentum) and, with forces, the internal and external forces (and moments), scattered
// block by block in colour order (simulation/block_scheduler.hpp), so every nodal sum is
// taken in the same order whatever the thread count. Also USF's forces after the stress
// update, at the stencils of the step's first map (MUSL's remap is in stages/remap.hpp).
#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "cosmpm/simulation/block_scheduler.hpp"
#include "cosmpm/stages/node_range.hpp"
#include "cosmpm/stages/node_records.hpp"
#include "cosmpm/stages/records.hpp"
#include "cosmpm/transfer/apic.hpp"

namespace cosmpm::stages {

// The stencil of particle p at the start of the step (the last map_to_grid).
template <class State>
COSMPM_ALWAYS_INLINE void start_stencil(const State& s, Index p,
                                        const shape::StencilGrid<State::dim>& stencil_grid,
                                        typename State::stencil_type& stencil) {
  stencil.compute_from_cell_units(
      stencil_grid, s.stencil_cells[p],
      s.particles.template get<particles::field::HalfWidth<State::dim>>()[p]);
}

template <class State>
void require_start_stencils(const State& s, const char* where) {
  require(static_cast<Index>(s.stencil_cells.size()) == s.particles.size(),
          std::string("Simulation::") + where +
              ": no stencils for this step's particles; call map_to_grid first");
}

// A particle's force (and moments) on the nodes as N weighted + grad N . by_gradient: weight
// m g and the stress divergence (Continuum::internal_force_coefficients), then the
// continuum's rotational terms. `weighted` points at the force's first component. Value is a
// double, or a pack for W particles (stages/fused_scatter.hpp, scatter_pack), each lane the
// double's arithmetic.
template <class State, class Value, class Stress, std::size_t F>
COSMPM_ALWAYS_INLINE void force_contribution(
    const Value& mass, const Value& volume, const Stress& stress, const Vec<State::dim>& gravity,
    Value* weighted, std::array<std::array<Value, State::dim>, F>& by_gradient) {
  constexpr int Dim = State::dim;
  static_assert(F == Dim + State::rotational_dofs, "force and moment components");
  using Continuum = typename State::continuum_type;
  const auto b = Continuum::internal_force_coefficients(stress, volume);
  for (int d = 0; d < Dim; ++d) {
    weighted[d] = mass * gravity[d];
    for (int e = 0; e < Dim; ++e) by_gradient[d][e] = b[d][e];
  }
  Continuum::rotational_force_terms(stress, volume, weighted + Dim, by_gradient.data() + Dim);
}

// A particle's momentum terms of the particle-to-grid maps: m v at `momentum` and, for an
// affine transfer (transfer/apic.hpp), m (v - C x) there and m C at `affine`, which
// nodal_momentum() completes per node; C = B D^-1 with the D of the map's stencil `st` at the
// particle's position in cell units `x_in_cells`.
template <class State, class Particles>
COSMPM_ALWAYS_INLINE void momentum_terms(
    const Particles& particles, Index p, double mass, const Vec<State::dim>& velocity,
    [[maybe_unused]] const typename State::stencil_type& st,
    [[maybe_unused]] const Vec<State::dim>& x_in_cells,
    [[maybe_unused]] const shape::StencilGrid<State::dim>& grid, double* momentum,
    [[maybe_unused]] double* affine) {
  constexpr int Dim = State::dim;
  if constexpr (State::transfer_type::affine) {
    const Mat<Dim> c = transfer::detail::affine_velocity(
        particles.template get<particles::field::AffineMoment<Dim>>()[p], st, grid, x_in_cells);
    for (int d = 0; d < Dim; ++d) {
      double cx = 0.0;
      for (int e = 0; e < Dim; ++e) {
        cx += c(d, e) * (x_in_cells[e] / grid.inverse_cell_size[e]);
        affine[d * Dim + e] = mass * c(d, e);
      }
      momentum[d] = mass * (velocity[d] - cx);
    }
  } else {
    for (int d = 0; d < Dim; ++d) momentum[d] = mass * velocity[d];
  }
}

// A particle's rotational terms of the particle-to-grid map, its inertia m J at `inertia` and
// spin momentum m J spin at `spin_momentum` for each rotational degree of freedom; Value a
// double, or a pack for particles p, ..., p + W - 1.
template <class State, class Value>
COSMPM_ALWAYS_INLINE void rotational_terms(const typename State::store_type& particles, Index p,
                                           const Value& mass, Value* inertia,
                                           Value* spin_momentum) {
  using Continuum = typename State::continuum_type;
  constexpr int W = lane_count<Value>();
  const auto j = Continuum::rotational_inertia(particles, p, mass);
  std::array<Value, State::rotational_dofs> spin;
  if constexpr (W == 1) {
    spin = Continuum::rotational_velocity(particles, p);  // any continuum of the concept
  } else {
    spin = Continuum::template rotational_velocity<W>(particles, p);
  }
  for (int k = 0; k < State::rotational_dofs; ++k) {
    inertia[k] = j[k];
    spin_momentum[k] = j[k] * spin[k];
  }
}

namespace detail {

// The particle arrays a scatter reads, their addresses taken once per pass: the loops run
// short of registers, and a pointer is one load where a vector is two.
template <class State>
struct ScatterSources {
  static constexpr int dim = State::dim;
  const Vec<dim>* x;
  const Vec<dim>* v;
  const double* mass;
  const double* volume;
  const Vec<dim>* half;
  const typename State::model_type::stress_type* stress;
  Vec<dim> gravity;
};

template <class State>
ScatterSources<State> scatter_sources(const State& s) {
  constexpr int Dim = State::dim;
  using Model = typename State::model_type;
  const auto& particles = s.particles;
  return {particles.template get<particles::field::Position<Dim>>().data(),
          particles.template get<particles::field::Velocity<Dim>>().data(),
          particles.template get<particles::field::Mass>().data(),
          particles.template get<particles::field::Volume>().data(),
          particles.template get<particles::field::HalfWidth<Dim>>().data(),
          particles.template get<particles::field::Stress<Model>>().data(),
          s.parameters.gravity};
}

// Particle p's mass, momentum (and, with_forces, force) terms added to the node records at
// its stencil st, whose position in cell units is x_in_cells.
template <bool with_forces, class State>
COSMPM_ALWAYS_INLINE void scatter_particle(const typename State::store_type& particles,
                                           const ScatterSources<State>& from, Index p,
                                           const typename State::stencil_type& st,
                                           const Vec<State::dim>& x_in_cells,
                                           const shape::StencilGrid<State::dim>& stencil_grid,
                                           double* records) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Record = typename State::scatter_record;
  constexpr int W = Record::weighted;
  constexpr int C = with_forces ? Record::all : W;
  const double mp = from.mass[p];
  std::array<double, C> weighted;
  std::array<std::array<double, Dim>, C - W> by_gradient;
  weighted[Record::mass] = mp;
  if constexpr (State::transfer_type::affine) {
    momentum_terms<State>(particles, p, mp, from.v[p], st, x_in_cells, stencil_grid,
                          weighted.data() + Record::momentum, weighted.data() + Record::affine);
  } else {
    (void)x_in_cells;
    for (int d = 0; d < Dim; ++d) weighted[Record::momentum + d] = mp * from.v[p][d];
  }
  if constexpr (R > 0) {
    rotational_terms<State>(particles, p, mp, weighted.data() + Record::inertia,
                            weighted.data() + Record::spin_momentum);
  }
  if constexpr (with_forces) {
    force_contribution<State>(mp, from.volume[p], from.stress[p], from.gravity,
                              weighted.data() + Record::force, by_gradient);
  }
  shape::scatter<W>(st, records, weighted, by_gradient);
}

// The node records of the particle-to-grid map, sized for the grid, zeroed in `cleared` (the
// step's node range, which no stencil leaves; every node for a scatter at positions not yet
// sorted into blocks).
template <bool with_forces, class State>
double* clear_scatter_records(State& s, NodeRange cleared) {
  using Record = typename State::scatter_record;
  constexpr int C = with_forces ? Record::all : Record::weighted;
  const Index nodes = s.grid.node_count();
  discard_pending_upper(s);
  s.scatter.resize(static_cast<std::size_t>(Record::all * nodes));
  zero_records_for_writing(s, C * cleared.first, C * cleared.end);
  s.prescattered = false;
  return s.scatter.data();
}

// The particle-to-grid pass of map_to_grid into s.scatter. False (and nothing usable) if a
// particle no longer lies in the block it was sorted into.
template <bool with_forces, class State>
bool scatter_particles(State& s) {
  constexpr int Dim = State::dim;
  reach_occupied_nodes(s);  // every stencil lies in its particle's block, or the pass fails
  double* const records = clear_scatter_records<with_forces>(s, s.node_range);
  const auto& particles = s.particles;
  const ScatterSources<State> from = scatter_sources(s);
  const auto* const x = from.x;
  const auto* const half = from.half;
  const auto blocks = s.blocks.lookup();
  const Index* const particle_block = blocks.particle_block;
  const Index count = particles.size();
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  s.stencil_cells.resize(static_cast<std::size_t>(count));
  Vec<Dim>* const stencil_cells = s.stencil_cells.data();
  // Inlined into the block loop.
  const auto [first_invalid, first_misplaced] = s.blocks.for_each_coloured(
      s.threads, count,
      [&, x, half, particle_block, stencil_cells, records](Index p) COSMPM_INLINE_LAMBDA {
        typename State::stencil_type st;
        // Reported after the (possibly parallel) loop.
        if (!st.try_compute(stencil_grid, x[p], half[p])) [[unlikely]]
          return Visit::invalid_stencil;
        if (blocks.block_of_cell(st.cell) != particle_block[p]) [[unlikely]]
          return Visit::misplaced;
        for (int d = 0; d < Dim; ++d) stencil_cells[p][d] = st.position_in_cells[d];
        scatter_particle<with_forces, State>(particles, from, p, st, stencil_cells[p], stencil_grid,
                                             records);
        return Visit::done;
      });
  if (first_invalid < count) {
    typename State::stencil_type st;
    st.compute(stencil_grid, x[first_invalid], half[first_invalid]);  // throws, naming it
  }
  return first_misplaced == count;
}

// map_to_grid's particle pass: the records in s.scatter, the node fields not yet taken.
template <class State>
void scatter_to_records(State& s, bool with_forces) {
  constexpr int Dim = State::dim;
  const auto& x = s.particles.template get<particles::field::Position<Dim>>();
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  s.blocks.bucket(x, s.particles.size(), stencil_grid);
  const auto scatter = [&] {
    return with_forces ? scatter_particles<true>(s) : scatter_particles<false>(s);
  };
  if (!scatter()) {
    // Particles were moved outside the engine since the last step (e.g. by the user): the
    // blocks no longer keep same-colour scatters apart. Sort again and redo.
    s.blocks.resort(x, s.particles.size(), stencil_grid);
    require(scatter(), "Simulation::map_to_grid: particle blocks inconsistent after sorting");
  }
}

}  // namespace detail

// Particle mass and momentum (and, with_forces, internal and external forces) to the nodes.
// Buckets particles into coloured blocks first.
template <class State>
void map_to_grid(State& s, bool with_forces) {
  detail::scatter_to_records(s, with_forces);
  nodes_from_records(s, with_forces);
}

// USF only: forces after the stress update (mass and momentum are already on the grid, and
// grid_velocity_from_momentum turned the momenta into velocities: they are restored).
template <class State>
void map_forces_to_grid(State& s) {
  constexpr int Dim = State::dim;
  constexpr int R = State::rotational_dofs;
  using Model = typename State::model_type;
  auto& nodes = s.nodes;
  const Index count = s.grid.node_count();
  const NodeRange range = s.node_range;  // the stencils of the step's map_to_grid
  for (Index n = range.first; n < range.end; ++n) {
    nodes.momentum[n] *= nodes.mass[n];
    for (int k = 0; k < R; ++k)
      nodes.spin_momentum[n * R + k] *= nodes.rotational_inertia[n * R + k];
  }
  constexpr int forces = Dim + R;
  s.scatter.resize(std::max(s.scatter.size(), static_cast<std::size_t>(forces * count)));
  s.prescattered = false;
  detail::discard_pending_upper(s);
  detail::zero_records_for_writing(s, forces * range.first, forces * range.end);
  require_start_stencils(s, "map_forces_to_grid");
  const auto& mass = s.particles.template get<particles::field::Mass>();
  const auto& vol = s.particles.template get<particles::field::Volume>();
  const auto& stress = s.particles.template get<particles::field::Stress<Model>>();
  const Vec<Dim> gravity = s.parameters.gravity;
  const shape::StencilGrid<Dim> stencil_grid(s.grid);
  double* const records = s.scatter.data();
  s.blocks.for_each_coloured(s.threads, s.particles.size(), [&](Index p) COSMPM_INLINE_LAMBDA {
    typename State::stencil_type st;
    start_stencil(s, p, stencil_grid, st);
    std::array<double, forces> weighted;
    std::array<std::array<double, Dim>, forces> by_gradient;
    force_contribution<State>(mass[p], vol[p], stress[p], gravity, weighted.data(), by_gradient);
    shape::scatter<0>(st, records, weighted, by_gradient);
  });
  for (Index n = range.first; n < range.end; ++n) {
    for (int d = 0; d < Dim; ++d) nodes.force[n][d] = records[n * forces + d];
    for (int k = 0; k < R; ++k) nodes.moment[n * R + k] = records[n * forces + Dim + k];
    std::fill(records + n * forces, records + (n + 1) * forces, 0.0);
  }
  detail::records_read_and_zeroed(s, forces * range.first, forces * range.end);
}

}  // namespace cosmpm::stages
