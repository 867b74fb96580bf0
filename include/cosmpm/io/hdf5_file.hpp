#pragma once
// One open HDF5 file: datasets of double, int32, int64 and bytes, scalar and string
// attributes. Every failure throws cosmpm::Error naming the file, the object and HDF5's own
// reason. HDF5's automatic error printing is switched off; its messages go into the Error.
//
// A new file is assembled in memory (HDF5's core driver) and written by close() in one
// checked write: HDF5 never meets a full or failing disk itself. HDF5 1.10 cannot recover
// from a failed flush at close: the file stays half-open and the library crashes when it
// closes it at exit (H5F__close_cb, seen under ASan after a disk-full error).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/detail/superblock.hpp"
#include "cosmpm/io/hdf5_handle.hpp"

namespace cosmpm::io {

struct DatasetOptions {
  // Chunked storage with a Fletcher-32 checksum: a corrupted byte makes the read fail
  // instead of returning wrong numbers (checkpoints use it).
  bool checksum = false;
};

// One open HDF5 file. Every failure throws cosmpm::Error naming the file and the object.
class Hdf5File {
 public:
  // A new file for `path`, held in memory until close() writes it (creating or truncating
  // `path`). `checksummed_metadata` selects the newer file format whose superblock and object
  // headers carry checksums.
  static Hdf5File create(const std::filesystem::path& path, bool checksummed_metadata = false) {
    detail::silence_hdf5_errors();
    detail::Hid access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    // Grows in steps of 1 MiB; no backing store: close() writes the image.
    if (!access.valid() || H5Pset_fapl_core(access.get(), std::size_t{1} << 20, 0) < 0) {
      throw Error("HDF5 file '" + path.string() + "': cannot set up the in-memory driver (" +
                  detail::hdf5_error_text() + ")");
    }
    if (checksummed_metadata) {
      H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST);
    }
    const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get());
    if (id < 0) {
      throw Error("HDF5 file '" + path.string() + "': cannot create it (" +
                  detail::hdf5_error_text() + ")");
    }
    return Hdf5File(detail::Hid(id, H5Fclose), path, true);
  }

  static Hdf5File open_read(const std::filesystem::path& path) {
    detail::silence_hdf5_errors();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      throw Error("HDF5 file '" + path.string() + "': no such file");
    }
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id < 0) {
      throw Error("HDF5 file '" + path.string() +
                  "': cannot open it (not an HDF5 file, truncated or corrupt: " +
                  detail::hdf5_error_text() + ")");
    }
    return Hdf5File(detail::Hid(id, H5Fclose), path, false);
  }

  const std::filesystem::path& path() const { return path_; }
  hid_t id() const { return file_.get(); }

  // Closes; a new file is written to its path now (an Error names the file and the
  // operating system's reason if that fails, and the file on disk is then incomplete).
  void close() {
    if (!file_.valid()) return;
    if (!writable_) {
      if (!file_.close()) fail("/", "cannot close the file");
      return;
    }
    if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) fail("/", "cannot complete the file");
    const ssize_t size = H5Fget_file_image(file_.get(), nullptr, 0);
    if (size < 0) fail("/", "cannot take the file's image");
    std::vector<char> image(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file_.get(), image.data(), image.size()) != size) {
      fail("/", "cannot take the file's image");
    }
    if (!file_.close()) fail("/", "cannot close the in-memory file");
    detail::repair_superblock_checksum(image);
    check_image(image);
    write_bytes(path_, image.data(), image.size());
  }

  // Whether the object at absolute `name` ("/grid/mass") exists.
  bool has(std::string_view name) const {
    std::string prefix;
    std::size_t start = 1;
    while (start <= name.size()) {
      const std::size_t end = std::min(name.find('/', start), name.size());
      prefix = std::string(name.substr(0, end));
      const htri_t exists = H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT);
      if (exists <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return false;
      }
      start = end + 1;
    }
    return true;
  }

  void create_group(const std::string& name) {
    detail::Hid group(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      H5Gclose);
    if (!group.valid()) fail(name, "cannot create the group");
  }

  // Writes a dataset of shape `dims` (row-major) from `data`.
  template <class T>
  void write(const std::string& name, const T* data, const std::vector<hsize_t>& dims,
             const DatasetOptions& options = {}) {
    detail::Hid space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                      H5Sclose);
    if (!space.valid()) fail(name, "cannot create the dataspace " + detail::shape_text(dims));
    detail::Hid create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (options.checksum) {
      // Chunks of 16 KiB: HDF5 1.10 checksums small chunks several times faster than 1 MiB
      // ones (measured: 20 vs 180 ms for 8.6 MB). A chunk needs at least one row.
      std::vector<hsize_t> chunk = dims;
      hsize_t row_bytes = sizeof(T);
      for (std::size_t i = 1; i < dims.size(); ++i) row_bytes *= std::max<hsize_t>(dims[i], 1);
      const hsize_t rows = std::max<hsize_t>(1, (hsize_t{1} << 14) / row_bytes);
      chunk[0] = std::clamp<hsize_t>(dims[0], 1, rows);
      for (std::size_t i = 1; i < chunk.size(); ++i) chunk[i] = std::max<hsize_t>(chunk[i], 1);
      if (H5Pset_chunk(create.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
          H5Pset_fletcher32(create.get()) < 0) {
        fail(name, "cannot set chunking and checksum");
      }
    }
    detail::Hid dataset(H5Dcreate2(file_.get(), name.c_str(), detail::native_type<T>(), space.get(),
                                   H5P_DEFAULT, create.get(), H5P_DEFAULT),
                        H5Dclose);
    if (!dataset.valid()) fail(name, "cannot create the dataset " + detail::shape_text(dims));
    hsize_t count = 1;
    for (const hsize_t d : dims) count *= d;
    if (count > 0 && H5Dwrite(dataset.get(), detail::native_type<T>(), H5S_ALL, H5S_ALL,
                              H5P_DEFAULT, data) < 0) {
      fail(name, "cannot write the dataset");
    }
    if (!dataset.close()) fail(name, "cannot close the dataset");
  }

  std::vector<hsize_t> shape(const std::string& name) const {
    detail::Hid dataset = open_dataset(name);
    detail::Hid space(H5Dget_space(dataset.get()), H5Sclose);
    const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0) fail(name, "cannot read the dataset's shape");
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    return dims;
  }

  // Reads a dataset into `data`, which holds the product of `expected` elements. The stored
  // shape must equal `expected`; with `exact_type` the stored element type must equal T's
  // native type, so nothing is converted (checkpoints are bit-exact).
  template <class T>
  void read(const std::string& name, T* data, const std::vector<hsize_t>& expected,
            bool exact_type = false) const {
    const std::vector<hsize_t> dims = shape(name);
    if (dims != expected) {
      fail(name, "has shape " + detail::shape_text(dims) + " but " + detail::shape_text(expected) +
                     " was expected");
    }
    detail::Hid dataset = open_dataset(name);
    if (exact_type) {
      detail::Hid stored(H5Dget_type(dataset.get()), H5Tclose);
      if (!stored.valid() || H5Tequal(stored.get(), detail::native_type<T>()) <= 0) {
        fail(name,
             "has a different element type than expected (written on another "
             "platform or by another program?)");
      }
    }
    hsize_t count = 1;
    for (const hsize_t d : dims) count *= d;
    if (count > 0 &&
        H5Dread(dataset.get(), detail::native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
      fail(name, "cannot read the dataset (corrupt data or checksum mismatch)");
    }
  }

  // --- scalar attributes of an object (default: the root group) -----------------------
  template <detail::AttributeNumber T>
  void set_attribute(const std::string& name, T value, const std::string& object = "/") {
    detail::Hid space(H5Screate(H5S_SCALAR), H5Sclose);
    write_attribute(object, name, space.get(), detail::native_type<T>(), &value);
  }

  template <detail::AttributeNumber T>
  void set_attribute(const std::string& name, const std::vector<T>& values,
                     const std::string& object = "/") {
    const hsize_t count = values.size();
    detail::Hid space(H5Screate_simple(1, &count, nullptr), H5Sclose);
    write_attribute(object, name, space.get(), detail::native_type<T>(), values.data());
  }

  void set_attribute(const std::string& name, const std::string& value,
                     const std::string& object = "/") {
    detail::Hid type = string_type(std::max<std::size_t>(value.size(), 1));
    detail::Hid space(H5Screate(H5S_SCALAR), H5Sclose);
    std::string padded = value;
    padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
    write_attribute(object, name, space.get(), type.get(), padded.data());
  }

  template <detail::AttributeNumber T>
  T attribute(const std::string& name, const std::string& object = "/") const {
    detail::Hid attr = open_attribute(object, name);
    detail::Hid space(H5Aget_space(attr.get()), H5Sclose);
    if (H5Sget_simple_extent_npoints(space.get()) != 1) {
      fail(object, "attribute '" + name + "' is not a single value");
    }
    T value{};
    if (H5Aread(attr.get(), detail::native_type<T>(), &value) < 0) {
      fail(object, "cannot read the attribute '" + name + "'");
    }
    return value;
  }

  std::string string_attribute(const std::string& name, const std::string& object = "/") const {
    detail::Hid attr = open_attribute(object, name);
    detail::Hid stored(H5Aget_type(attr.get()), H5Tclose);
    if (!stored.valid() || H5Tget_class(stored.get()) != H5T_STRING ||
        H5Tis_variable_str(stored.get()) != 0) {
      fail(object, "attribute '" + name + "' is not a fixed-length string");
    }
    const std::size_t size = H5Tget_size(stored.get());
    detail::Hid memory = string_type(size);
    std::string value(size, '\0');
    if (H5Aread(attr.get(), memory.get(), value.data()) < 0) {
      fail(object, "cannot read the attribute '" + name + "'");
    }
    value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
    return value;
  }

  bool has_attribute(const std::string& name, const std::string& object = "/") const {
    const htri_t exists = H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT);
    if (exists < 0) H5Eclear2(H5E_DEFAULT);
    return exists > 0;
  }

  [[noreturn]] void fail(const std::string& object, const std::string& what) const {
    throw Error("HDF5 file '" + path_.string() + "', object '" + object + "': " + what + " (" +
                detail::hdf5_error_text() + ")");
  }

 private:
  Hdf5File(detail::Hid file, std::filesystem::path path, bool writable)
      : file_(std::move(file)), path_(std::move(path)), writable_(writable) {}

  // The image must open again before it goes to disk (under a name no file has: the core
  // driver would read an existing file of that name instead).
  void check_image(std::vector<char>& image) const {
    detail::Hid access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    const bool set = access.valid() &&
                     H5Pset_fapl_core(access.get(), std::size_t{1} << 20, 0) >= 0 &&
                     H5Pset_file_image(access.get(), image.data(), image.size()) >= 0;
    detail::Hid reopened(
        set ? H5Fopen("cosmpm in-memory image check", H5F_ACC_RDONLY, access.get()) : -1, H5Fclose);
    if (!reopened.valid() || !reopened.close()) {
      throw Error("HDF5 file '" + path_.string() +
                  "': the completed file does not open again, so it was not written (" +
                  detail::hdf5_error_text() + ")");
    }
  }

  detail::Hid open_dataset(const std::string& name) const {
    if (!has(name)) fail(name, "the dataset is missing");
    detail::Hid dataset(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dataset.valid()) fail(name, "cannot open the dataset");
    return dataset;
  }

  detail::Hid open_attribute(const std::string& object, const std::string& name) const {
    if (!has_attribute(name, object)) fail(object, "the attribute '" + name + "' is missing");
    detail::Hid attr(
        H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    if (!attr.valid()) fail(object, "cannot open the attribute '" + name + "'");
    return attr;
  }

  detail::Hid string_type(std::size_t size) const {
    detail::Hid type(H5Tcopy(H5T_C_S1), H5Tclose);
    if (!type.valid() || H5Tset_size(type.get(), size) < 0 ||
        H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0) {
      fail("/", "cannot create a string type");
    }
    return type;
  }

  void write_attribute(const std::string& object, const std::string& name, hid_t space, hid_t type,
                       const void* data) {
    detail::Hid attr(H5Acreate_by_name(file_.get(), object.c_str(), name.c_str(), type, space,
                                       H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     H5Aclose);
    if (!attr.valid() || H5Awrite(attr.get(), type, data) < 0) {
      fail(object, "cannot write the attribute '" + name + "'");
    }
  }

  detail::Hid file_;
  std::filesystem::path path_;
  bool writable_ = false;
};

}  // namespace cosmpm::io
