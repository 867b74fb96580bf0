#pragma once
// Whether a flat-blade case can keep its promises before it starts: enough memory, a run
// that ends within a day, and a time step short enough for every output it promises
// (forces.csv rows, frames, the draft average, the blade stress profile). Each refusal
// names the options to change; --allow-large-run true starts a long or large run anyway.
#include <cmath>
#include <cstdint>
#include <string>

#include "case.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/detail/number_text.hpp"
#include "cosmpm/io/options.hpp"

#if __has_include(<unistd.h>)
#include <unistd.h>
#endif

namespace flat_blade {

// Blade travel between two rows of forces.csv, m.
inline constexpr double forces_row_interval = 1e-4;

// Particle-steps per second and thread this machine class reaches at best: measured 7e6
// (linear, MUSL, nonpolar) and 5e6 (polar) on the 2-core development VM; 1e7 is on the
// optimistic side, so a refused run really is too long.
inline constexpr double optimistic_particle_steps_per_second = 1e7;

// Bytes of memory per particle and per grid node, with room to spare: measured about
// 400 bytes per particle (node share included) at 480 x 280 cells.
inline constexpr double bytes_per_particle = 800.0;
inline constexpr double bytes_per_node = 300.0;

inline std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

inline double physical_memory_bytes() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGE_SIZE)
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) return static_cast<double>(pages) * static_cast<double>(page);
#endif
  return 0.0;  // unknown: no check
}

// Particles the case seeds (the soil layer in front of the blade).
inline double seeded_particles(const Case& c) {
  const double cell_x = c.grid_length / static_cast<double>(c.cells_x);
  const double cell_y = c.grid_height / static_cast<double>(c.cells_y);
  const double per_cell = static_cast<double>(c.particles_per_cell * c.particles_per_cell);
  const double length = c.grid_length - c.blade_start - c.blade_thickness;
  return std::ceil(length / cell_x) * std::ceil(c.soil_depth / cell_y) * per_cell;
}

// Before anything is allocated: the memory the case needs against the machine's.
inline void check_memory(const Case& c, const cosmpm::io::Options& options) {
  const double nodes = static_cast<double>(c.cells_x + 1) * static_cast<double>(c.cells_y + 1);
  const double bytes = seeded_particles(c) * bytes_per_particle + nodes * bytes_per_node;
  const double available = physical_memory_bytes();
  if (available > 0.0 && bytes > 0.8 * available && !c.allow_large_run) {
    options.fail("mesh", "the case needs about " + number(bytes / 1e9) + " GB of memory (" +
                             number(seeded_particles(c)) + " particles, " + number(nodes) +
                             " grid nodes) and this machine has " + number(available / 1e9) +
                             " GB: coarsen --mesh or lower --particles-per-cell, or give "
                             "--allow-large-run true to try anyway");
  }
}

// Once the time step is known, before any output is written.
inline void check_promises(const Case& c, const cosmpm::io::Options& o, double dt,
                           long long particles, int threads) {
  using cosmpm::Error;
  const double step_travel = dt * c.blade_speed;
  const std::string time_step = "the time step dt = " + number(dt) + " s (from " +
                                o.describe("youngs-modulus") + ", " + o.describe("density") + ", " +
                                o.describe("cfl") + " and the cell size)";
  if (!(step_travel <= forces_row_interval)) {
    throw Error(time_step + " moves the blade " + number(step_travel) + " m per step at " +
                o.describe("speed") +
                ", more than the 0.1 mm between the rows of forces.csv: lower --speed or --cfl, "
                "refine --mesh, or check --youngs-modulus and --density");
  }
  if (c.write_frames && c.frame_interval < step_travel) {
    o.fail("frame-interval", "is shorter than the blade travel of one step (" +
                                 number(step_travel) + " m, " + time_step +
                                 "): raise --frame-interval");
  }
  if (c.average_to - c.average_from < step_travel) {
    o.fail("average-to", "leaves a draft average window (from " + o.describe("average-from") +
                             ") shorter than the blade travel of one step (" + number(step_travel) +
                             " m): widen the window");
  }
  if (c.profile_at > c.travel - step_travel) {
    o.fail("profile-at",
           "is within one step of the end of " + o.describe("travel") +
               " (a step moves the blade " + number(step_travel) +
               " m), so the profile might never be taken: lower --profile-at or raise --travel");
  }
  const double steps = (c.equilibrium_time + c.travel / c.blade_speed) / dt;
  const double work = steps * static_cast<double>(particles);
  const double seconds = work / (optimistic_particle_steps_per_second *
                                 static_cast<double>(threads > 0 ? threads : 1));
  if (seconds > 86400.0 && !c.allow_large_run) {
    throw Error("the run needs about " + number(steps) + " steps of " + std::to_string(particles) +
                " particles: at least " + number(seconds / 86400.0) + " days on " +
                std::to_string(threads) + " thread(s) at " +
                number(optimistic_particle_steps_per_second) +
                " particle-steps per second and thread (optimistic). " + time_step +
                "; coarsen --mesh, shorten --travel or --equilibrium-time, raise --speed, or "
                "give --allow-large-run true to start it anyway");
  }
}

}  // namespace flat_blade
