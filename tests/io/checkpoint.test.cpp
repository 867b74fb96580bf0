// Checkpoint/restart: a restarted run continues bit-identically (compared with ==, tolerance
// none), special doubles survive bit for bit, and a checkpoint of another composition or a
// damaged file is refused with an Error naming the file and the problem.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/simulation.hpp"
#include "cosmpm/transfer/apic.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;
using namespace cosmpm::test_io;
namespace field = particles::field;

// Linear elasticity with a state that changes every step (accumulated |shear increment| and a
// flag), so the restart also exercises the material state.
struct TrackingElastic {
  using scalar_type = double;
  using stress_type = SymTensor2D<double>;
  using strain_type = SymTensor2D<double>;
  using state_type = material::PlasticState;
  static constexpr bool is_cosserat = false;
  static const char* name() { return "TrackingElastic"; }
  material::LinearElastic<> elastic{1e6, 0.3};
  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    material::NoState none;
    elastic.update(stress, none, de);
    state.plastic_shear_strain += std::abs(de[3]);
    state.plastic = state.plastic_shear_strain > 1e-4 ? 1.0 : 0.0;
  }
  double p_wave_modulus() const { return elastic.p_wave_modulus(); }
  double shear_modulus() const { return elastic.shear_modulus(); }
};

template <class Kernel = shape::Linear, class Scheme = integrator::USL>
using Sim =
    Simulation<2, Kernel, continuum::Classical<TrackingElastic>, contact::SingleField, Scheme>;
using ApicSim = Simulation<2, shape::QuadraticBSpline, continuum::Classical<TrackingElastic>,
                           contact::SingleField, integrator::MUSL, transfer::APIC>;

const grid::Grid<2> block_grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});

// An elastic block on a fixed base under gravity, thrown sideways so everything moves.
template <class S>
void set_up(S& sim, const grid::Grid<2>& grid = block_grid) {
  const auto seeding = particles::seed_box(grid, Vec<2>(0.2, 0.0), Vec<2>(0.6, 0.5), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  auto& v = sim.particles().template get<field::Velocity<2>>();
  const auto& x = sim.particles().template get<field::Position<2>>();
  for (std::size_t p = 0; p < v.size(); ++p) v[p] = Vec<2>(0.5 * x[p][1], 0.0);
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
}

template <class S>
S make_sim(const grid::Grid<2>& grid = block_grid, int threads = 0) {
  SimulationParameters<2> parameters;
  parameters.threads = threads;
  // A PIC share, so both velocity paths are exercised (APIC has no FLIP part).
  parameters.flip_fraction = S::transfer_type::affine ? 1.0 : 0.95;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.time_step = 1e-4;  // below the stable step h / c = 0.1 / 37 m/s = 2.7e-3 s
  S sim(grid, TrackingElastic{}, parameters);
  set_up(sim, grid);
  return sim;
}

// Every field of two stores equal: values with ==, the state byte for byte.
template <class Store>
void check_identical(const Store& a, const Store& b) {
  REQUIRE(a.size() == b.size());
  a.for_each_field([&](auto tag, const auto& column) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const auto& other = b.template get<Tag>();
    bool equal = true;
    for (std::size_t p = 0; p < column.size(); ++p) {
      if constexpr (std::is_same_v<V, material::PlasticState>) {
        equal = equal && std::memcmp(&column[p], &other[p], sizeof(V)) == 0;
      } else {
        equal = equal && column[p] == other[p];
      }
    }
    CHECK_MESSAGE(equal, std::string(Tag::label()));
  });
}

std::string error_of(auto&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
}  // namespace

// Runs first + second steps straight, and first steps, checkpoint, load into a fresh
// simulation (with `restart_threads` threads), second steps; all fields must agree with ==.
template <class S>
void check_restart(const std::string& name, int restart_threads) {
  const auto dir = output_dir("restart_" + name);
  const int first = 40, second = 35;
  const double dt = 1e-4;

  auto straight = make_sim<S>();
  for (int i = 0; i < first + second; ++i) straight.step(dt);

  auto before = make_sim<S>();
  for (int i = 0; i < first; ++i) before.step(dt);
  io::save_checkpoint(before, dir / "at_40.h5");

  auto restarted = make_sim<S>(block_grid, restart_threads);
  io::load_checkpoint(restarted, dir / "at_40.h5");
  CHECK(restarted.time() == before.time());
  CHECK(restarted.step_count() == first);
  check_identical(restarted.particles(), before.particles());
  for (int i = 0; i < second; ++i) restarted.step(dt);

  CHECK(restarted.time() == straight.time());
  CHECK(restarted.step_count() == straight.step_count());
  check_identical(restarted.particles(), straight.particles());
  // The run did something: the state and the positions changed from the start.
  const auto& state = straight.particles().template get<field::MaterialState<TrackingElastic>>();
  CHECK(state[0].plastic_shear_strain > 0.0);
  const auto& x = straight.particles().template get<field::Position<2>>();
  const auto& x0 = straight.particles().template get<field::InitialPosition<2>>();
  CHECK(x[0] != x0[0]);
}

TEST_CASE("a run restarted from a checkpoint continues bit-identically") {
  SUBCASE("USL") {
    check_restart<Sim<>>("usl", 0);
  }
  SUBCASE("MUSL") {
    check_restart<Sim<shape::Linear, integrator::MUSL>>("musl", 0);
  }
  SUBCASE("USF") {
    check_restart<Sim<shape::Linear, integrator::USF>>("usf", 0);
  }
  // The engine's sums do not depend on the thread count, so neither does the restart.
  SUBCASE("USL restarted on one thread") {
    check_restart<Sim<>>("usl_one_thread", 1);
  }
  // APIC adds the affine moment to the particles.
  SUBCASE("MUSL with APIC") {
    check_restart<ApicSim>("apic", 0);
  }
}

namespace {
// The block of make_sim and a lone particle shot up through the open top (y = 1), so it
// leaves the grid after about 100 steps.
Sim<> shot_block(StrayParticles policy) {
  SimulationParameters<2> parameters;
  parameters.flip_fraction = 0.95;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.time_step = 1e-4;
  parameters.stray_particles = policy;
  Sim<> sim(block_grid, TrackingElastic{}, parameters);
  set_up(sim);
  const auto seeding = particles::seed_box(block_grid, Vec<2>(0.2, 0.0), Vec<2>(0.6, 0.5), 2);
  const Index shot =
      sim.add_particles({Vec<2>(0.06, 0.95)}, seeding.volume, 1000.0, seeding.half_width);
  sim.particles().get<field::Velocity<2>>()[shot] = Vec<2>(0.0, 5.0);
  return sim;
}
}  // namespace

TEST_CASE("a run that lost particles off the grid restarts bit-identically") {
  for (const StrayParticles policy : {StrayParticles::freeze, StrayParticles::remove}) {
    const bool freeze = policy == StrayParticles::freeze;
    CAPTURE(freeze);
    const auto dir = output_dir(freeze ? "strays_frozen" : "strays_removed");
    const int first = 150, second = 40;
    auto straight = shot_block(policy);
    for (int i = 0; i < first + second; ++i) straight.step(1e-4);
    auto before = shot_block(policy);
    for (int i = 0; i < first; ++i) before.step(1e-4);
    REQUIRE(before.stray_particles().count == 1);  // the shot particle left before the save
    io::save_checkpoint(before, dir / "after_stray.h5");

    auto restarted = shot_block(policy);
    io::load_checkpoint(restarted, dir / "after_stray.h5");
    CHECK(restarted.particles().size() == before.particles().size());
    for (int i = 0; i < second; ++i) restarted.step(1e-4);
    check_identical(restarted.particles(), straight.particles());
    check_identical(restarted.frozen_particles(), straight.frozen_particles());
    CHECK(restarted.frozen_particles().size() == (freeze ? 1 : 0));
    CHECK(restarted.stray_particles().count == straight.stray_particles().count);
    CHECK(restarted.stray_particles().mass == straight.stray_particles().mass);
    // A simulation set up with another particle count is refused, naming both counts.
    auto other = make_sim<Sim<>>();
    CHECK(contains(error_of([&] { io::load_checkpoint(other, dir / "after_stray.h5"); }),
                   "and 1 that left the grid but the simulation has"));
  }
}

TEST_CASE("checkpoints keep special doubles and the state bit for bit") {
  const auto dir = output_dir("special_values");
  Store2 store = random_store(6);
  auto& stress = store.get<field::Stress<PlasticModel>>();
  stress[0][0] = -0.0;
  stress[0][1] = std::numeric_limits<double>::denorm_min();
  stress[0][2] = std::numeric_limits<double>::infinity();
  stress[0][3] = std::bit_cast<double>(std::uint64_t{0x7ff8'0000'dead'beefULL});  // NaN payload
  store.get<field::Body>()[1] = std::numeric_limits<std::int32_t>::min();
  io::write_checkpoint(dir / "special.h5", store, {1.5, 7}, "test=special");
  Store2 loaded;
  const auto clock = io::read_checkpoint(dir / "special.h5", loaded, "test=special");
  CHECK(clock.time == 1.5);
  CHECK(clock.step_count == 7);
  REQUIRE(loaded.size() == store.size());
  // Compare raw bits so -0.0 and the NaN payload count.
  const auto& back = loaded.get<field::Stress<PlasticModel>>();
  for (std::size_t p = 0; p < stress.size(); ++p) {
    for (int k = 0; k < 4; ++k) {
      CHECK(std::bit_cast<std::uint64_t>(back[p][k]) == std::bit_cast<std::uint64_t>(stress[p][k]));
    }
  }
  CHECK(loaded.get<field::Body>() == store.get<field::Body>());
  // Every field with ==, once the NaN (never == itself) is replaced in both.
  stress[0][3] = 0.0;
  loaded.get<field::Stress<PlasticModel>>()[0][3] = 0.0;
  check_identical(loaded, store);
}

TEST_CASE("an empty store checkpoints and loads") {
  const auto dir = output_dir("empty");
  Store2 empty;
  io::write_checkpoint(dir / "empty.h5", empty, {0.0, 0}, "test=empty");
  Store2 loaded = random_store(3);
  io::read_checkpoint(dir / "empty.h5", loaded, "test=empty");
  CHECK(loaded.size() == 0);
}

TEST_CASE("loading a checkpoint of another composition names the file and the mismatch") {
  const auto dir = output_dir("mismatch");
  auto sim = make_sim<Sim<>>();
  sim.step(1e-4);
  const auto path = dir / "linear_usl.h5";
  io::save_checkpoint(sim, path);

  auto quadratic = make_sim<Sim<shape::QuadraticBSpline>>();
  const std::string kernel_error = error_of([&] { io::load_checkpoint(quadratic, path); });
  MESSAGE(kernel_error);
  CHECK(contains(kernel_error, path.string()));
  CHECK(contains(kernel_error, "kernel is 'Linear' in the file but 'QuadraticBSpline'"));

  auto musl = make_sim<Sim<shape::Linear, integrator::MUSL>>();
  const std::string scheme_error = error_of([&] { io::load_checkpoint(musl, path); });
  CHECK(contains(scheme_error, "scheme is 'USL' in the file but 'MUSL'"));

  // The velocity transfer and the anti-locking policy are part of the composition.
  CHECK(contains(io::composition_signature(sim), "transfer=PIC/FLIP blend"));
  CHECK(contains(io::composition_signature(sim), "antilocking=none"));
  auto apic = make_sim<ApicSim>();
  CHECK(contains(io::composition_signature(apic), "transfer=APIC"));

  // Same particle count on a grid shifted by one cell: the geometry differs.
  const grid::Grid<2> shifted(Vec<2>(-0.1, 0.0), Vec<2>(1.1, 1.0), {11, 10});
  auto other_grid = make_sim<Sim<>>(shifted);
  REQUIRE(other_grid.particles().size() == sim.particles().size());
  const std::string grid_error = error_of([&] { io::load_checkpoint(other_grid, path); });
  CHECK(contains(grid_error, "grid.cells is '10 10' in the file but '11 10'"));

  // A simulation not set up like the original (no particles added).
  SimulationParameters<2> parameters;
  Sim<> bare(block_grid, TrackingElastic{}, parameters);
  const std::string count_error = error_of([&] { io::load_checkpoint(bare, path); });
  CHECK(contains(count_error, "holds " + std::to_string(sim.particles().size()) +
                                  " particles but the simulation has 0"));

  // Store level: other field types.
  const std::string store_error =
      error_of([&] { io::read_checkpoint(path, sim.particles(), "dim=3"); });
  CHECK(contains(store_error, "dim is '2' in the file but '3'"));
}

TEST_CASE("damaged or foreign checkpoint files give an Error naming the file") {
  const auto dir = output_dir("corrupt");
  Store2 store = random_store(2000);
  // A distinctive value whose bytes we can find in the file.
  const double marker = 0.123456789012345;
  store.get<field::Mass>()[1000] = marker;
  const auto good = dir / "good.h5";
  io::write_checkpoint(good, store, {1.0, 10}, "test=corrupt");
  std::string bytes;
  {
    std::ifstream in(good, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    bytes = buffer.str();
  }
  Store2 loaded = random_store(5);
  const Store2 untouched = loaded;

  SUBCASE("missing file") {
    const std::string error =
        error_of([&] { io::read_checkpoint(dir / "missing.h5", loaded, "test=corrupt"); });
    CHECK(contains(error, "missing.h5"));
  }
  SUBCASE("not an HDF5 file") {
    std::ofstream(dir / "text.h5") << "this is not a checkpoint\n";
    const std::string error =
        error_of([&] { io::read_checkpoint(dir / "text.h5", loaded, "test=corrupt"); });
    CHECK(contains(error, "text.h5"));
    CHECK(contains(error, "cannot open"));
  }
  SUBCASE("truncated file") {
    std::ofstream(dir / "truncated.h5", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string error =
        error_of([&] { io::read_checkpoint(dir / "truncated.h5", loaded, "test=corrupt"); });
    CHECK(contains(error, "truncated.h5"));
  }
  SUBCASE("a flipped bit in the data fails the checksum") {
    char pattern[sizeof(double)];
    std::memcpy(pattern, &marker, sizeof(double));
    const auto at = bytes.find(std::string(pattern, sizeof(double)));
    REQUIRE(at != std::string::npos);
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x01);
    std::ofstream(dir / "flipped.h5", std::ios::binary) << damaged;
    const std::string error =
        error_of([&] { io::read_checkpoint(dir / "flipped.h5", loaded, "test=corrupt"); });
    MESSAGE(error);
    CHECK(contains(error, "flipped.h5"));
    CHECK(contains(error, "/particles/mass"));
  }
  SUBCASE("a frame file is not a checkpoint") {
    io::ParticleFrameWriter writer(dir, "frame");
    const auto frame = writer.write(store, 0.0, 0);
    const std::string error = error_of([&] { io::read_checkpoint(frame, loaded, "test=corrupt"); });
    CHECK(contains(error, "is not a cosmpm checkpoint"));
  }
  // A failed load leaves the destination as it was.
  check_identical(loaded, untouched);
}

TEST_CASE("frames written before a run goes unstable stay readable, grid fields included") {
  const auto dir = output_dir("unstable_run");
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.time_step = 1e-4;
  Sim<> sim(block_grid, TrackingElastic{}, parameters);
  set_up(sim);
  io::ParticleFrameWriter writer(dir, "run", {.grid_fields = true});
  sim.step(1e-4);
  writer.write(sim);
  // A step 1000 times the stable one throws the run away (particles leave or blow up).
  std::string error;
  try {
    for (int i = 0; i < 50; ++i) {
      sim.step(1.0);
      writer.write(sim);
    }
  } catch (const Error& e) {
    error = e.what();
  }
  MESSAGE(error);
  CHECK_FALSE(error.empty());
  const Index frames = writer.frame_count();
  CHECK(frames >= 1);
  for (Index f = 0; f < frames; ++f) {
    CHECK(read_raw(writer.frame_path(f), "/particles/position").ok);
    CHECK(read_raw(writer.frame_path(f), "/grid/mass").ok);
  }
  const RawDataset mass = read_raw(writer.frame_path(0), "/grid/mass");
  const RawDataset nodes = read_raw(writer.frame_path(0), "/grid/position");
  CHECK(mass.dims == std::vector<hsize_t>{121});  // 11 x 11 nodes
  CHECK(nodes.dims == std::vector<hsize_t>{121, 3});
  // Node 12 = (i, j) = (1, 1) sits at (0.1, 0.1): x fastest numbering, exact products.
  CHECK(nodes.values[3 * 12] == 0.1);
  CHECK(nodes.values[3 * 12 + 1] == 0.1);
  // Mass is conserved on the grid: sum of node masses = particle mass (partition of unity),
  // to rounding (relative 1e-12).
  double grid_mass = 0.0;
  for (const double m : mass.values) grid_mass += m;
  double particle_mass = 0.0;
  for (const double m : sim.particles().get<field::Mass>()) particle_mass += m;
  CHECK(grid_mass == doctest::Approx(particle_mass).epsilon(1e-12));
  std::ifstream xdmf(writer.grid_xdmf_path());
  std::stringstream text;
  text << xdmf.rdbuf();
  CHECK(contains(text.str(), "Name=\"grid\""));
  CHECK(contains(text.str(), "run_000000.h5:/grid/velocity"));
}

TEST_CASE("a restarted simulation resumes its frame series, grid meshes included") {
  const auto dir = output_dir("resume_sim");
  const double dt = 1e-4;
  auto sim = make_sim<Sim<>>();
  {
    io::ParticleFrameWriter writer(dir, "run", {.grid_fields = true});
    for (int f = 0; f < 3; ++f) {
      sim.step(dt);
      writer.write(sim);
      if (f == 1) io::save_checkpoint(sim, dir / "restart.h5");
    }
  }
  auto restarted = make_sim<Sim<>>();
  io::load_checkpoint(restarted, dir / "restart.h5");
  io::ParticleFrameWriter writer(dir, "run", {.grid_fields = true});
  // Frames 0 and 1 were written at or before the checkpoint's time; frame 2 is redone.
  CHECK(writer.resume(restarted) == 2);
  restarted.step(dt);
  CHECK(writer.write(restarted) == dir / "run_000002.h5");
  // The redone step reaches the state the frame was first written from, bit for bit.
  check_identical(restarted.particles(), sim.particles());
  CHECK(read_raw(dir / "run_000002.h5", "/particles/stress").ok);
  std::ifstream xdmf(writer.grid_xdmf_path());
  std::stringstream text;
  text << xdmf.rdbuf();
  for (const char* reference : {"run_000000.h5:/grid/position", "run_000001.h5:/grid/velocity",
                                "run_000002.h5:/grid/mass"}) {
    CHECK_MESSAGE(contains(text.str(), reference), reference);
  }
}

namespace {
// A contact law with state that time alone does not give back (it accumulates), exposing the
// checkpoint hooks; the rigid-body laws need the same to restart bit-identically.
struct DriftingContact {
  static constexpr const char* name() { return "drifting"; }
  Vec<2> offset = Vec<2>::Zero();
  template <int Dim>
  void correct(contact::GridView<Dim>& /*view*/) {}
  void advance(double dt, double time) { offset += dt * Vec<2>(1.0 + time, 0.1 / 3.0); }
  std::vector<double> checkpoint_values() const { return {offset[0], offset[1]}; }
  void restore_checkpoint_values(const std::vector<double>& values) {
    REQUIRE(values.size() == 2);
    offset = Vec<2>(values[0], values[1]);
  }
};
using DriftingSim =
    Simulation<2, shape::Linear, continuum::Classical<TrackingElastic>, DriftingContact>;
}  // namespace

TEST_CASE("a contact law's own state is checkpointed through its hooks") {
  const auto dir = output_dir("contact_state");
  auto straight = make_sim<DriftingSim>();
  for (int i = 0; i < 20; ++i) straight.step(1e-4);
  auto before = make_sim<DriftingSim>();
  for (int i = 0; i < 10; ++i) before.step(1e-4);
  io::save_checkpoint(before, dir / "drift.h5");
  auto restarted = make_sim<DriftingSim>();
  io::load_checkpoint(restarted, dir / "drift.h5");
  CHECK(restarted.contact().offset == before.contact().offset);
  for (int i = 0; i < 10; ++i) restarted.step(1e-4);
  CHECK(restarted.contact().offset == straight.contact().offset);
  check_identical(restarted.particles(), straight.particles());
  CHECK(contains(io::composition_signature(restarted), "contact_state=yes"));
}

TEST_CASE("a caller's own values travel with the checkpoint bit for bit") {
  const auto dir = output_dir("caller_values");
  auto sim = make_sim<Sim<>>();
  sim.step(1e-4);
  io::CheckpointValues values;
  values.set("draft_sum", 0.1 + 0.2);  // 0.30000000000000004: needs every bit
  values.set("next_frame", -0.0);
  values.set("averaged_steps", 12345.0);
  values.set("draft_sum", 0.1 + 0.7);  // set again: replaced, not duplicated
  io::save_checkpoint(sim, dir / "with_values.h5", values);
  auto restarted = make_sim<Sim<>>();
  const io::CheckpointValues loaded = io::load_checkpoint(restarted, dir / "with_values.h5");
  REQUIRE(loaded.entries().size() == 3);
  CHECK(std::bit_cast<std::uint64_t>(loaded.get("draft_sum")) ==
        std::bit_cast<std::uint64_t>(0.1 + 0.7));
  CHECK(std::signbit(loaded.get("next_frame")));
  CHECK(loaded.get("averaged_steps") == 12345.0);
  CHECK(contains(error_of([&] { (void)loaded.get("missing", "restart"); }),
                 "restart: holds no value 'missing'"));
  CHECK_THROWS_AS(values.set("two\nlines", 1.0), Error);
  // A checkpoint without values loads with none.
  io::save_checkpoint(sim, dir / "without_values.h5");
  CHECK(io::load_checkpoint(restarted, dir / "without_values.h5").empty());
}
