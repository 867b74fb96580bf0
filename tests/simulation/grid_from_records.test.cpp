// map_and_update_grid and map_or_reuse_and_update_grid (stages/grid_update.hpp, fused_pass.hpp):
// the node fields taken from the particle-to-grid records in the grid update's own node pass,
// which USL, MUSL and the fused schemes call. Each node's arithmetic is that of
// nodes_from_records then update_grid, so a run through them and a run through the two stages
// agree bit for bit, every particle field and every node field, step after step; so do the
// laws that need the node fields first (added forces, a corrected start velocity), which run
// the two stages in turn.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cosmpm/transfer/apic.hpp"
#include "sliding_block.hpp"

namespace {
using namespace cosmpm;
using test::sliding_block;
using test::Soil;
using Polar = test::PolarContinuum;
using Classical = continuum::Classical<Soil>;

// The schemes with map_to_grid (or map_to_grid_or_reuse) and update_grid called apart.
struct USLApart {
  static constexpr const char* name() { return "USL, the node fields in a pass of their own"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/true);
    sim.update_grid(dt);
    sim.map_to_particles(dt, /*with_stress_update=*/true);
  }
};
struct MUSLApart {
  static constexpr const char* name() { return "MUSL, the node fields in a pass of their own"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid(/*with_forces=*/true);
    sim.update_grid(dt);
    sim.map_to_particles(dt);
    sim.remap_momentum(dt);
    sim.update_stress_from_grid(dt, sim.nodes().velocity, sim.nodes().spin);
  }
};
struct FusedMUSLApart {
  static constexpr const char* name() { return "fused MUSL, the node fields apart"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid_or_reuse();
    sim.update_grid(dt);
    sim.map_to_particles_and_remap(dt);
    sim.update_stress_and_map_to_grid(dt, sim.nodes().velocity, sim.nodes().spin);
  }
};
struct FusedUSLApart {
  static constexpr const char* name() { return "fused USL, the node fields apart"; }
  template <class Sim>
  static void step(Sim& sim, double dt) {
    sim.map_to_grid_or_reuse();
    sim.update_grid(dt);
    sim.map_to_particles_and_grid(dt);
  }
};

// A law that adds forces (a drag on the start momentum): it needs every node's fields before
// the update, so the node fields come first, in a pass of their own.
struct Drag {
  static constexpr const char* name() { return "test drag"; }
  void advance(double, double) {}
  void add_forces(contact::ForceView<2>& view) {
    for (std::size_t n = 0; n < view.mass.size(); ++n) view.force[n] -= 30.0 * view.momentum[n];
  }
};
// A law that corrects the start velocity (Nairn et al. 2020's phase): likewise.
struct SlowStart {
  static constexpr const char* name() { return "test start-of-step correction"; }
  void advance(double, double) {}
  bool corrects_start_of_step() const { return true; }
  void correct(contact::GridView<2>& view) {
    if (view.phase != contact::Phase::start_velocity) return;
    for (auto& v : view.velocity) v *= 0.999;
  }
};

// Steps a run of `Scheme` and one of `Apart` side by side and compares them every 20 steps.
template <class Continuum, class Scheme, class Apart, class Contact = contact::SingleField,
          class Transfer = transfer::FlipBlend, class Kernel = shape::Linear>
void check_from_records(int threads, bool wide, double damping, const std::string& label) {
  using Sim = Simulation<2, Kernel, Continuum, Contact, Scheme, Transfer>;
  using SimApart = Simulation<2, Kernel, Continuum, Contact, Apart, Transfer>;
  INFO(label);
  Sim one_pass = sliding_block<Sim>(threads, wide);
  SimApart apart = sliding_block<SimApart>(threads, wide);
  one_pass.set_damping(damping);
  apart.set_damping(damping);
  const double dt = one_pass.time_step();
  for (int i = 1; i <= 100; ++i) {
    one_pass.step(dt);
    apart.step(dt);
    if (i % 20 == 0) test::check_same_fields(one_pass, apart);
  }
}
}  // namespace

TEST_CASE("map_and_update_grid: as map_to_grid then update_grid, bit for bit") {
  SUBCASE("USL and MUSL, Mohr-Coulomb and Cosserat Drucker-Prager") {
    check_from_records<Classical, integrator::USL, USLApart>(1, false, 0.0, "USL MC");
    check_from_records<Classical, integrator::MUSL, MUSLApart>(1, false, 0.0, "MUSL MC");
    check_from_records<Polar, integrator::USL, USLApart>(1, false, 0.0, "USL Cosserat");
    check_from_records<Polar, integrator::MUSL, MUSLApart>(1, false, 0.0, "MUSL Cosserat");
  }
  SUBCASE("with local damping") {
    check_from_records<Classical, integrator::MUSL, MUSLApart>(1, false, 0.2, "damped MC");
    check_from_records<Polar, integrator::MUSL, MUSLApart>(1, false, 0.2, "damped Cosserat");
  }
  SUBCASE("APIC (quadratic B-splines): the affine terms completed per node") {
    check_from_records<Classical, integrator::MUSL, MUSLApart, contact::SingleField, transfer::APIC,
                       shape::QuadraticBSpline>(1, false, 0.0, "MUSL APIC");
  }
  SUBCASE("laws that need the node fields first run the two stages in turn") {
    check_from_records<Classical, integrator::MUSL, MUSLApart, Drag>(1, false, 0.0, "drag");
    check_from_records<Classical, integrator::USL, USLApart, SlowStart>(1, false, 0.0,
                                                                        "start correction");
  }
  SUBCASE("two threads over 6,200 particles") {
    check_from_records<Classical, integrator::MUSL, MUSLApart>(2, true, 0.0, "2 threads MC");
    check_from_records<Polar, integrator::USL, USLApart>(2, true, 0.0, "2 threads Cosserat");
  }
}

TEST_CASE("map_or_reuse_and_update_grid: as map_to_grid_or_reuse then update_grid") {
  // The fused records carry the second half's terms pending (EngineState::scatter_upper): the
  // grid update's pass adds them, as nodes_from_records does.
  SUBCASE("fused MUSL and fused USL, one thread and two") {
    check_from_records<Classical, integrator::FusedMUSL, FusedMUSLApart>(1, false, 0.0,
                                                                         "fused MUSL MC");
    check_from_records<Polar, integrator::FusedMUSL, FusedMUSLApart>(1, false, 0.0,
                                                                     "fused MUSL Cosserat");
    check_from_records<Classical, integrator::FusedUSL, FusedUSLApart>(1, false, 0.0,
                                                                       "fused USL MC");
    check_from_records<Classical, integrator::FusedMUSL, FusedMUSLApart>(2, true, 0.0,
                                                                         "2 threads fused MUSL");
    check_from_records<Polar, integrator::FusedUSL, FusedUSLApart>(2, true, 0.0,
                                                                   "2 threads fused USL");
  }
}
