#pragma once
// HDF5 identifiers closed by RAII, HDF5's error stack as message text, and the native types
// of the element types cosmpm writes. The only header that includes <hdf5.h>: everything
// under cosmpm/io/hdf5*.hpp and cosmpm/io/checkpoint.hpp needs the cosmpm::hdf5 target.
#if defined(__has_include) && !__has_include(<hdf5.h>)
#error \
    "cosmpm/io/hdf5*.hpp and cosmpm/io/checkpoint.hpp need HDF5: link the CMake target cosmpm::hdf5 (find_package(cosmpm COMPONENTS hdf5); Debian package libhdf5-dev)"
#else
#include <hdf5.h>

#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace cosmpm::io::detail {

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

}  // namespace cosmpm::io::detail
#endif
