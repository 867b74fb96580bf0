// The zeros of the node records (stages/records.hpp): the node passes that read the records zero
// them, EngineState::scatter_dirty keeps what may still be nonzero, and a writer clears only
// that part of its extent. Checked here: the bookkeeping itself, the invariant (every double
// outside the extent is +0) after every stage of every scheme, and stages called in orders no
// scheme uses (a writer twice, without a reader between) against the same stage run once.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/stages/records.hpp"
#include "sliding_block.hpp"

namespace {
using namespace cosmpm;
using test::same_bits;
using test::Soil;
using Polar = test::PolarContinuum;

struct Buffer {
  std::vector<double> scatter = std::vector<double>(40, 0.0);
  NodeRange scatter_dirty{0, 0};
};

// Every double of the records outside the dirty extent is +0 (not -0: a sum starting there
// must start from +0).
template <class Sim>
bool zero_outside_extent(const Sim& sim) {
  const auto& s = sim.engine();
  const NodeRange dirty = s.scatter_dirty;
  for (Index i = 0; i < static_cast<Index>(s.scatter.size()); ++i) {
    if (i >= dirty.first && i < dirty.end) continue;
    const double x = s.scatter[static_cast<std::size_t>(i)];
    if (x != 0.0 || std::signbit(x)) return false;
  }
  return true;
}

// Every double of the fused pass's second-half records is +0 but those still pending (the node
// pass that reads the records takes them, in place or added to the first half's).
template <class Sim>
bool upper_zero_unless_pending(const Sim& sim) {
  const auto& s = sim.engine();
  const Index first = s.upper_end > s.upper_first ? s.upper_first * s.upper_width : 0;
  const Index end = s.upper_end > s.upper_first ? s.upper_end * s.upper_width : 0;
  for (Index i = 0; i < static_cast<Index>(s.scatter_upper.size()); ++i) {
    if (i >= first && i < end) continue;
    const double x = s.scatter_upper[static_cast<std::size_t>(i)];
    if (x != 0.0 || std::signbit(x)) return false;
  }
  return true;
}

// Each step's stages one by one (MUSL's, with USF's force map and the fused schemes' passes in
// between), the invariant checked after each.
template <class Continuum>
void check_invariant_through_stages(const std::string& label) {
  INFO(label);
  using Sim = Simulation<2, shape::Linear, Continuum, contact::SingleField, integrator::MUSL>;
  Sim sim = test::sliding_block<Sim>(1, false);
  const double dt = sim.time_step();
  const auto check = [&](const char* stage) {
    INFO(stage);
    CHECK(zero_outside_extent(sim));
    CHECK(upper_zero_unless_pending(sim));
  };
  for (int i = 0; i < 20; ++i) {
    sim.map_to_grid(true);
    check("map_to_grid");
    CHECK(std::as_const(sim).engine().scatter_dirty.size() == 0);  // read and zeroed
    sim.update_grid(dt);
    sim.map_to_particles(dt);
    sim.remap_momentum(dt);
    check("remap_momentum");
    CHECK(std::as_const(sim).engine().scatter_dirty.size() == 0);
    sim.update_stress_from_grid(dt, sim.nodes().velocity, sim.nodes().spin);
    sim.map_forces_to_grid();
    check("map_forces_to_grid");
    sim.map_to_grid_or_reuse();
    check("map_to_grid_or_reuse");
    sim.update_grid(dt);
    sim.map_to_particles_and_grid(dt);
    check("map_to_particles_and_grid");  // written, not yet read: the stencils' nodes
    CHECK(std::as_const(sim).engine().scatter_dirty.size() > 0);
    sim.map_to_grid_or_reuse();
    check("map_to_grid_or_reuse after the fused pass");
    CHECK(std::as_const(sim).engine().scatter_dirty.size() == 0);
    sim.update_grid(dt);
    sim.map_to_particles_and_grid(dt);
    sim.map_or_reuse_and_update_grid(dt);
    check("map_or_reuse_and_update_grid after the fused pass");
    CHECK(std::as_const(sim).engine().scatter_dirty.size() == 0);
    sim.map_to_particles(dt);
    sim.map_and_update_grid(dt);
    check("map_and_update_grid");
    CHECK(std::as_const(sim).engine().scatter_dirty.size() == 0);
    sim.map_to_particles(dt, /*with_stress_update=*/true);
    sim.handle_stray_particles();
  }
}
}  // namespace

TEST_CASE("node records: the dirty extent's bookkeeping") {
  using cosmpm::stages::detail::records_read_and_zeroed;
  using cosmpm::stages::detail::records_written_within;
  using cosmpm::stages::detail::zero_records_for_writing;
  Buffer b;
  // A reader zeroes what it read, then reports it.
  const auto read = [&](Index first, Index end) {
    for (Index i = first; i < end; ++i) b.scatter[static_cast<std::size_t>(i)] = 0.0;
    records_read_and_zeroed(b, first, end);
  };
  zero_records_for_writing(b, 8, 20);  // from all zero: the extent is the writer's
  CHECK(b.scatter_dirty.first == 8);
  CHECK(b.scatter_dirty.end == 20);
  for (int i = 8; i < 20; ++i) b.scatter[static_cast<std::size_t>(i)] = 1.0;
  zero_records_for_writing(b, 15, 30);  // clears its overlap, [15, 20), and grows the extent
  CHECK(b.scatter[14] == 1.0);
  CHECK(b.scatter[15] == 0.0);
  CHECK(b.scatter[19] == 0.0);
  CHECK(b.scatter_dirty.first == 8);
  CHECK(b.scatter_dirty.end == 30);
  read(0, 12);  // the front read: the extent starts after it
  CHECK(b.scatter_dirty.first == 12);
  CHECK(b.scatter_dirty.end == 30);
  read(20, 24);  // a middle part: the extent stays
  CHECK(b.scatter_dirty.first == 12);
  CHECK(b.scatter_dirty.end == 30);
  read(25, 35);  // the back
  CHECK(b.scatter_dirty.end == 25);
  zero_records_for_writing(b, 0, 40);  // covers the extent: everything zero, then its own
  for (double x : b.scatter) CHECK(x == 0.0);
  CHECK(b.scatter_dirty.first == 0);
  CHECK(b.scatter_dirty.end == 40);
  records_written_within(b, 16, 24);  // a pass that noted where it wrote
  read(16, 24);
  CHECK(b.scatter_dirty.size() == 0);
}

TEST_CASE("node records: the second half's records completed, read in place where only it wrote") {
  using cosmpm::stages::detail::complete_records;
  using cosmpm::stages::detail::PendingUpper;
  constexpr Index width = 2;
  constexpr Index nodes = 12;
  // The halves' nodes in the usual order (the first half below), overlapping, the other way
  // round, apart, and no pending records at all.
  struct Case {
    NodeRange lower;
    NodeRange upper;
  };
  for (const Case c : {Case{{1, 7}, {5, 11}}, Case{{5, 12}, {0, 6}}, Case{{0, 4}, {8, 12}},
                       Case{{2, 9}, {0, 0}}}) {
    for (Index first = 0; first <= nodes; ++first) {
      for (Index last = first; last <= nodes; ++last) {
        CAPTURE(c.lower.first);
        CAPTURE(c.upper.first);
        CAPTURE(first);
        CAPTURE(last);
        constexpr auto size = static_cast<std::size_t>(width * nodes);
        std::vector<double> lower(size, 0.0);
        std::vector<double> upper(size, 0.0);
        for (std::size_t i = 0; i < size; ++i) {
          const auto n = static_cast<Index>(i) / width;
          if (n >= c.lower.first && n < c.lower.end) lower[i] = 1.0 + 0.1 * static_cast<double>(i);
          if (n >= c.upper.first && n < c.upper.end) upper[i] = 0.3 + 0.7 * static_cast<double>(i);
        }
        std::vector<double> sum(size);
        for (std::size_t i = 0; i < size; ++i) sum[i] = lower[i] + upper[i];
        const PendingUpper pending{upper.data(), c.upper.first, c.upper.end, width, c.lower};
        Index next = first;
        bool complete = true;
        for (const auto run : complete_records(pending, lower.data(), first, last)) {
          CHECK(run.first == next);
          CHECK(run.last > run.first);
          next = run.last;
          for (Index n = run.first; n < run.last; ++n) {
            const bool only_upper =
                n >= c.upper.first && n < c.upper.end && !(n >= c.lower.first && n < c.lower.end);
            CHECK(run.records == (only_upper ? upper.data() : lower.data()));
            for (Index k = 0; k < width; ++k) {
              const auto i = static_cast<std::size_t>(n * width + k);
              complete &=
                  same_bits(std::vector<double>{run.records[i]}, std::vector<double>{sum[i]});
            }
          }
        }
        CHECK(next == std::max(first, last));
        CHECK(complete);
        // What was added is zeroed in the second half's records; what is read in place stays
        // for its reader to zero.
        for (Index n = first; n < last; ++n) {
          const bool both =
              n >= c.upper.first && n < c.upper.end && n >= c.lower.first && n < c.lower.end;
          if (both) CHECK(upper[static_cast<std::size_t>(n * width)] == 0.0);
        }
      }
    }
  }
}

TEST_CASE("node records: zero outside the dirty extent after every stage") {
  check_invariant_through_stages<continuum::Classical<Soil>>("Mohr-Coulomb");
  check_invariant_through_stages<Polar>("Cosserat Drucker-Prager");
}

TEST_CASE("node records: stages in any order give what clearing every record gives") {
  // The reference clears every record before each stage (its extent set to the whole buffer),
  // as the engine did before the readers zeroed them; the stages run in orders no scheme uses:
  // a fused pass's records dropped unread, an unfused scatter while a fused pass's records are
  // pending (it clears only its own range), the remap twice, the schemes mixed.
  using Sim = Simulation<2, shape::Linear, Polar, contact::SingleField, integrator::MUSL>;
  Sim kept = test::sliding_block<Sim>(1, false);
  Sim cleared = test::sliding_block<Sim>(1, false);
  const double dt = kept.time_step();
  const auto run = [&](auto&& stage, const char* name) {
    INFO(name);
    auto& engine = cleared.engine();
    engine.scatter_dirty = {0, static_cast<Index>(engine.scatter.size())};
    stage(kept);
    stage(cleared);
    CHECK(zero_outside_extent(kept));
    const auto& a = kept.nodes();
    const auto& b = cleared.nodes();
    CHECK(same_bits(a.mass, b.mass));
    CHECK(same_bits(a.momentum, b.momentum));
    CHECK(same_bits(a.force, b.force));
    CHECK(same_bits(a.velocity, b.velocity));
    CHECK(same_bits(a.spin_momentum, b.spin_momentum));
    CHECK(same_bits(a.moment, b.moment));
    CHECK(same_bits(a.spin, b.spin));
    namespace field = particles::field;
    CHECK(same_bits(std::as_const(kept).particles().get<field::Velocity<2>>(),
                    std::as_const(cleared).particles().get<field::Velocity<2>>()));
    CHECK(same_bits(std::as_const(kept).particles().get<field::Stress<Polar::model_type>>(),
                    std::as_const(cleared).particles().get<field::Stress<Polar::model_type>>()));
  };
  for (int i = 0; i < 10; ++i) {
    run([&](Sim& s) { s.map_to_grid(true); }, "map_to_grid");
    run([&](Sim& s) { s.update_grid(dt); }, "update_grid");
    run([&](Sim& s) { s.map_to_particles_and_grid(dt); }, "fused USL pass");
    run([&](Sim& s) { (void)s.particles(); }, "records dropped unread");
    run([&](Sim& s) { s.map_to_grid_or_reuse(); }, "a fresh scatter over every node");
    run([&](Sim& s) { s.update_grid(dt); }, "update_grid");
    run([&](Sim& s) { s.map_to_particles(dt); }, "map_to_particles");
    run([&](Sim& s) { s.remap_momentum(dt); }, "remap_momentum");
    run([&](Sim& s) { s.remap_momentum(dt); }, "remap_momentum again");
    run([&](Sim& s) { s.update_stress_and_map_to_grid(dt, s.nodes().velocity, s.nodes().spin); },
        "fused MUSL pass");
    run([&](Sim& s) { s.map_to_grid(false); }, "an unfused scatter, the fused records pending");
    run([&](Sim& s) { s.grid_velocity_from_momentum(dt); }, "USF start velocity");
    run([&](Sim& s) { s.update_stress_from_grid(dt, s.nodes().momentum, s.nodes().spin_momentum); },
        "USF stress");
    run([&](Sim& s) { s.map_forces_to_grid(); }, "map_forces_to_grid");
    run([&](Sim& s) { s.update_grid(dt); }, "update_grid");
    run([&](Sim& s) { s.map_to_particles(dt); }, "map_to_particles");
    run([&](Sim& s) { s.map_and_update_grid(dt); }, "map_and_update_grid");
    run([&](Sim& s) { s.map_to_particles_and_grid(dt); }, "fused USL pass");
    run([&](Sim& s) { s.map_or_reuse_and_update_grid(dt); }, "its records in the grid update");
    run([&](Sim& s) { s.map_to_particles(dt); }, "map_to_particles");
    run([&](Sim& s) { s.handle_stray_particles(); }, "strays");
  }
}
