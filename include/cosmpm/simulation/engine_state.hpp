#pragma once
// Everything a simulation owns, in one place, for the stages (stages/*.hpp) to work on: the
// grid and its conditions, the policies' values, the particles (SoA), the node fields, the
// block scheduler and the buffers the transfers share within a step. Simulation is the
// public face of it; a stage is a function of an EngineState and the step's dt, nothing else.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/simulation/block_scheduler.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/simulation/node_fields.hpp"
#include "cosmpm/simulation/parameters.hpp"
#include "cosmpm/transfer/flip_blend.hpp"

namespace cosmpm {

template <int Dim, shape::Kernel Kernel, class Continuum, class Contact,
          class Transfer = transfer::FlipBlend>
struct EngineState {
  static constexpr int dim = Dim;
  using kernel_type = Kernel;
  using continuum_type = Continuum;
  using contact_type = Contact;
  using transfer_type = Transfer;
  using stencil_type = shape::SeparableStencil<Dim, Kernel>;
  using model_type = typename Continuum::model_type;
  // The continuum's fields, and the affine velocity of an affine transfer.
  using store_type = std::conditional_t<
      Transfer::affine,
      particles::append_fields_t<typename Continuum::template particle_store<Dim>,
                                 particles::field::AffineMoment<Dim>>,
      typename Continuum::template particle_store<Dim>>;
  using rates_type = typename Continuum::template rates_type<Dim>;
  // The continuum's nodal degrees of freedom besides the translations.
  static constexpr int rotational_dofs = Continuum::rotational_dofs;
  static constexpr int affine_terms = Transfer::affine ? Dim * Dim : 0;
  using scatter_record = ScatterRecord<Dim, rotational_dofs, affine_terms>;
  using gather_record = GatherRecord<Dim, rotational_dofs>;

  EngineState(const grid::Grid<Dim>& background, const Continuum& continuum_value,
              const SimulationParameters<Dim>& parameter_values, Contact contact_law)
      : grid(background),
        continuum(continuum_value),
        parameters(parameter_values),
        contact(std::move(contact_law)),
        nodes(background.node_count()),
        blocks(background),
        threads(resolve_thread_count(parameter_values.threads)),
        node_range{0, background.node_count()} {}

  grid::Grid<Dim> grid;
  Continuum continuum;  // holds the constitutive model
  SimulationParameters<Dim> parameters;
  grid::BoundaryConditions<Dim> boundary;
  Contact contact;
  store_type particles;
  NodeFields<Dim, rotational_dofs> nodes;
  BlockScheduler<Dim, Kernel> blocks;
  int threads = 1;
  StepClock clock;
  // The nodes the step's particles may reach (stages/node_range.hpp); every node outside holds
  // zero fields, and the dense node passes skip them.
  NodeRange node_range;
  // False: the node passes run over every node (a check that the range changes nothing).
  bool prune_node_range = true;
  double typical_particle_mass = 0.0;  // the largest particle mass added
  double max_density = 0.0;
  StrayReport strays;
  bool strays_pending = false;  // set by the grid-to-particle map, handled at the step's end
  store_type frozen;            // strays kept under StrayParticles::freeze

  // Shared by the stages of one step:
  std::vector<double> scatter;  // node records of the particle-to-grid maps
  // The doubles of `scatter` that may be nonzero, [first, end); every other one is +0: the node
  // passes that read the records zero them, so the next scatter need not (stages/records.hpp).
  NodeRange scatter_dirty{0, 0};
  // The fused schemes' particle pass scattered the next step's records (stages/fused_pass.hpp);
  // cleared by anything that writes the records or may have changed the particles since.
  bool prescattered = false;
  NodeRange prescattered_nodes{0, 0};  // the nodes its stencils reach
  // Its second half's records, upper_width doubles per node, pending in the nodes
  // [upper_first, upper_end) until the node pass that reads them completes them (zero
  // elsewhere and after); the nodes its first half's records may be nonzero in; and the
  // threads that ran the pass last.
  std::vector<double> scatter_upper;
  Index upper_first = 0;
  Index upper_end = 0;
  int upper_width = 0;
  NodeRange lower_nodes{0, 0};
  int fused_team = 1;
  std::vector<double> gather;  // node records of the grid-to-particle maps
  // Stage 4a's node records where velocity and rotational rates are copied into records (3 doubles
  // per node in 2D); apart from `gather` (8), so that neither thread's records lie in the lines
  // the other thread's node share writes in the grid update.
  std::vector<double> rate_gather;
  // Particle positions in cell units at the last map_to_grid: the stencils of the step.
  std::vector<Vec<Dim>> stencil_cells;
  std::vector<rates_type> particle_rates;  // MUSL/USF: between rates and stress update
  bool rates_stored = false;           // particle_rates holds every particle's rates of the last 4a
  std::vector<double> cell_sums;       // antilocking::FBar: per-cell volume sums
  std::vector<unsigned char> imposed;  // components the face conditions imposed, per node
  std::vector<unsigned char> held;     // ... would impose on the field before contact
  std::vector<Vec<Dim>> held_scratch;  // the field the prediction of `held` works on

  const model_type& model() const { return continuum.model(); }
  double empty_node_mass() const {
    return parameters.empty_node_mass_fraction * typical_particle_mass;
  }
};

}  // namespace cosmpm
