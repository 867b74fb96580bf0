#pragma once
// Checkpoint and restart. A checkpoint holds every particle field bit-exactly (doubles and
// int32 as native values, the material state as its raw bytes), the clock and a signature of
// the composition, so a restarted run continues bit-identically and a checkpoint of another
// composition, or a damaged file, is refused with a cosmpm::Error naming the file and the
// mismatch. Datasets carry Fletcher-32 checksums and the file uses HDF5's checksummed
// metadata format; the file is written under a temporary name and renamed.
//
// Everything else the engine needs is rebuilt from the particles every step. The set-up
// (grid, model, parameters, boundary conditions) is not stored: load into a simulation set up
// as for the original run, including its add_particles calls (they also set the engine's
// mass and density scales), then load_checkpoint replaces the particles and the clock.
//
// Layout: attributes of / : format = "cosmpm-checkpoint", version = 1, composition (string),
// time (double), step_count (int64), particle_count (int64); /particles/<label>: N values or
// N x C doubles (row-major), the state as N x sizeof(state) bytes; /contact/values if the
// contact law has state (checkpoint_values() / restore_checkpoint_values()); /caller/values
// with the attribute names (one per line) if the caller stored values of its own (a driver's
// running sums and next output times: CheckpointValues); /engine/values (stray_count,
// stray_mass, ...) and /frozen/<label> (attribute particle_count) for the particles that left
// the grid (SimulationParameters::stray_particles), so a restart also continues a run that
// froze or removed some; checkpoints without them hold none.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/detail/checkpoint_fields.hpp"
#include "cosmpm/io/detail/checkpoint_signature.hpp"
#include "cosmpm/io/field_layout.hpp"
#include "cosmpm/io/hdf5_file.hpp"
#include "cosmpm/simulation/diagnostics.hpp"
#include "cosmpm/version.hpp"

namespace cosmpm::io {

struct CheckpointClock {
  double time = 0.0;
  std::int64_t step_count = 0;
};

// Named values of the caller's own, kept bit-exactly beside the simulation's state, so a
// driver resumes its running sums and output schedule exactly where it stopped.
class CheckpointValues {
 public:
  void set(const std::string& name, double value) {
    require(!name.empty() && name.find('\n') == std::string::npos,
            "CheckpointValues: name '" + name + "' must be non-empty and on one line");
    for (auto& [key, stored] : entries_) {
      if (key == name) {
        stored = value;
        return;
      }
    }
    entries_.emplace_back(name, value);
  }
  bool has(const std::string& name) const {
    for (const auto& entry : entries_) {
      if (entry.first == name) return true;
    }
    return false;
  }
  // The value stored under `name`; an Error naming `where` if there is none.
  double get(const std::string& name, const std::string& where = "checkpoint") const {
    for (const auto& [key, value] : entries_) {
      if (key == name) return value;
    }
    throw Error(where + ": holds no value '" + name +
                "' (written by another program or an older version?)");
  }
  bool empty() const { return entries_.empty(); }
  const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }

 private:
  std::vector<std::pair<std::string, double>> entries_;
};

namespace detail {

inline constexpr const char* checkpoint_format = "cosmpm-checkpoint";
inline constexpr std::int64_t checkpoint_version = 1;

template <class Sim>
concept HasContactState = requires(Sim& sim, const std::vector<double>& values) {
  { std::as_const(sim).contact().checkpoint_values() } -> std::convertible_to<std::vector<double>>;
  sim.contact().restore_checkpoint_values(values);
};

// Named values as a dataset with their names (one per line) in its attribute "names".
inline void write_values(Hdf5File& file, const std::string& group, const CheckpointValues& named) {
  std::vector<double> values;
  std::string names;
  for (const auto& [name, value] : named.entries()) {
    values.push_back(value);
    names += (names.empty() ? "" : "\n") + name;
  }
  const std::string dataset = group + "/values";
  file.create_group(group);
  file.write(dataset, values.data(), {static_cast<hsize_t>(values.size())},
             DatasetOptions{.checksum = true});
  file.set_attribute("names", names, dataset);
}

// The values of write_values; none if the file has no such group.
inline CheckpointValues read_values(const Hdf5File& file, const std::string& group) {
  CheckpointValues named;
  const std::string dataset = group + "/values";
  if (!file.has(dataset)) return named;
  const auto dims = file.shape(dataset);
  std::vector<double> values(dims.size() == 1 ? static_cast<std::size_t>(dims[0]) : 0);
  file.read(dataset, values.data(), {values.size()}, true);
  const std::string names = file.string_attribute("names", dataset);
  std::size_t start = 0;
  for (const double value : values) {
    const std::size_t end = std::min(names.find('\n', start), names.size());
    named.set(names.substr(start, end - start), value);
    start = end + 1;
  }
  if (named.entries().size() != values.size()) {
    file.fail(dataset, "has names that do not match its values");
  }
  return named;
}

inline CheckpointValues stray_values(const StrayReport& strays) {
  CheckpointValues values;
  values.set("stray_count", static_cast<double>(strays.count));
  values.set("stray_mass", strays.mass);
  values.set("stray_count_last_step", static_cast<double>(strays.count_last_step));
  values.set("stray_mass_last_step", strays.mass_last_step);
  return values;
}

inline StrayReport stray_report(const CheckpointValues& values) {
  StrayReport strays;
  if (values.empty()) return strays;  // a checkpoint of a run that lost no particle
  const std::string where = "checkpoint /engine/values";
  strays.count = static_cast<Index>(values.get("stray_count", where));
  strays.mass = values.get("stray_mass", where);
  strays.count_last_step = static_cast<Index>(values.get("stray_count_last_step", where));
  strays.mass_last_step = values.get("stray_mass_last_step", where);
  return strays;
}

}  // namespace detail

// The particles that left the grid (SimulationParameters::stray_particles): those frozen and
// the count and mass of all, written beside the particles.
template <class Store>
struct CheckpointStrays {
  Store frozen;
  StrayReport report;
};

// Writes `particles` and `clock` to `path` (temporary name + rename). `composition` is the
// signature load compares against; see composition_signature for a simulation's.
template <class Store>
void write_checkpoint(const std::filesystem::path& path, const Store& particles,
                      const CheckpointClock& clock, const std::string& composition,
                      const std::vector<double>* contact_values = nullptr,
                      const CheckpointValues* caller_values = nullptr,
                      const CheckpointStrays<Store>* strays = nullptr) {
  if (path.has_parent_path()) create_directories(path.parent_path(), "save_checkpoint");
  TemporaryFile temporary(path);
  Hdf5File file = Hdf5File::create(temporary.path(), /*checksummed_metadata=*/true);
  file.set_attribute("format", std::string(detail::checkpoint_format));
  file.set_attribute("version", detail::checkpoint_version);
  file.set_attribute("composition", composition);
  file.set_attribute("written_by", "cosmpm " + std::to_string(version_major) + "." +
                                       std::to_string(version_minor) + "." +
                                       std::to_string(version_patch));
  file.set_attribute("time", clock.time);
  file.set_attribute("step_count", clock.step_count);
  file.set_attribute("particle_count", static_cast<std::int64_t>(particles.size()));
  detail::write_store(file, "/particles", particles);
  if (contact_values != nullptr) {
    file.create_group("/contact");
    file.write("/contact/values", contact_values->data(),
               {static_cast<hsize_t>(contact_values->size())}, DatasetOptions{.checksum = true});
  }
  if (caller_values != nullptr && !caller_values->empty()) {
    detail::write_values(file, "/caller", *caller_values);
  }
  if (strays != nullptr && (strays->report.count > 0 || strays->frozen.size() > 0)) {
    detail::write_values(file, "/engine", detail::stray_values(strays->report));
    detail::write_store(file, "/frozen", strays->frozen);
    file.set_attribute("particle_count", static_cast<std::int64_t>(strays->frozen.size()),
                       "/frozen");
  }
  file.close();
  temporary.commit();
}

// Reads a checkpoint written by write_checkpoint with the same `composition` into
// `particles` (resized to the stored count). On any error `particles` is left unchanged.
template <class Store>
CheckpointClock read_checkpoint(const std::filesystem::path& path, Store& particles,
                                const std::string& composition,
                                std::vector<double>* contact_values = nullptr,
                                CheckpointValues* caller_values = nullptr,
                                CheckpointStrays<Store>* strays = nullptr) {
  const std::string where = "load_checkpoint: '" + path.string() + "'";
  Hdf5File file = Hdf5File::open_read(path);
  if (!file.has_attribute("format") ||
      file.string_attribute("format") != detail::checkpoint_format) {
    throw Error(where +
                " is not a cosmpm checkpoint (its 'format' attribute is missing or "
                "not '" +
                std::string(detail::checkpoint_format) + "')");
  }
  const auto version = file.attribute<std::int64_t>("version");
  if (version != detail::checkpoint_version) {
    throw Error(where + " has checkpoint format version " + std::to_string(version) +
                "; this build reads version " + std::to_string(detail::checkpoint_version));
  }
  const std::string stored = file.string_attribute("composition");
  if (stored != composition) {
    throw Error(where + " was written by a different composition: " +
                detail::signature_difference(stored, composition));
  }
  auto count_of = [&](const std::string& object) {
    const auto count = file.attribute<std::int64_t>("particle_count", object);
    if (count < 0) {
      throw Error(where + ": particle_count of " + object + " = " + std::to_string(count) +
                  " is outside the valid range [0, inf)");
    }
    return static_cast<Index>(count);
  };
  CheckpointClock clock;
  clock.time = file.attribute<double>("time");
  clock.step_count = file.attribute<std::int64_t>("step_count");

  Store loaded = particles;
  detail::read_store(file, "/particles", loaded, count_of("/"));
  if (contact_values != nullptr) {
    const auto dims = file.shape("/contact/values");
    if (dims.size() != 1) file.fail("/contact/values", "is not a 1D dataset");
    contact_values->resize(static_cast<std::size_t>(dims[0]));
    file.read("/contact/values", contact_values->data(), dims, true);
  }
  if (caller_values != nullptr) *caller_values = detail::read_values(file, "/caller");
  if (strays != nullptr) {
    CheckpointStrays<Store> left;
    left.report = detail::stray_report(detail::read_values(file, "/engine"));
    if (file.has("/frozen")) detail::read_store(file, "/frozen", left.frozen, count_of("/frozen"));
    *strays = std::move(left);
  }
  particles = std::move(loaded);
  return clock;
}

// The signature of a simulation's composition: dimension, kernel, scheme, contact law,
// model, continuum, grid geometry (exact) and every particle field's type.
template <class Sim>
std::string composition_signature(const Sim& sim) {
  using Model = typename Sim::model_type;
  std::string model_name;
  if constexpr (requires { Model::name(); }) {
    model_name = Model::name();
  } else {
    model_name = detail::type_name<Model>();
  }
  std::string text = "dim=" + std::to_string(Sim::dim);
  text += "; kernel=" + std::string(Sim::kernel_type::name());
  text += "; scheme=" + std::string(Sim::scheme_type::name());
  text += "; contact=" + std::string(Sim::contact_type::name());
  text += "; contact_state=" + std::string(detail::HasContactState<Sim> ? "yes" : "no");
  text += "; continuum=" + std::string(Sim::continuum_type::is_cosserat ? "cosserat" : "classical");
  if constexpr (requires { typename Sim::continuum_type::antilocking_type; }) {
    text += "; antilocking=" + std::string(Sim::continuum_type::antilocking_type::name());
  }
  if constexpr (requires { typename Sim::transfer_type; }) {
    text += "; transfer=" + std::string(Sim::transfer_type::name());
  }
  text += "; model=" + model_name;
  const auto& grid = sim.grid();
  std::string cells;
  std::string origin;
  std::string cell_size;
  for (int d = 0; d < Sim::dim; ++d) {
    const std::string sep = d > 0 ? " " : "";
    cells += sep + std::to_string(grid.cells(d));
    origin += sep + detail::exact_text(grid.origin()[d]);
    cell_size += sep + detail::exact_text(grid.cell_size()[d]);
  }
  text += "; grid.cells=" + cells + "; grid.origin=" + origin + "; grid.cell_size=" + cell_size;
  return text + detail::store_signature<typename Sim::store_type>();
}

// Saves the particles and the clock of `sim` (and the contact law's state, if it has one, and
// the particles that left the grid), with the caller's own `values`.
template <class Sim>
void save_checkpoint(const Sim& sim, const std::filesystem::path& path,
                     const CheckpointValues& values = {}) {
  const CheckpointClock clock{sim.time(), sim.step_count()};
  using Store = typename Sim::store_type;
  const CheckpointStrays<Store> strays{sim.frozen_particles(), sim.stray_particles()};
  if constexpr (detail::HasContactState<Sim>) {
    const std::vector<double> contact = sim.contact().checkpoint_values();
    write_checkpoint(path, sim.particles(), clock, composition_signature(sim), &contact, &values,
                     &strays);
  } else {
    write_checkpoint(path, sim.particles(), clock, composition_signature(sim), nullptr, &values,
                     &strays);
  }
}

// Restores a checkpoint into `sim`, which must be set up as for the run that wrote it (same
// composition, grid and particles added); see the note at the top of this header. Returns the
// caller's values saved with it.
template <class Sim>
CheckpointValues load_checkpoint(Sim& sim, const std::filesystem::path& path) {
  const std::string where = "load_checkpoint: '" + path.string() + "'";
  Hdf5File probe = Hdf5File::open_read(path);
  if (probe.has_attribute("particle_count")) {
    // Particles that left the grid are no longer in the simulation that wrote the file.
    const auto stored = probe.attribute<std::int64_t>("particle_count");
    const auto left = static_cast<std::int64_t>(
        detail::stray_report(detail::read_values(probe, "/engine")).count);
    if (stored + left != static_cast<std::int64_t>(sim.particles().size())) {
      throw Error(where + " holds " + std::to_string(stored) + " particles" +
                  (left > 0 ? " and " + std::to_string(left) + " that left the grid" : "") +
                  " but the simulation has " + std::to_string(sim.particles().size()) +
                  "; set the simulation up as for the original run (add_particles) before "
                  "loading");
    }
  }
  probe.close();
  using Store = typename Sim::store_type;
  CheckpointClock clock;
  CheckpointValues caller;
  CheckpointStrays<Store> strays;
  if constexpr (detail::HasContactState<Sim>) {
    std::vector<double> contact;
    clock = read_checkpoint(path, sim.particles(), composition_signature(sim), &contact, &caller,
                            &strays);
    sim.contact().restore_checkpoint_values(contact);
  } else {
    clock = read_checkpoint(path, sim.particles(), composition_signature(sim), nullptr, &caller,
                            &strays);
  }
  sim.engine().frozen = std::move(strays.frozen);
  sim.engine().strays = strays.report;
  sim.set_clock(clock.time, clock.step_count);
  return caller;
}

}  // namespace cosmpm::io
