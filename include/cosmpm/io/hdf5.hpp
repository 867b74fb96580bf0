#pragma once
// HDF5 output: RAII handles, a small typed file API whose failures are cosmpm::Error naming the
// file and the object, and the per-frame particle writer. The only header that includes
// <hdf5.h>. HDF5's automatic error printing is switched off; its messages go into the Error.
//
// Frame file layout (`<dir>/<prefix>_<NNNNNN>.h5`, NNNNNN = frame number from 000000):
//   attributes of /      format = "cosmpm-frame", version = 1, time [s] (double),
//                        step (int64), frame (int64), particle_count (int64)
//   /<label>             one dataset per particle field, named by the field tag's label():
//                          double and int32 fields: N values (position ... mass, body)
//                          Eigen fields: N x C doubles; a matrix is flattened row by row
//                          (velocity_gradient: L_xx, L_xy, L_yx, L_yy); stress and strain
//                          in 2D: [xx, yy, zz, xy] (tensor shear, tension positive), Cosserat:
//                          [xx, yy, zz, xy, yx, 31, 32] (m_31, m_32 or kappa_31, kappa_32)
//   /<state label>       one N-value double dataset per material state label
//                        (e.g. plastic, plastic_shear_strain)
//   /displacement        N x Dim: position - initial_position, when both fields exist
//   /<vector>3           N x 3 copies of the Dim < 3 vectors padded with zeros (position3,
//                        velocity3, displacement3), for ParaView only
//   /grid/...            optional node fields: position (+3), mass, velocity (+3); attributes
//                        node_count, nodes_per_axis, origin, cell_size
// `<dir>/<prefix>.xdmf` lists all complete frames for ParaView (see io/xdmf.hpp).
#include <hdf5.h>

#include <algorithm>
#include <array>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/xdmf.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::io {

namespace detail {

// Once per process: HDF5 must not print its error stack on stderr; the Error carries it.
inline void silence_hdf5_errors() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// The most specific descriptions on HDF5's error stack (then cleared), for messages.
inline std::string hdf5_error_text() {
  struct Collected {
    std::string text;
    int count = 0;
  } collected;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* entry, void* data) -> herr_t {
        auto* c = static_cast<Collected*>(data);
        if (c->count < 3 && entry->desc != nullptr && entry->desc[0] != '\0') {
          if (!c->text.empty()) c->text += "; ";
          c->text += entry->desc;
          ++c->count;
        }
        return 0;
      },
      &collected);
  H5Eclear2(H5E_DEFAULT);
  return collected.text.empty() ? std::string("no HDF5 detail") : collected.text;
}

// An HDF5 identifier closed by its own close function.
class Hid {
 public:
  using Closer = herr_t (*)(hid_t);
  Hid() = default;
  Hid(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  Hid(Hid&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Hid& operator=(Hid&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, -1);
      closer_ = other.closer_;
    }
    return *this;
  }
  ~Hid() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports whether HDF5 accepted the close.
  bool close() {
    if (id_ < 0 || closer_ == nullptr) return true;
    const herr_t status = closer_(id_);
    id_ = -1;
    return status >= 0;
  }

 private:
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, double>) {
    return H5T_NATIVE_DOUBLE;
  } else if constexpr (std::is_same_v<T, std::int32_t>) {
    return H5T_NATIVE_INT32;
  } else if constexpr (std::is_same_v<T, std::int64_t>) {
    return H5T_NATIVE_INT64;
  } else {
    static_assert(std::is_same_v<T, unsigned char>, "io::Hdf5File: unsupported element type");
    return H5T_NATIVE_UCHAR;
  }
}

// The numeric attribute types: times and counts.
template <class T>
concept AttributeNumber = std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>;

inline std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string text = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (i > 0) text += ", ";
    text += std::to_string(dims[i]);
  }
  return text + "]";
}

}  // namespace detail

struct DatasetOptions {
  // Chunked storage with a Fletcher-32 checksum: a corrupted byte makes the read fail
  // instead of returning wrong numbers (checkpoints use it).
  bool checksum = false;
};

// One open HDF5 file. Every failure throws cosmpm::Error naming the file and the object.
class Hdf5File {
 public:
  // Creates (truncates) `path`. `checksummed_metadata` selects the newer file format whose
  // superblock and object headers carry checksums.
  static Hdf5File create(const std::filesystem::path& path, bool checksummed_metadata = false) {
    detail::silence_hdf5_errors();
    detail::Hid access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
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

  // Flushes and closes; a failure here means the file is incomplete.
  void close() {
    if (!file_.valid()) return;
    const herr_t flushed = writable_ ? H5Fflush(file_.get(), H5F_SCOPE_LOCAL) : 0;
    const bool closed = file_.close();
    if (flushed < 0 || !closed) fail("/", "cannot flush and close the file");
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

// --- particle fields as datasets --------------------------------------------------------

namespace detail {

template <class V>
struct EigenFixed : std::false_type {};
template <int Rows, int Cols, int Options, int MaxRows, int MaxCols>
struct EigenFixed<Eigen::Matrix<double, Rows, Cols, Options, MaxRows, MaxCols>>
    : std::bool_constant<(Rows > 0 && Cols > 0)> {
  static constexpr Index rows = Rows;
  static constexpr Index cols = Cols;
};

// How a field value type maps to datasets.
enum class FieldKind { real, integer, eigen, state };

template <class V>
constexpr FieldKind field_kind() {
  if constexpr (std::is_same_v<V, double>) {
    return FieldKind::real;
  } else if constexpr (std::is_same_v<V, std::int32_t>) {
    return FieldKind::integer;
  } else if constexpr (EigenFixed<V>::value) {
    return FieldKind::eigen;
  } else {
    static_assert(material::OutputState<V> && std::is_trivially_copyable_v<V>,
                  "io: a particle field must be double, std::int32_t, a fixed-size Eigen double "
                  "matrix or a trivially copyable material state with labels and values()");
    return FieldKind::state;
  }
}

// Row-major flattening of a fixed-size Eigen column: element (i, j) of particle p goes to
// out[p * rows * cols + i * cols + j].
template <class V>
std::vector<double> flatten(const std::vector<V>& column) {
  constexpr Index rows = EigenFixed<V>::rows;
  constexpr Index cols = EigenFixed<V>::cols;
  std::vector<double> out(column.size() * static_cast<std::size_t>(rows * cols));
  std::size_t k = 0;
  for (const V& value : column) {
    for (Index i = 0; i < rows; ++i) {
      for (Index j = 0; j < cols; ++j) out[k++] = value(i, j);
    }
  }
  return out;
}

template <class V>
void unflatten(const std::vector<double>& flat, std::vector<V>& column) {
  constexpr Index rows = EigenFixed<V>::rows;
  constexpr Index cols = EigenFixed<V>::cols;
  std::size_t k = 0;
  for (V& value : column) {
    for (Index i = 0; i < rows; ++i) {
      for (Index j = 0; j < cols; ++j) value(i, j) = flat[k++];
    }
  }
}

// Name of column k of an N x C field, for the XDMF component attributes.
inline std::string component_name(Index rows, Index cols, Index k) {
  static constexpr std::array<const char*, 4> symmetric{"xx", "yy", "zz", "xy"};
  static constexpr std::array<const char*, 7> cosserat{"xx", "yy", "zz", "xy", "yx", "31", "32"};
  static constexpr std::array<char, 3> axes{'x', 'y', 'z'};
  if (cols == 1 && rows == 4) return symmetric[static_cast<std::size_t>(k)];
  if (cols == 1 && rows == 7) return cosserat[static_cast<std::size_t>(k)];
  if (cols > 1 && rows <= 3 && cols <= 3) {
    return std::string{axes[static_cast<std::size_t>(k / cols)],
                       axes[static_cast<std::size_t>(k % cols)]};
  }
  return std::to_string(k);
}

template <class Store, class F>
void for_each_tag(F&& f) {
  [&]<class... Tags>(std::tuple<Tags...>*) {
    (f(Tags{}), ...);
  }(static_cast<typename Store::tags*>(nullptr));
}

// Writes the datasets of one mesh (particles or grid nodes) and describes them for XDMF. With
// no file (`file == nullptr`) it only describes: a restart rebuilds the XDMF entries of the
// frames written before it without reading their data.
class MeshWriter {
 public:
  MeshWriter(Hdf5File* file, std::string group, std::string mesh_name, Index points)
      : file_(file), group_(std::move(group)) {
    mesh_.name = std::move(mesh_name);
    mesh_.points = points;
  }

  template <class T>
  void scalar(const std::string& label, const T* data) {
    const std::string name = claim(label);
    if (file_ != nullptr) file_->write(name, data, {rows()});
    XdmfAttribute attribute;
    attribute.name = label;
    attribute.dataset = name;
    attribute.number = std::is_same_v<T, double> ? XdmfNumber::float64 : XdmfNumber::int32;
    mesh_.attributes.push_back(attribute);
  }

  // A fixed-size Eigen field (`column` may be null when only describing).
  template <class V>
  void eigen(const std::string& label, const std::vector<V>* column) {
    constexpr Index rows_per = EigenFixed<V>::rows;
    constexpr Index cols_per = EigenFixed<V>::cols;
    constexpr Index components = rows_per * cols_per;
    const std::string name = claim(label);
    if (file_ != nullptr) {
      file_->write(name, flatten(*column).data(), {rows(), static_cast<hsize_t>(components)});
    }
    if constexpr (cols_per == 1 && rows_per <= 3) {
      // A spatial vector: ParaView wants 3 components.
      std::string padded_name = name;
      if constexpr (rows_per < 3) {
        padded_name = claim(label + "3");
        if (file_ != nullptr) {
          std::vector<double> padded(static_cast<std::size_t>(mesh_.points) * 3, 0.0);
          for (std::size_t p = 0; p < column->size(); ++p) {
            for (Index d = 0; d < rows_per; ++d) padded[3 * p + d] = (*column)[p][d];
          }
          file_->write(padded_name, padded.data(), {rows(), 3});
        }
      }
      if (label == "position") {
        mesh_.geometry_dataset = padded_name;
        return;
      }
      XdmfAttribute attribute;
      attribute.name = label;
      attribute.dataset = padded_name;
      attribute.kind = XdmfAttribute::Kind::vector;
      attribute.columns = 3;
      mesh_.attributes.push_back(attribute);
    } else {
      for (Index k = 0; k < components; ++k) {
        XdmfAttribute attribute;
        attribute.name = label + "_" + component_name(rows_per, cols_per, k);
        attribute.dataset = name;
        attribute.kind = XdmfAttribute::Kind::component;
        attribute.columns = components;
        attribute.component = k;
        mesh_.attributes.push_back(attribute);
      }
    }
  }

  // One double dataset per label of a material state.
  template <class S>
  void state(const std::vector<S>* column) {
    for (std::size_t k = 0; k < S::labels.size(); ++k) {
      std::vector<double> values;
      if (file_ != nullptr) {
        values.resize(column->size());
        for (std::size_t p = 0; p < column->size(); ++p) values[p] = (*column)[p].values()[k];
      }
      scalar(std::string(S::labels[k]), values.data());
    }
  }

  XdmfMesh take() { return std::move(mesh_); }
  const std::string& group() const { return group_; }

 private:
  hsize_t rows() const { return static_cast<hsize_t>(mesh_.points); }

  std::string claim(const std::string& label) {
    const std::string name = group_ + "/" + label;
    if (!names_.insert(name).second) {
      throw Error("io: two particle fields or state labels would both be written as dataset '" +
                  name + "'; labels must be unique");
    }
    return name;
  }

  Hdf5File* file_;
  std::string group_;
  XdmfMesh mesh_;
  std::set<std::string> names_;
};

// Writes (or, with a null column source, only describes) every field of a particle store,
// plus the displacement from the start.
template <class Store>
void put_particles(MeshWriter& mesh, const Store* store) {
  for_each_tag<Store>([&](auto tag) {
    using Tag = decltype(tag);
    using V = typename Tag::value_type;
    const std::vector<V>* column = store != nullptr ? &store->template get<Tag>() : nullptr;
    constexpr FieldKind kind = field_kind<V>();
    if constexpr (kind == FieldKind::real || kind == FieldKind::integer) {
      mesh.scalar(Tag::label(), column != nullptr ? column->data() : nullptr);
    } else if constexpr (kind == FieldKind::eigen) {
      mesh.eigen(Tag::label(), column);
    } else {
      mesh.state(column);
    }
  });
  auto displacement = [&]<int D>(std::integral_constant<int, D>) {
    using particles::field::InitialPosition;
    using particles::field::Position;
    if constexpr (Store::template has<Position<D>> && Store::template has<InitialPosition<D>>) {
      std::vector<Vec<D>> u;
      if (store != nullptr) {
        const auto& x = store->template get<Position<D>>();
        const auto& x0 = store->template get<InitialPosition<D>>();
        u.resize(x.size());
        for (std::size_t p = 0; p < x.size(); ++p) u[p] = x[p] - x0[p];
      }
      mesh.eigen("displacement", store != nullptr ? &u : nullptr);
    }
  };
  displacement(std::integral_constant<int, 1>{});
  displacement(std::integral_constant<int, 2>{});
  displacement(std::integral_constant<int, 3>{});
}

template <class Sim>
concept FrameSource = requires(const Sim& sim) {
  sim.particles();
  sim.grid();
  sim.nodes().mass;
  sim.nodes().velocity;
  { sim.time() } -> std::convertible_to<double>;
  { sim.step_count() } -> std::convertible_to<std::int64_t>;
};

}  // namespace detail

struct FrameOptions {
  bool grid_fields = false;  // also write node positions, mass and velocity (write(sim) only)
  bool xdmf = true;          // keep <prefix>.xdmf up to date
};

// Writes one HDF5 file per frame and keeps the XDMF index of the series current. Each frame is
// written under a temporary name and renamed, then the XDMF file is rewritten the same way:
// after a crash every frame listed is complete.
class ParticleFrameWriter {
 public:
  ParticleFrameWriter(std::filesystem::path directory, std::string prefix,
                      FrameOptions options = {})
      : directory_(std::move(directory)),
        prefix_(std::move(prefix)),
        options_(options),
        xdmf_(directory_ / (prefix_ + ".xdmf")) {
    require(
        !prefix_.empty() && prefix_.find('/') == std::string::npos,
        "ParticleFrameWriter: prefix '" + prefix_ + "' must be a non-empty file name without '/'");
    create_directories(directory_, "ParticleFrameWriter");
  }

  std::filesystem::path frame_path(Index frame) const {
    return directory_ / frame_file_name(frame);
  }
  std::filesystem::path xdmf_path() const { return xdmf_.path(); }
  Index frame_count() const { return next_frame_; }
  const FrameOptions& options() const { return options_; }

  // A frame of a bare particle store at the given clock.
  template <class Store>
  std::filesystem::path write(const Store& particles, double time, std::int64_t step) {
    return write_frame<Store, 0, void, void>(particles, nullptr, nullptr, time, step);
  }

  // A frame of a simulation: its particles, clock and (with grid_fields) its grid nodes.
  template <detail::FrameSource Sim>
  std::filesystem::path write(const Sim& sim) {
    using Grid = std::remove_cvref_t<decltype(sim.grid())>;
    constexpr int dim = Grid::dim;
    return write_frame<std::remove_cvref_t<decltype(sim.particles())>, dim>(
        sim.particles(), &sim.grid(), &sim.nodes(), sim.time(), sim.step_count());
  }

  // After a restart of `sim` (at sim.time()): see resume(time) below.
  template <detail::FrameSource Sim>
  Index resume(const Sim& sim) {
    using Grid = std::remove_cvref_t<decltype(sim.grid())>;
    return resume<std::remove_cvref_t<decltype(sim.particles())>, Grid::dim>(sim.time());
  }

  // After a restart at `time`: finds the frames already on disk with frame time <= `time`
  // (consecutive from frame 0), lists them in the XDMF index again and continues numbering
  // after them; later frames are overwritten as the run reaches them. `Store` (and, for
  // grid frames, `GridDim`) must be those the frames were written with. Returns the count.
  template <class Store, int GridDim = 0>
  Index resume(double time) {
    xdmf_.clear();
    next_frame_ = 0;
    for (;;) {
      const std::filesystem::path path = frame_path(next_frame_);
      std::error_code error;
      if (!std::filesystem::is_regular_file(path, error)) break;
      Hdf5File file = Hdf5File::open_read(path);
      const double frame_time = file.attribute<double>("time");
      if (!(frame_time <= time)) break;
      const Index count = file.attribute<std::int64_t>("particle_count");
      XdmfFrame frame;
      frame.file = frame_file_name(next_frame_);
      frame.time = frame_time;
      detail::MeshWriter particles(nullptr, "", "particles", count);
      detail::put_particles<Store>(particles, nullptr);
      frame.meshes.push_back(particles.take());
      if (file.has("/grid")) {
        if constexpr (GridDim > 0) {
          const Index nodes = file.attribute<std::int64_t>("node_count", "/grid");
          frame.meshes.push_back(describe_grid<GridDim>(nodes));
        } else {
          throw Error("ParticleFrameWriter::resume: frame '" + path.string() +
                      "' has grid fields; pass the grid dimension as GridDim");
        }
      }
      xdmf_.append(std::move(frame));
      ++next_frame_;
    }
    if (options_.xdmf) xdmf_.write();
    return next_frame_;
  }

 private:
  std::string frame_file_name(Index frame) const {
    std::string number = std::to_string(frame);
    if (number.size() < 6) number.insert(0, 6 - number.size(), '0');
    return prefix_ + "_" + number + ".h5";
  }

  template <int Dim>
  static XdmfMesh describe_grid(Index nodes) {
    detail::MeshWriter mesh(nullptr, "/grid", "grid", nodes);
    mesh.eigen<Vec<Dim>>("position", nullptr);
    mesh.scalar<double>("mass", nullptr);
    mesh.eigen<Vec<Dim>>("velocity", nullptr);
    return mesh.take();
  }

  template <class Store, int Dim, class Grid, class Nodes>
  std::filesystem::path write_frame(const Store& particles, const Grid* grid, const Nodes* nodes,
                                    double time, std::int64_t step) {
    const std::filesystem::path final_path = frame_path(next_frame_);
    XdmfFrame frame;
    frame.file = frame_file_name(next_frame_);
    frame.time = time;
    {
      TemporaryFile temporary(final_path);
      Hdf5File file = Hdf5File::create(temporary.path());
      file.set_attribute("format", std::string("cosmpm-frame"));
      file.set_attribute("version", std::int64_t{1});
      file.set_attribute("time", time);
      file.set_attribute("step", step);
      file.set_attribute("frame", static_cast<std::int64_t>(next_frame_));
      file.set_attribute("particle_count", static_cast<std::int64_t>(particles.size()));
      detail::MeshWriter mesh(&file, "", "particles", particles.size());
      detail::put_particles(mesh, &particles);
      frame.meshes.push_back(mesh.take());
      if constexpr (Dim > 0) {
        if (options_.grid_fields) frame.meshes.push_back(put_grid<Dim>(file, *grid, *nodes));
      }
      file.close();
      temporary.commit();
    }
    ++next_frame_;
    if (options_.xdmf) xdmf_.add_frame(std::move(frame));
    return final_path;
  }

  template <int Dim, class Grid, class Nodes>
  static XdmfMesh put_grid(Hdf5File& file, const Grid& grid, const Nodes& nodes) {
    const Index count = grid.node_count();
    file.create_group("/grid");
    file.set_attribute("node_count", static_cast<std::int64_t>(count), "/grid");
    std::vector<std::int64_t> per_axis;
    std::vector<double> origin;
    std::vector<double> cell_size;
    for (int d = 0; d < Dim; ++d) {
      per_axis.push_back(static_cast<std::int64_t>(grid.nodes(d)));
      origin.push_back(grid.origin()[d]);
      cell_size.push_back(grid.cell_size()[d]);
    }
    file.set_attribute("nodes_per_axis", per_axis, "/grid");
    file.set_attribute("origin", origin, "/grid");
    file.set_attribute("cell_size", cell_size, "/grid");
    std::vector<Vec<Dim>> positions(static_cast<std::size_t>(count));
    for (Index n = 0; n < count; ++n)
      positions[static_cast<std::size_t>(n)] = grid.node_position(n);
    detail::MeshWriter mesh(&file, "/grid", "grid", count);
    mesh.eigen("position", &positions);
    mesh.scalar("mass", nodes.mass.data());
    mesh.eigen("velocity", &nodes.velocity);
    return mesh.take();
  }

  std::filesystem::path directory_;
  std::string prefix_;
  FrameOptions options_;
  XdmfWriter xdmf_;
  Index next_frame_ = 0;
};

}  // namespace cosmpm::io
