#pragma once
// The particle store of a checkpoint (io/checkpoint.hpp) in one HDF5 group: every field
// bit-exactly, doubles and int32 as native values, Eigen values as N x C doubles (row-major),
// the material state as N x sizeof(state) bytes; each dataset Fletcher-32 checksummed.
#include <cstring>
#include <string>
#include <vector>

#include "cosmpm/io/field_layout.hpp"
#include "cosmpm/io/hdf5_file.hpp"

namespace cosmpm::io::detail {

template <class Store>
void write_store(Hdf5File& file, const std::string& group, const Store& store) {
  file.create_group(group);
  const auto count = static_cast<hsize_t>(store.size());
  const DatasetOptions checked{.checksum = true};
  for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const std::string name = group + "/" + std::string(Tag::label());
    const auto& column = store.template get<Tag>();
    constexpr FieldKind kind = field_kind<V>();
    if constexpr (kind == FieldKind::real || kind == FieldKind::integer) {
      file.write(name, column.data(), {count}, checked);
    } else if constexpr (kind == FieldKind::eigen) {
      constexpr auto components = static_cast<hsize_t>(EigenFixed<V>::rows * EigenFixed<V>::cols);
      file.write(name, flatten(column).data(), {count, components}, checked);
    } else {
      std::vector<unsigned char> bytes(column.size() * sizeof(V));
      if (!bytes.empty()) std::memcpy(bytes.data(), column.data(), bytes.size());
      file.write(name, bytes.data(), {count, static_cast<hsize_t>(sizeof(V))}, checked);
    }
  });
}

// Reads `rows` particles of every field of `store` (resized to `rows`) from `group`.
template <class Store>
void read_store(const Hdf5File& file, const std::string& group, Store& store, Index rows) {
  store.resize(rows);
  const auto count = static_cast<hsize_t>(rows);
  for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const std::string name = group + "/" + std::string(Tag::label());
    auto& column = store.template get<Tag>();
    constexpr FieldKind kind = field_kind<V>();
    if constexpr (kind == FieldKind::real || kind == FieldKind::integer) {
      file.read(name, column.data(), {count}, /*exact_type=*/true);
    } else if constexpr (kind == FieldKind::eigen) {
      constexpr auto components = static_cast<hsize_t>(EigenFixed<V>::rows * EigenFixed<V>::cols);
      std::vector<double> flat(static_cast<std::size_t>(count * components));
      file.read(name, flat.data(), {count, components}, true);
      unflatten(flat, column);
    } else {
      std::vector<unsigned char> bytes(column.size() * sizeof(V));
      file.read(name, bytes.data(), {count, static_cast<hsize_t>(sizeof(V))}, true);
      if (!bytes.empty()) {
        std::memcpy(static_cast<void*>(column.data()), bytes.data(), bytes.size());
      }
    }
  });
}

}  // namespace cosmpm::io::detail
