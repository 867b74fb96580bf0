// The DEM step on the paper's rig: 10,000 particles in a layer 1.14 m long (the flat blade's
// rig, Coetzee 2014), as disks (9-11 mm) or as two-disk corn clumps (9-11 mm long, 0.6 wide),
// with the corn's contact law (k = 420 kN/m per particle, mu = 0.1) and local damping 0.7.
// Each packing is made once (about a minute): a jittered lattice rained into the rig and settled
// (PFC's unbalanced force ratio below 1e-3, at most 2.5 s). The
// counters: items_per_second = particle-steps per second (bodies), contacts_per_second =
// touching contacts x steps per second.
#include <benchmark/benchmark.h>

#include <memory>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;
using Sim = dem::Simulation<dem::LinearSpring, dem::LocalDamping>;

std::unique_ptr<Sim> make_rig(bool clumps) {
  dem::Grains grains;
  if (clumps) grains.shape = dem::ClumpShape::two_disks(1.0, 0.6);
  dem::Assembly a;
  dem::rain(a, grains, 10000, {0.0, 1.14, 0.0, 3.0}, 17);
  dem::Parameters parameters;
  parameters.threads = 1;  // set per benchmark below
  auto sim =
      std::make_unique<Sim>(std::move(a), dem::LinearSpring(), dem::LocalDamping(0.7), parameters);
  const dem::LinearSpringMaterial steel{420e3, 420e3, 0.25};
  sim->add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), steel);
  sim->add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), steel);
  sim->add_plane_wall("right", Vec<2>(1.14, 0), Vec<2>(-1, 0), steel);
  const double dt = 0.8 * sim->critical_time_step();
  dem::settle(*sim, dt, 2.5, 1e-3, 0.5);
  return sim;
}

const Sim& rig(bool clumps) {
  static const std::unique_ptr<Sim> disks = make_rig(false);
  static const std::unique_ptr<Sim> grains = make_rig(true);
  return clumps ? *grains : *disks;
}

void BM_DemStep(benchmark::State& state) {
  const bool clumps = state.range(0) != 0;
  Sim sim = rig(clumps);
  sim.parameters().threads = static_cast<int>(state.range(1));
  const double dt = 0.8 * sim.critical_time_step();
  sim.step(dt);
  double contacts = 0.0;
  for (auto _ : state) {
    sim.step(dt);
    contacts += static_cast<double>(sim.active_contacts());
  }
  state.SetItemsProcessed(state.iterations() * sim.assembly().body_count());
  state.counters["contacts_per_second"] = benchmark::Counter(contacts, benchmark::Counter::kIsRate);
  state.counters["elements"] = static_cast<double>(sim.assembly().element_count());
  state.counters["list_builds"] = static_cast<double>(sim.contact_lists().builds);
}

}  // namespace

BENCHMARK(BM_DemStep)
    ->ArgNames({"clumps", "threads"})
    ->Args({0, 1})
    ->Args({0, 2})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
