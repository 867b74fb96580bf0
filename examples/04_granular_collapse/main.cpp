// Example 04: a column of dry cohesionless soil released under gravity flows to rest; the
// deposit is compared with the true-2D collapse experiments of "Failure Mechanism of True 2D
// Granular Flows" (arXiv:1512.05180, 2015, the group of Bui and Fukagawa): aluminium rods in a
// column against a wall on a horizontal floor:
//   final height      h0 / h = 1.42 a^(2/3)                      (a > 0.65)
//   runout from wall  d / d0 = 4.30 a^0.72                       (a > 0.65)
//                     (d - d0) / d0 = 3.25 a^0.96                (0.65 < a < 1.5)
// with a = h0 / d0 the column's height over its width. The rods are the material of Bui,
// Fukagawa, Sako and Ohno (2008): phi = 19.8 deg, c = 0, psi = 0, E = 0.84 MPa, nu = 0.3,
// rho = 2650 kg/m^3 (docs/validation.md, "Granular flow to rest", says where each number is
// read from).
//
// The column stands at rest under K0 = 1 - sin(phi) against the left wall (a roller: smooth)
// and is released at t = 0; the floor is fixed (no slip) or a Coulomb friction wall. The run
// ends when the grid's kinetic energy has stayed below --rest-fraction of the column's
// potential energy m g h0 / 2 for --rest-time seconds, or at --end-time.
//
//   example_04_granular_collapse [--shape quadratic] [--scheme musl] [--cell 0.0025]
//                                [--ppc 2] [--transfer blend] [--flip 0.99] [--floor fixed]
//                                [--wall X] [--out DIR] ...
//   example_04_granular_collapse --help
//
// The run declares itself a free-surface flow (SimulationParameters::free_surface_flow), so
// the compositions known to fail one (linear shape functions, pure FLIP) stop at once with
// the reason unless --allow-fragile true. --wall X puts a fixed rigid wall with Coulomb
// friction across the floor at x = X (contact::RigidContact; without it the law has no body
// and changes nothing).
//
// Writes to --out: series.csv (energies, fronts, against time), profile.csv (the final
// deposit), summary.txt (name = value: outcome, runout, tail mass, run time, the reference),
// failure.txt when the run stopped (the particle the engine named and its neighbourhood) and
// frames/collapse.xdmf (ParaView). scripts/plot_granular_collapse.py draws the PNGs. Exit
// status: 0 at rest, 2 still moving at --end-time, 1 stopped by an error.
#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cosmpm/analysis.hpp"
#include "cosmpm/cosmpm.hpp"
#include "cosmpm/io/hdf5.hpp"

namespace {
using namespace cosmpm;
namespace fs = std::filesystem;

// The wall's thickness: wider than any kernel's support, so no node sees through it.
constexpr double wall_thickness_cells = 4.0;

struct Options {
  std::string shape = "quadratic";  // linear, gimp, quadratic, cubic
  std::string scheme = "musl";      // usl, musl, usf
  double cell = 0.0025;             // m, square cells
  int ppc = 2;                      // particles per cell and axis
  std::string transfer = "blend";   // blend (PIC/FLIP, --flip) or apic
  double flip = 0.99;               // FLIP fraction of the velocity update (blend only)
  // A fixed (no-slip) floor, or a Coulomb floor; mu = tan(19.8 deg) makes it as rough as the
  // rods' internal friction (no source we could read gives the rods' friction on the floor).
  // docs/validation.md, "Granular flow to rest", says why the default is fixed.
  std::string floor = "fixed";  // fixed or friction
  double floor_friction = 0.36;
  // A fixed rigid wall across the floor at x = wall (its face towards the column; 0: none),
  // with Coulomb friction wall_friction: contact::RigidContact with a body that does not move.
  double wall = 0.0, wall_friction = 0.36;
  // Runs a composition the library rejects for free-surface flows (linear, pure FLIP).
  bool allow_fragile = false;
  // The column (a = 1) and the rods of Bui et al. (2008).
  double column_height = 0.1, column_width = 0.1;  // h0, d0 in m
  double friction_angle = 19.8, dilatancy_angle = 0.0;
  double youngs_modulus = 0.84e6, poisson_ratio = 0.3, density = 2650.0;
  double grid_length = 0.8;  // m of floor
  double end_time = 2.0, rest_fraction = 1e-6, rest_time = 0.05;
  double frame_interval = 0.05, record_interval = 5e-4;  // s
  double cfl = 0.5;
  double empty_node_fraction = 1e-12;  // SimulationParameters::empty_node_mass_fraction
  int threads = 0;
  bool frames = true;
  long trace = -1;  // a particle whose every step goes to trace.csv
  std::string out;  // default out/04_granular_collapse/<tag>

  std::string tag() const {
    std::ostringstream name;
    name << shape << "_" << scheme << "_h" << cell * 1e3 << "mm_ppc" << ppc;
    if (transfer == "apic") {
      name << "_apic";
    } else {
      name << "_flip" << flip;
    }
    name << "_" << floor;
    if (wall > 0.0) name << "_wall" << wall;
    if (empty_node_fraction != 1e-12) name << "_empty" << empty_node_fraction;
    return name.str();
  }
};

const char* usage =
    "usage: example_04_granular_collapse [--name value]...\n"
    "  --shape linear|gimp|quadratic|cubic   shape functions                [quadratic]\n"
    "  --scheme usl|musl|usf                 update scheme                  [musl]\n"
    "  --cell M          cell size, (0, 0.05]                               [0.0025]\n"
    "  --ppc N           particles per cell and axis, 1..4                  [2]\n"
    "  --transfer blend|apic    PIC/FLIP blend or APIC (not with linear)    [blend]\n"
    "  --flip F          FLIP fraction of the blend, [0, 1]                 [0.99]\n"
    "  --floor fixed|friction   the floor under the column                  [fixed]\n"
    "  --floor-friction MU      Coulomb coefficient of a friction floor     [0.36]\n"
    "  --wall X                 a fixed rigid wall with its face at x = X   [none]\n"
    "  --wall-friction MU       its Coulomb coefficient                     [0.36]\n"
    "  --allow-fragile true|false  run linear or pure-FLIP compositions     [false]\n"
    "  --height M --width M     the column h0 and d0                        [0.1 0.1]\n"
    "  --phi DEG --psi DEG      friction and dilatancy angles               [19.8 0]\n"
    "  --E PA --nu N --rho KG   Young's modulus, Poisson ratio, density     [0.84e6 0.3 2650]\n"
    "  --grid-length M          floor length in the grid                    [0.8]\n"
    "  --end-time S             longest simulated time                      [2]\n"
    "  --rest-fraction F        rest: grid kinetic energy / (m g h0 / 2)    [1e-6]\n"
    "  --rest-time S            ... held for this long                      [0.05]\n"
    "  --frame-interval S       between ParaView frames                     [0.05]\n"
    "  --frames true|false      write ParaView frames                       [true]\n"
    "  --empty-node-fraction F  nodes lighter than F x particle mass are empty [1e-12]\n"
    "  --trace P                particle P's state and cell, every step, to trace.csv\n"
    "  --cfl F --threads N --out DIR\n";

double number(std::string_view flag, std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) {
    throw Error("command line: " + std::string(flag) + " = '" + std::string(text) +
                "' is not a number");
  }
  return value;
}

int whole(std::string_view flag, std::string_view text, int lo, int hi) {
  const double value = number(flag, text);
  require_in_range("command line", flag, value, lo, hi, Bounds::closed);
  if (value != std::floor(value)) {
    throw Error("command line: " + std::string(flag) + " = " + std::string(text) +
                " must be a whole number");
  }
  return static_cast<int>(value);
}

std::string one_of(std::string_view flag, std::string_view text,
                   std::initializer_list<std::string_view> valid) {
  for (auto v : valid) {
    if (text == v) return std::string(text);
  }
  std::string list;
  for (auto v : valid) list += (list.empty() ? "" : ", ") + std::string(v);
  throw Error("command line: " + std::string(flag) + " = '" + std::string(text) +
              "' is not one of " + list);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::cout << usage;
      std::exit(0);
    }
    if (i + 1 >= argc) throw Error("command line: " + std::string(flag) + " needs a value");
    const std::string_view text = argv[++i];
    const auto positive = [&](double& target) {
      target = number(flag, text);
      require_positive("command line", flag, target);
    };
    if (flag == "--shape") {
      o.shape = one_of(flag, text, {"linear", "gimp", "quadratic", "cubic"});
    } else if (flag == "--scheme") {
      o.scheme = one_of(flag, text, {"usl", "musl", "usf"});
    } else if (flag == "--cell") {
      o.cell = number(flag, text);
      require_in_range("command line", flag, o.cell, 0.0, 0.05, Bounds::right_closed);
    } else if (flag == "--ppc") {
      o.ppc = whole(flag, text, 1, 4);
    } else if (flag == "--transfer") {
      o.transfer = one_of(flag, text, {"blend", "apic"});
    } else if (flag == "--flip") {
      o.flip = number(flag, text);
      require_in_range("command line", flag, o.flip, 0.0, 1.0, Bounds::closed);
    } else if (flag == "--floor") {
      o.floor = one_of(flag, text, {"fixed", "friction"});
    } else if (flag == "--floor-friction") {
      o.floor_friction = number(flag, text);
      require_non_negative("command line", flag, o.floor_friction);
    } else if (flag == "--wall") {
      positive(o.wall);
    } else if (flag == "--wall-friction") {
      o.wall_friction = number(flag, text);
      require_non_negative("command line", flag, o.wall_friction);
    } else if (flag == "--allow-fragile") {
      o.allow_fragile = one_of(flag, text, {"true", "false"}) == "true";
    } else if (flag == "--height") {
      positive(o.column_height);
    } else if (flag == "--width") {
      positive(o.column_width);
    } else if (flag == "--phi") {
      o.friction_angle = number(flag, text);  // MohrCoulomb checks the range
    } else if (flag == "--psi") {
      o.dilatancy_angle = number(flag, text);
    } else if (flag == "--E") {
      positive(o.youngs_modulus);
    } else if (flag == "--nu") {
      o.poisson_ratio = number(flag, text);
    } else if (flag == "--rho") {
      positive(o.density);
    } else if (flag == "--grid-length") {
      positive(o.grid_length);
    } else if (flag == "--end-time") {
      positive(o.end_time);
    } else if (flag == "--rest-fraction") {
      positive(o.rest_fraction);
    } else if (flag == "--rest-time") {
      positive(o.rest_time);
    } else if (flag == "--frame-interval") {
      positive(o.frame_interval);
    } else if (flag == "--frames") {
      o.frames = one_of(flag, text, {"true", "false"}) == "true";
    } else if (flag == "--cfl") {
      o.cfl = number(flag, text);  // SimulationParameters checks the range
    } else if (flag == "--threads") {
      o.threads = whole(flag, text, 0, 4096);
    } else if (flag == "--empty-node-fraction") {
      o.empty_node_fraction = number(flag, text);  // SimulationParameters checks the range
    } else if (flag == "--trace") {
      o.trace = whole(flag, text, 0, 1 << 30);
    } else if (flag == "--out") {
      o.out = std::string(text);
    } else {
      throw Error("command line: unknown option '" + std::string(flag) + "' (see --help)");
    }
  }
  // Whole cells: the column and the grid edges on nodes, so every run seeds the same shape.
  for (double length : {o.column_height, o.column_width, o.grid_length}) {
    const double cells = length / o.cell;
    if (std::abs(cells - std::round(cells)) > 1e-9 * cells) {
      throw Error(
          "command line: the column height and width and the grid length must be whole "
          "multiples of --cell = " +
          detail::format_number(o.cell) + " m (" + detail::format_number(length) + " m is not)");
    }
  }
  if (o.transfer == "apic" && o.shape == "linear") {
    throw Error(
        "command line: --transfer apic needs a kernel with a continuous gradient (gimp, "
        "quadratic, cubic), not --shape linear (include/cosmpm/transfer/apic.hpp says why)");
  }
  require_in_range("command line", "--width", o.column_width, 0.0, 0.5 * o.grid_length,
                   Bounds::right_closed);
  if (o.wall > 0.0) {
    require_in_range("command line", "--wall", o.wall, o.column_width + 2.0 * o.cell,
                     o.grid_length - wall_thickness_cells * o.cell, Bounds::closed);
  }
  return o;
}

using Soil = material::MohrCoulomb<>;

// What a run did, for summary.txt and the console.
struct Outcome {
  std::string status = "running";  // rest, stopped, end-time
  std::string error;
  double time = 0.0, rest_time = NAN;
  long steps = 0, particles = 0;
  double dt = 0.0, wall_seconds = 0.0;
  double deposit_front = NAN, extreme_front = NAN, tail_mass_fraction = NAN;
  double height_at_wall = NAN, max_volume_ratio = NAN;
  double grid_energy = NAN, particle_energy = NAN, energy_scale = NAN;
  long anomaly_step = -1;        // the first step a particle exceeded sqrt(2 g 2 h0)
  Vec<2> wall_force{NAN, NAN};   // the soil's force on the wall in the last step, N/m
  double deepest_in_wall = NAN;  // largest particle depth past the wall's face, m
};

// A particle's state and the node masses around it (node mass over the particle's mass, at
// the 4 x 4 nodes around where it started the last step), for the diagnosis of a run.
template <class Sim>
std::string describe_particle(const Sim& sim, Index p) {
  namespace field = particles::field;
  const auto& store = sim.particles();
  const auto& x = store.template get<field::Position<2>>();
  const auto& grid = sim.grid();
  std::ostringstream text;
  text.precision(8);
  text << "step = " << sim.step_count() << "\ntime_s = " << sim.time() << "\nparticle = " << p
       << "\nposition = " << x[p].transpose()
       << "\ninitial_position = " << store.template get<field::InitialPosition<2>>()[p].transpose()
       << "\nvelocity = " << store.template get<field::Velocity<2>>()[p].transpose()
       << "\nvolume_ratio = "
       << store.template get<field::DeformationGradient<2>>()[p].determinant()
       << "\nstress = " << store.template get<field::Stress<Soil>>()[p].transpose()
       << "\nheight_above_floor_cells = " << x[p][1] / grid.cell_size()[1] << "\n";
  const auto& start = sim.engine().stencil_cells;
  if (static_cast<std::size_t>(p) >= start.size()) return text.str();
  const Vec<2> cell_units = start[static_cast<std::size_t>(p)];
  text << "step_start_position_cells = " << cell_units.transpose() << "\n";
  const Index i0 = static_cast<Index>(std::floor(cell_units[0])) - 1;
  const Index j0 = static_cast<Index>(std::floor(cell_units[1])) - 1;
  text << "node_mass_over_particle_mass (rows j = " << j0 + 3 << " .. " << j0
       << ", columns i = " << i0 << " .. " << i0 + 3 << "):\n";
  const double mass = store.template get<field::Mass>()[p];
  for (Index j = j0 + 3; j >= j0; --j) {
    for (Index i = i0; i <= i0 + 3; ++i) {
      if (i < 0 || j < 0 || i >= grid.nodes(0) || j >= grid.nodes(1)) {
        text << "       -";
        continue;
      }
      char cell[32];
      std::snprintf(cell, sizeof(cell), " %7.3g", sim.nodes().mass[grid.node_index({i, j})] / mass);
      text << cell;
    }
    text << "\n";
  }
  return text.str();
}

// The particle the engine named: the lowest index with a non-finite state, det F <= 0 or a
// position outside the grid; -1 if none.
template <class Sim>
Index unsound_particle(const Sim& sim) {
  namespace field = particles::field;
  const auto& store = sim.particles();
  const auto& x = store.template get<field::Position<2>>();
  const auto& v = store.template get<field::Velocity<2>>();
  const auto& F = store.template get<field::DeformationGradient<2>>();
  const auto& stress = store.template get<field::Stress<Soil>>();
  for (Index p = 0; p < store.size(); ++p) {
    if (!x[p].allFinite() || !v[p].allFinite() || !stress[p].allFinite() ||
        !(F[p].determinant() > 0.0) || !sim.grid().contains(x[p])) {
      return p;
    }
  }
  return -1;
}

// The fastest particle, if faster than `bound`; -1 otherwise.
template <class Sim>
Index faster_than(const Sim& sim, double bound) {
  const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  Index fastest = -1;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    if (v[p].norm() > bound && (fastest < 0 || v[p].norm() > v[fastest].norm())) fastest = p;
  }
  return fastest;
}

// One row per step of particle p: its state, and the nodes of the cell it started the step in
// (node mass over the particle's mass, node velocity at the end of the step).
template <class Sim>
class ParticleTrace {
 public:
  ParticleTrace(const fs::path& path, Index particle)
      : particle_(particle),
        csv_(path,
             {"step", "time_s", "x",       "y",      "vx",     "vy",   "volume_ratio", "sxx", "syy",
              "szz",  "sxy",    "plastic", "cell_i", "cell_j", "m00",  "m10",          "m01", "m11",
              "v00x", "v00y",   "v10x",    "v10y",   "v01x",   "v01y", "v11x",         "v11y"}) {}

  void write(const Sim& sim) {
    namespace field = particles::field;
    const auto& store = sim.particles();
    require(particle_ < store.size(), "example_04: --trace names no particle");
    const Index p = particle_;
    const Vec<2> x = store.template get<field::Position<2>>()[p];
    const Vec<2> v = store.template get<field::Velocity<2>>()[p];
    const auto& s = store.template get<field::Stress<Soil>>()[p];
    const double m = store.template get<field::Mass>()[p];
    const auto& cells = sim.engine().stencil_cells;
    const Vec<2> start = static_cast<std::size_t>(p) < cells.size()
                             ? cells[static_cast<std::size_t>(p)]
                             : sim.grid().to_cell_units(x);
    const Index i = static_cast<Index>(std::floor(start[0]));
    const Index j = static_cast<Index>(std::floor(start[1]));
    std::vector<double> row{static_cast<double>(sim.step_count()),
                            sim.time(),
                            x[0],
                            x[1],
                            v[0],
                            v[1],
                            store.template get<field::DeformationGradient<2>>()[p].determinant(),
                            s[0],
                            s[1],
                            s[2],
                            s[3],
                            store.template get<field::MaterialState<Soil>>()[p].plastic,
                            static_cast<double>(i),
                            static_cast<double>(j)};
    const auto& grid = sim.grid();
    const auto node = [&](Index a, Index b) {
      return grid.node_index(
          {std::clamp<Index>(a, 0, grid.nodes(0) - 1), std::clamp<Index>(b, 0, grid.nodes(1) - 1)});
    };
    const std::array<Index, 4> nodes{node(i, j), node(i + 1, j), node(i, j + 1),
                                     node(i + 1, j + 1)};
    for (Index n : nodes) row.push_back(sim.nodes().mass[n] / m);
    for (Index n : nodes) {
      row.push_back(sim.nodes().velocity[n][0]);
      row.push_back(sim.nodes().velocity[n][1]);
    }
    csv_.write_row(row);
  }

 private:
  Index particle_;
  io::CsvWriter csv_;
};

template <class Kernel, class Scheme, class Transfer>
Outcome run(const Options& o, const fs::path& out) {
  using Sim =
      Simulation<2, Kernel, continuum::Classical<Soil>, contact::RigidContact<2>, Scheme, Transfer>;
  const Soil soil({.youngs_modulus = o.youngs_modulus,
                   .poisson_ratio = o.poisson_ratio,
                   .friction_angle_deg = o.friction_angle,
                   .dilatancy_angle_deg = o.dilatancy_angle});
  // The grid: the floor at y = 0, the wall at x = 0, a quarter of the column's height of room
  // above it.
  const auto cells = [&](double length) {
    return static_cast<Index>(std::lround(length / o.cell));
  };
  const double grid_height = o.cell * static_cast<double>(cells(1.25 * o.column_height) + 1);
  const grid::Grid<2> grid(Vec<2>::Zero(), Vec<2>(o.grid_length, grid_height),
                           {cells(o.grid_length), cells(grid_height)});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  if (o.transfer == "blend") parameters.flip_fraction = o.flip;
  parameters.cfl = o.cfl;
  parameters.threads = o.threads;
  parameters.empty_node_mass_fraction = o.empty_node_fraction;
  parameters.free_surface_flow = true;
  parameters.allow_fragile_composition = o.allow_fragile;
  // Without --wall no body: RigidContact then changes nothing (the runs of SingleField).
  contact::RigidContact<2> walls;
  if (o.wall > 0.0) {
    walls.add_body(contact::RigidBody<2>::box(
                       Vec<2>(o.wall, -o.cell),
                       Vec<2>(o.wall + wall_thickness_cells * o.cell, grid_height + o.cell)),
                   contact::Interface::coulomb(o.wall_friction));
  }
  Sim sim(grid, soil, parameters, walls);
  const auto column = particles::seed_box(grid, Vec<2>(Vec<2>::Zero()),
                                          Vec<2>(o.column_width, o.column_height), o.ppc);
  sim.add_particles(column.positions, column.volume, o.density, column.half_width);
  // At rest under K0 = 1 - sin(phi) (Jaky), as the gate held it.
  const double k0 = initial::jaky_k0(o.friction_angle);
  {
    const auto& x = sim.particles().template get<particles::field::Position<2>>();
    auto& stress = sim.particles().template get<particles::field::Stress<Soil>>();
    for (Index p = 0; p < sim.particles().size(); ++p) {
      stress[p] = initial::geostatic_stress(o.density, 9.81, o.column_height - x[p][1], k0);
    }
  }
  using BC = grid::BoundaryConditions<2>;
  auto& bc = sim.boundary_conditions();
  bc.set(BC::face(0, false), grid::BoundaryKind::roller);  // the wall the column stands at
  bc.set(BC::face(0, true), grid::BoundaryKind::roller);
  if (o.floor == "fixed") {
    bc.set(BC::face(1, false), grid::BoundaryKind::fixed);
  } else {
    bc.set(BC::face(1, false), grid::BoundaryKind::friction, o.floor_friction);
  }

  Outcome outcome;
  outcome.particles = static_cast<long>(sim.particles().size());
  outcome.dt = sim.time_step();
  const double total_mass = analysis::mass_of(sim).mass;
  outcome.energy_scale = total_mass * 9.81 * 0.5 * o.column_height;
  const double potential_start = analysis::potential_energy(sim, parameters.gravity);
  const analysis::HeightProfileOptions profile_options{
      .from = 0.0, .to = o.grid_length, .bin_width = o.cell, .base = 0.0};
  // The deposit ends where less than a quarter cell of material is left (at initial density).
  const double min_thickness = 0.25 * o.cell;

  io::CsvWriter series(
      out / "series.csv",
      {"time_s", "grid_kinetic_J_per_m", "particle_kinetic_J_per_m", "potential_released_J_per_m",
       "deposit_front_m", "extreme_front_m", "max_particle_speed_m_per_s"});
  std::optional<io::ParticleFrameWriter> frames;
  if (o.frames) frames.emplace(out / "frames", "collapse");
  const auto record = [&] {
    const auto profile = analysis::height_profile(sim, profile_options);
    double fastest = 0.0;
    for (const auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
      fastest = std::max(fastest, v.norm());
    }
    series.write_row({sim.time(), analysis::grid_kinetic_energy(sim),
                      analysis::particle_kinetic_energy(sim),
                      potential_start - analysis::potential_energy(sim, parameters.gravity),
                      analysis::deposit_front(profile, min_thickness),
                      analysis::extreme_front(sim).position, fastest});
  };
  record();
  if (frames) frames->write(sim);
  std::optional<ParticleTrace<Sim>> trace;
  if (o.trace >= 0) trace.emplace(out / "trace.csv", static_cast<Index>(o.trace));

  const double fast_bound = std::sqrt(2.0 * 9.81 * 2.0 * o.column_height);
  io::ProgressReporter progress("granular collapse " + o.tag(), o.end_time, sim.particles().size());
  const auto wall_start = std::chrono::steady_clock::now();
  double next_frame = o.frame_interval, next_record = o.record_interval, quiet_since = NAN;
  try {
    while (sim.time() < o.end_time - 0.5 * outcome.dt) {
      sim.step(outcome.dt);
      progress.update(sim.time(), sim.step_count());
      if (trace) trace->write(sim);
      // The first particle faster than free fall from twice the column's height allows: where
      // a run that blows up starts to (anomaly.txt).
      if (outcome.anomaly_step < 0) {
        if (const Index fast = faster_than(sim, fast_bound); fast >= 0) {
          outcome.anomaly_step = static_cast<long>(sim.step_count());
          io::write_file_atomically(out / "anomaly.txt", describe_particle(sim, fast));
        }
      }
      const double grid_energy = analysis::grid_kinetic_energy(sim);
      if (grid_energy < o.rest_fraction * outcome.energy_scale) {
        if (std::isnan(quiet_since)) quiet_since = sim.time();
      } else {
        quiet_since = NAN;
      }
      if (sim.time() >= next_record - 1e-12) {
        record();
        next_record += o.record_interval;
      }
      if (frames && sim.time() >= next_frame - 1e-12) {
        frames->write(sim);
        next_frame += o.frame_interval;
      }
      if (!std::isnan(quiet_since) && sim.time() - quiet_since >= o.rest_time) {
        outcome.status = "rest";
        outcome.rest_time = quiet_since;
        break;
      }
    }
    if (outcome.status == "running") outcome.status = "end-time";
  } catch (const Error& error) {
    outcome.status = "stopped";
    outcome.error = error.what();
    if (trace) trace->write(sim);  // the state the step stopped in
    const Index bad = unsound_particle(sim);
    io::write_file_atomically(out / "failure.txt",
                              bad < 0 ? "no particle is unsound\n" : describe_particle(sim, bad));
  }
  progress.finish(sim.time(), sim.step_count());
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  outcome.time = sim.time();
  outcome.steps = static_cast<long>(sim.step_count());
  if (frames) frames->write(sim);  // the last state, also of a stopped run

  // The deposit (of a stopped run: the state it stopped in).
  const auto profile = analysis::height_profile(sim, profile_options);
  {
    io::CsvWriter csv(out / "profile.csv", {"x_m", "surface_m", "thickness_m", "particles"});
    for (std::size_t i = 0; i < profile.size(); ++i) {
      csv.write_row({profile.x[i], profile.surface[i], profile.thickness[i],
                     static_cast<double>(profile.count[i])});
    }
  }
  if (outcome.status != "stopped") {
    outcome.deposit_front = analysis::deposit_front(profile, min_thickness);
    outcome.extreme_front = analysis::extreme_front(sim).position;
    outcome.tail_mass_fraction =
        analysis::mass_beyond(sim, outcome.deposit_front).mass / total_mass;
    outcome.height_at_wall = profile.surface.front();
    double largest = 0.0;
    const auto& volume = sim.particles().template get<particles::field::Volume>();
    const auto& initial = sim.particles().template get<particles::field::InitialVolume>();
    for (std::size_t p = 0; p < volume.size(); ++p)
      largest = std::max(largest, volume[p] / initial[p]);
    outcome.max_volume_ratio = largest;
    outcome.grid_energy = analysis::grid_kinetic_energy(sim);
    outcome.particle_energy = analysis::particle_kinetic_energy(sim);
  }
  if (o.wall > 0.0) {
    outcome.wall_force = sim.contact().force_on_body(0);
    double deepest = 0.0;
    for (const auto& x : sim.particles().template get<particles::field::Position<2>>()) {
      deepest = std::max(deepest, x[0] - o.wall);
    }
    outcome.deepest_in_wall = deepest;
  }
  return outcome;
}

template <class Kernel, class Transfer>
Outcome run_scheme(const Options& o, const fs::path& out) {
  if (o.scheme == "usl") return run<Kernel, integrator::USL, Transfer>(o, out);
  if (o.scheme == "usf") return run<Kernel, integrator::USF, Transfer>(o, out);
  return run<Kernel, integrator::MUSL, Transfer>(o, out);
}

template <class Kernel>
Outcome run_kernel(const Options& o, const fs::path& out) {
  if constexpr (shape::has_continuous_gradient<Kernel>) {
    if (o.transfer == "apic") return run_scheme<Kernel, transfer::APIC>(o, out);
  }
  return run_scheme<Kernel, transfer::FlipBlend>(o, out);  // parse() rejects linear APIC
}

Outcome run_composition(const Options& o, const fs::path& out) {
  if (o.shape == "linear") return run_kernel<shape::Linear>(o, out);
  if (o.shape == "gimp") return run_kernel<shape::GIMP>(o, out);
  if (o.shape == "cubic") return run_kernel<shape::CubicBSpline>(o, out);
  return run_kernel<shape::QuadraticBSpline>(o, out);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const fs::path out =
        o.out.empty() ? fs::path("out/04_granular_collapse") / o.tag() : fs::path(o.out);
    io::create_directories(out, "example_04");
    // The experiment's laws at this aspect ratio (arXiv:1512.05180).
    const double a = o.column_height / o.column_width;
    const double runout_power = o.column_width * 4.30 * std::pow(a, 0.72);
    const double runout_linear = o.column_width * (1.0 + 3.25 * std::pow(a, 0.96));
    const double final_height = o.column_height / (1.42 * std::pow(a, 2.0 / 3.0));
    std::printf("granular collapse: %s, a = %.3g, %s floor; phi = %g deg, psi = %g deg\n",
                o.tag().c_str(), a, o.floor.c_str(), o.friction_angle, o.dilatancy_angle);
    const Outcome r = run_composition(o, out);

    std::ostringstream summary;
    summary.precision(10);
    summary << "shape = " << o.shape << "\nscheme = " << o.scheme << "\ncell_m = " << o.cell
            << "\nppc = " << o.ppc << "\ntransfer = " << o.transfer
            << "\nflip = " << (o.transfer == "apic" ? 1.0 : o.flip) << "\nfloor = " << o.floor
            << "\nstatus = " << r.status << "\nerror = " << r.error << "\ntime_s = " << r.time
            << "\nrest_time_s = " << r.rest_time << "\nsteps = " << r.steps
            << "\ntime_step_s = " << r.dt << "\nparticles = " << r.particles
            << "\nwall_seconds = " << r.wall_seconds << "\ndeposit_front_m = " << r.deposit_front
            << "\nextreme_front_m = " << r.extreme_front
            << "\ntail_mass_fraction = " << r.tail_mass_fraction
            << "\nheight_at_wall_m = " << r.height_at_wall
            << "\nmax_volume_ratio = " << r.max_volume_ratio
            << "\ngrid_kinetic_J_per_m = " << r.grid_energy
            << "\nparticle_kinetic_J_per_m = " << r.particle_energy
            << "\nenergy_scale_J_per_m = " << r.energy_scale
            << "\nfirst_fast_particle_step = " << r.anomaly_step << "\nwall_m = " << o.wall
            << "\nwall_friction = " << o.wall_friction
            << "\nwall_force_x_N_per_m = " << r.wall_force[0]
            << "\nwall_force_y_N_per_m = " << r.wall_force[1]
            << "\nparticle_depth_past_wall_m = " << r.deepest_in_wall << "\naspect_ratio = " << a
            << "\ncolumn_height_m = " << o.column_height << "\ncolumn_width_m = " << o.column_width
            << "\nreference_runout_power_m = " << runout_power
            << "\nreference_runout_linear_m = " << runout_linear
            << "\nreference_final_height_m = " << final_height << "\n";
    io::write_file_atomically(out / "summary.txt", summary.str());

    std::printf("  %ld particles, %ld steps of %.3g s, %.1f s of computing\n", r.particles, r.steps,
                r.dt, r.wall_seconds);
    if (r.status == "stopped") {
      std::fprintf(stderr, "error: %s\n(the state it stopped in: %s)\n", r.error.c_str(),
                   (out / "failure.txt").c_str());
      return 1;
    }
    std::printf("  %s at t = %.3f s (grid kinetic energy %.3g J/m, particles' %.3g J/m)\n",
                r.status == "rest" ? "at rest" : "still moving", r.time, r.grid_energy,
                r.particle_energy);
    std::printf("  runout %.4f m (experiment %.4f-%.4f m, %+.1f %%), tail ahead %.2f %% of mass\n",
                r.deposit_front, runout_linear, runout_power,
                100.0 * (r.deposit_front / runout_power - 1.0), 100.0 * r.tail_mass_fraction);
    std::printf("  final height at the wall %.4f m (experiment %.4f m, %+.1f %%)\n",
                r.height_at_wall, final_height, 100.0 * (r.height_at_wall / final_height - 1.0));
    if (o.wall > 0.0) {
      std::printf(
          "  wall at x = %.4f m: the soil pushes it with (%.4g, %.4g) N/m; deepest "
          "particle past its face %.3g m\n",
          o.wall, r.wall_force[0], r.wall_force[1], r.deepest_in_wall);
    }
    std::printf("results in %s: series.csv, profile.csv, summary.txt%s\n", out.c_str(),
                o.frames ? ", frames/collapse.xdmf (ParaView)" : "");
    return r.status == "rest" ? 0 : 2;
  } catch (const Error& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
