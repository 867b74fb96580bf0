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
// contact law has state (checkpoint_values() / restore_checkpoint_values()).
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
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/version.hpp"

#if __has_include(<cxxabi.h>)
#include <cxxabi.h>

#include <cstdlib>
#define COSMPM_IO_HAVE_CXXABI 1
#endif

namespace cosmpm::io {

struct CheckpointClock {
  double time = 0.0;
  std::int64_t step_count = 0;
};

namespace detail {

inline constexpr const char* checkpoint_format = "cosmpm-checkpoint";
inline constexpr std::int64_t checkpoint_version = 1;

// Exact text of a double (hexadecimal float), so geometry compares bit for bit.
inline std::string exact_text(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%a", value);
  return buffer;
}

// "field.<label>=<type>" items of a store, in declaration order.
template <class Store>
std::string store_signature() {
  std::string text;
  for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    text += "; field." + std::string(Tag::label()) + "=";
    constexpr FieldKind kind = field_kind<V>();
    if constexpr (kind == FieldKind::real) {
      text += "double";
    } else if constexpr (kind == FieldKind::integer) {
      text += "int32";
    } else if constexpr (kind == FieldKind::eigen) {
      text += "double[" + std::to_string(EigenFixed<V>::rows) + "x" +
              std::to_string(EigenFixed<V>::cols) + "]";
    } else {
      text += "bytes[" + std::to_string(sizeof(V)) + "](";
      for (std::size_t k = 0; k < V::labels.size(); ++k) {
        if (k > 0) text += ',';
        text += V::labels[k];
      }
      text += ")";
    }
  });
  return text;
}

// Splits "key=value; key=value" into items.
inline std::vector<std::string> signature_items(const std::string& signature) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= signature.size()) {
    const std::size_t end = std::min(signature.find("; ", start), signature.size());
    if (end > start) items.push_back(signature.substr(start, end - start));
    start = end + 2;
  }
  return items;
}

// The first difference between two signatures, in words.
inline std::string signature_difference(const std::string& in_file, const std::string& expected) {
  const auto file_items = signature_items(in_file);
  const auto our_items = signature_items(expected);
  auto key_of = [](const std::string& item) { return item.substr(0, item.find('=')); };
  auto value_of = [](const std::string& item) {
    const std::size_t eq = item.find('=');
    return eq == std::string::npos ? std::string() : item.substr(eq + 1);
  };
  for (const auto& ours : our_items) {
    bool found = false;
    for (const auto& theirs : file_items) {
      if (key_of(theirs) != key_of(ours)) continue;
      found = true;
      if (theirs != ours) {
        return key_of(ours) + " is '" + value_of(theirs) + "' in the file but '" + value_of(ours) +
               "' in this simulation";
      }
    }
    if (!found)
      return "the file has no " + key_of(ours) + " (this simulation has '" + value_of(ours) + "')";
  }
  for (const auto& theirs : file_items) {
    bool found = false;
    for (const auto& ours : our_items) found = found || key_of(ours) == key_of(theirs);
    if (!found) return "the file has " + theirs + ", which this simulation does not";
  }
  return "the item order differs";
}

// A readable type name for the signature (demangled where the ABI allows).
template <class T>
std::string type_name() {
  const char* mangled = typeid(T).name();
#if defined(COSMPM_IO_HAVE_CXXABI)
  int status = 0;
  char* readable = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
  if (status == 0 && readable != nullptr) {
    std::string name = readable;
    std::free(readable);
    return name;
  }
  std::free(readable);
#endif
  return mangled;
}

template <class Sim>
concept HasContactState = requires(Sim& sim, const std::vector<double>& values) {
  { std::as_const(sim).contact().checkpoint_values() } -> std::convertible_to<std::vector<double>>;
  sim.contact().restore_checkpoint_values(values);
};

}  // namespace detail

// Writes `particles` and `clock` to `path` (temporary name + rename). `composition` is the
// signature load compares against; see composition_signature for a simulation's.
template <class Store>
void write_checkpoint(const std::filesystem::path& path, const Store& particles,
                      const CheckpointClock& clock, const std::string& composition,
                      const std::vector<double>* contact_values = nullptr) {
  if (path.has_parent_path()) create_directories(path.parent_path(), "save_checkpoint");
  TemporaryFile temporary(path);
  Hdf5File file = Hdf5File::create(temporary.path(), /*checksummed_metadata=*/true);
  const auto count = static_cast<hsize_t>(particles.size());
  file.set_attribute("format", std::string(detail::checkpoint_format));
  file.set_attribute("version", detail::checkpoint_version);
  file.set_attribute("composition", composition);
  file.set_attribute("written_by", "cosmpm " + std::to_string(version_major) + "." +
                                       std::to_string(version_minor) + "." +
                                       std::to_string(version_patch));
  file.set_attribute("time", clock.time);
  file.set_attribute("step_count", clock.step_count);
  file.set_attribute("particle_count", static_cast<std::int64_t>(particles.size()));
  file.create_group("/particles");
  const DatasetOptions checked{.checksum = true};
  detail::for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const std::string name = "/particles/" + std::string(Tag::label());
    const auto& column = particles.template get<Tag>();
    constexpr detail::FieldKind kind = detail::field_kind<V>();
    if constexpr (kind == detail::FieldKind::real || kind == detail::FieldKind::integer) {
      file.write(name, column.data(), {count}, checked);
    } else if constexpr (kind == detail::FieldKind::eigen) {
      constexpr auto components =
          static_cast<hsize_t>(detail::EigenFixed<V>::rows * detail::EigenFixed<V>::cols);
      file.write(name, detail::flatten(column).data(), {count, components}, checked);
    } else {
      std::vector<unsigned char> bytes(column.size() * sizeof(V));
      if (!bytes.empty()) std::memcpy(bytes.data(), column.data(), bytes.size());
      file.write(name, bytes.data(), {count, static_cast<hsize_t>(sizeof(V))}, checked);
    }
  });
  if (contact_values != nullptr) {
    file.create_group("/contact");
    file.write("/contact/values", contact_values->data(),
               {static_cast<hsize_t>(contact_values->size())}, checked);
  }
  file.close();
  temporary.commit();
}

// Reads a checkpoint written by write_checkpoint with the same `composition` into
// `particles` (resized to the stored count). On any error `particles` is left unchanged.
template <class Store>
CheckpointClock read_checkpoint(const std::filesystem::path& path, Store& particles,
                                const std::string& composition,
                                std::vector<double>* contact_values = nullptr) {
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
  const auto count = file.attribute<std::int64_t>("particle_count");
  if (count < 0) {
    throw Error(where + ": particle_count = " + std::to_string(count) +
                " is outside the valid range [0, inf)");
  }
  CheckpointClock clock;
  clock.time = file.attribute<double>("time");
  clock.step_count = file.attribute<std::int64_t>("step_count");

  Store loaded = particles;
  loaded.resize(static_cast<Index>(count));
  const auto rows = static_cast<hsize_t>(count);
  detail::for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const std::string name = "/particles/" + std::string(Tag::label());
    auto& column = loaded.template get<Tag>();
    constexpr detail::FieldKind kind = detail::field_kind<V>();
    if constexpr (kind == detail::FieldKind::real || kind == detail::FieldKind::integer) {
      file.read(name, column.data(), {rows}, /*exact_type=*/true);
    } else if constexpr (kind == detail::FieldKind::eigen) {
      constexpr auto components =
          static_cast<hsize_t>(detail::EigenFixed<V>::rows * detail::EigenFixed<V>::cols);
      std::vector<double> flat(static_cast<std::size_t>(rows * components));
      file.read(name, flat.data(), {rows, components}, true);
      detail::unflatten(flat, column);
    } else {
      std::vector<unsigned char> bytes(column.size() * sizeof(V));
      file.read(name, bytes.data(), {rows, static_cast<hsize_t>(sizeof(V))}, true);
      if (!bytes.empty())
        std::memcpy(static_cast<void*>(column.data()), bytes.data(), bytes.size());
    }
  });
  if (contact_values != nullptr) {
    const auto dims = file.shape("/contact/values");
    if (dims.size() != 1) file.fail("/contact/values", "is not a 1D dataset");
    contact_values->resize(static_cast<std::size_t>(dims[0]));
    file.read("/contact/values", contact_values->data(), dims, true);
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

// Saves the particles and the clock of `sim` (and the contact law's state, if it has one).
template <class Sim>
void save_checkpoint(const Sim& sim, const std::filesystem::path& path) {
  const CheckpointClock clock{sim.time(), sim.step_count()};
  if constexpr (detail::HasContactState<Sim>) {
    const std::vector<double> values = sim.contact().checkpoint_values();
    write_checkpoint(path, sim.particles(), clock, composition_signature(sim), &values);
  } else {
    write_checkpoint(path, sim.particles(), clock, composition_signature(sim));
  }
}

// Restores a checkpoint into `sim`, which must be set up as for the run that wrote it (same
// composition, grid and particle count); see the note at the top of this header.
template <class Sim>
void load_checkpoint(Sim& sim, const std::filesystem::path& path) {
  const std::string where = "load_checkpoint: '" + path.string() + "'";
  Hdf5File probe = Hdf5File::open_read(path);
  if (probe.has_attribute("particle_count")) {
    const auto stored = probe.attribute<std::int64_t>("particle_count");
    if (stored != static_cast<std::int64_t>(sim.particles().size())) {
      throw Error(where + " holds " + std::to_string(stored) +
                  " particles but the simulation has " + std::to_string(sim.particles().size()) +
                  "; set the simulation up as for the original run (add_particles) before "
                  "loading");
    }
  }
  probe.close();
  CheckpointClock clock;
  if constexpr (detail::HasContactState<Sim>) {
    std::vector<double> values;
    clock = read_checkpoint(path, sim.particles(), composition_signature(sim), &values);
    sim.contact().restore_checkpoint_values(values);
  } else {
    clock = read_checkpoint(path, sim.particles(), composition_signature(sim));
  }
  sim.set_clock(clock.time, clock.step_count);
}

}  // namespace cosmpm::io
