#pragma once
// Shared helpers of the io tests: a particle store covering every field kind, an output
// directory per test, and reading datasets back with the HDF5 C API directly (not through
// the code under test).
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"
#include "test_output.hpp"

namespace cosmpm::test_io {

// A model type only for its field types: 2D stress/strain and the plastic state.
struct PlasticModel {
  using stress_type = SymTensor2D<double>;
  using strain_type = SymTensor2D<double>;
  using state_type = material::PlasticState;
};

using Store2 =
    particles::Store<particles::field::Position<2>, particles::field::InitialPosition<2>,
                     particles::field::Velocity<2>, particles::field::Mass, particles::field::Body,
                     particles::field::VelocityGradient<2>, particles::field::Stress<PlasticModel>,
                     particles::field::Strain<PlasticModel>,
                     particles::field::MaterialState<PlasticModel>>;

// Random but reproducible contents (fixed seed).
inline Store2 random_store(Index count, unsigned seed = 12345) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Store2 store;
  store.append(count);
  for (Index p = 0; p < count; ++p) {
    store.get<particles::field::Position<2>>()[p] = Vec<2>(uniform(random), uniform(random));
    store.get<particles::field::InitialPosition<2>>()[p] = Vec<2>(uniform(random), uniform(random));
    store.get<particles::field::Velocity<2>>()[p] = Vec<2>(uniform(random), uniform(random));
    store.get<particles::field::Mass>()[p] = 1.0 + uniform(random);
    store.get<particles::field::Body>()[p] = static_cast<std::int32_t>(p % 3);
    Mat<2> L;
    L << uniform(random), uniform(random), uniform(random), uniform(random);
    store.get<particles::field::VelocityGradient<2>>()[p] = L;
    for (int k = 0; k < 4; ++k) {
      store.get<particles::field::Stress<PlasticModel>>()[p][k] = 1e5 * uniform(random);
      store.get<particles::field::Strain<PlasticModel>>()[p][k] = 1e-3 * uniform(random);
    }
    auto& state = store.get<particles::field::MaterialState<PlasticModel>>()[p];
    state.plastic_shear_strain = 0.5 * (1.0 + uniform(random));
    state.plastic = p % 2 == 0 ? 1.0 : 0.0;
    state.separation = p % 3 == 0 ? 1e-3 * static_cast<double>(p) : 0.0;  // no random draw
  }
  return store;
}

inline std::filesystem::path output_dir(const std::string& name) {
  const std::filesystem::path dir = cosmpm::test::output_root() / "io" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct RawDataset {
  std::vector<hsize_t> dims;
  std::vector<double> values;  // read as double whatever the stored type
  bool ok = false;
};

// Reads a dataset with the plain HDF5 C API; ok = false if anything fails.
inline RawDataset read_raw(const std::filesystem::path& file, const std::string& name) {
  RawDataset out;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return out;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  if (d >= 0) {
    const hid_t s = H5Dget_space(d);
    const int rank = H5Sget_simple_extent_ndims(s);
    out.dims.resize(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(s, out.dims.data(), nullptr);
    hsize_t count = 1;
    for (const hsize_t n : out.dims) count *= n;
    out.values.resize(static_cast<std::size_t>(count));
    out.ok = count == 0 ||
             H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) >= 0;
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return out;
}

inline double read_root_double(const std::filesystem::path& file, const std::string& name) {
  double value = -1.0;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return value;
  const hid_t a = H5Aopen(f, name.c_str(), H5P_DEFAULT);
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(a);
  }
  H5Fclose(f);
  return value;
}

// A fixed-length string attribute of `object` ("/" or a dataset), read with the plain HDF5 C
// API; "<missing>" if anything fails.
inline std::string read_string_attribute(const std::filesystem::path& file,
                                         const std::string& object, const std::string& name) {
  std::string value = "<missing>";
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return value;
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    const hid_t type = H5Aget_type(a);
    const std::size_t size = H5Tget_size(type);
    std::string text(size, '\0');
    if (H5Aread(a, type, text.data()) >= 0) value = text.substr(0, text.find('\0'));
    H5Tclose(type);
    H5Aclose(a);
  }
  H5Fclose(f);
  return value;
}

}  // namespace cosmpm::test_io
