#pragma once
// Structure-of-arrays particle storage keyed by typed field tags. A tag is an empty struct
// with `value_type` and a `label()` that is also the field's HDF5 dataset name; which fields
// exist follows from the composition (continuum and material), never from a runtime flag.
#include <concepts>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/core/types.hpp"

namespace cosmpm::particles {

template <class Tag>
concept FieldTag = requires {
  typename Tag::value_type;
  { Tag::label() } -> std::convertible_to<std::string_view>;
};

template <FieldTag... Tags>
class Store {
 public:
  using tags = std::tuple<Tags...>;

  template <class Tag>
  static constexpr bool has = (std::is_same_v<Tag, Tags> || ...);

  Index size() const { return size_; }

  // Appends `count` value-initialised particles and returns the index of the first one.
  Index append(Index count) {
    const Index first = size_;
    resize(size_ + count);
    return first;
  }

  void resize(Index count) {
    std::apply([count](auto&... column) { (resize_zeroed(column, count), ...); }, columns_);
    size_ = count;
  }

  // Moves the particles whose `leaving(p)` is true to the end of `to` (another store of the
  // same fields) and closes the gaps, keeping the order of those that stay; returns how many
  // moved. `to` may be null: then they are dropped.
  template <class Predicate>
  Index extract_if(Predicate&& leaving, Store* to) {
    std::vector<Index> moving;
    for (Index p = 0; p < size_; ++p) {
      if (leaving(p)) moving.push_back(p);
    }
    if (moving.empty()) return 0;
    if (to != nullptr) {
      const Index first = to->append(static_cast<Index>(moving.size()));
      [&]<std::size_t... I>(std::index_sequence<I...>) {
        (copy_rows(std::get<I>(columns_), moving, std::get<I>(to->columns_), first), ...);
      }
      (std::index_sequence_for<Tags...>{});
    }
    std::apply([&](auto&... column) { (close_gaps(column, moving), ...); }, columns_);
    size_ -= static_cast<Index>(moving.size());
    return static_cast<Index>(moving.size());
  }

  void reserve(Index count) {
    std::apply([count](auto&... column) { (column.reserve(count), ...); }, columns_);
  }

  template <class Tag>
  requires has<Tag> std::vector<typename Tag::value_type>
  &get() { return std::get<index_of<Tag>()>(columns_); }

  template <class Tag>
  requires has<Tag>
  const std::vector<typename Tag::value_type>& get() const {
    return std::get<index_of<Tag>()>(columns_);
  }

  // Calls f(Tag{}, column) for every field, in declaration order.
  template <class F>
  void for_each_field(F&& f) {
    (f(Tags{}, get<Tags>()), ...);
  }
  template <class F>
  void for_each_field(F&& f) const {
    (f(Tags{}, get<Tags>()), ...);
  }

 private:
  template <class Tag>
  static constexpr std::size_t index_of() {
    std::size_t index = 0;
    std::size_t found = 0;
    ((std::is_same_v<Tag, Tags> ? (found = index, ++index) : ++index), ...);
    return found;
  }

  template <class T>
  static void copy_rows(const std::vector<T>& from, const std::vector<Index>& rows,
                        std::vector<T>& to, Index first) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
      to[static_cast<std::size_t>(first) + k] = from[static_cast<std::size_t>(rows[k])];
    }
  }

  // Removes `rows` (ascending) from the column, shifting the others down in order.
  template <class T>
  static void close_gaps(std::vector<T>& column, const std::vector<Index>& rows) {
    std::size_t write = static_cast<std::size_t>(rows.front());
    std::size_t next_row = 0;
    for (std::size_t read = write; read < column.size(); ++read) {
      if (next_row < rows.size() && read == static_cast<std::size_t>(rows[next_row])) {
        ++next_row;
        continue;
      }
      column[write++] = column[read];
    }
    column.resize(write);
  }

  // New entries are zero: vector::resize value-initialises, which for Eigen's fixed-size types
  // runs a default constructor that leaves the coefficients uninitialised.
  template <class T>
  static void resize_zeroed(std::vector<T>& column, Index count) {
    if constexpr (requires { T::Zero(); }) {
      column.resize(static_cast<std::size_t>(count), T(T::Zero()));
    } else {
      column.resize(static_cast<std::size_t>(count));
    }
  }

  // One column per tag, found by position, so tags sharing a value_type stay distinct.
  std::tuple<std::vector<typename Tags::value_type>...> columns_;
  Index size_ = 0;
};

// A store with the fields of Store and Extra (e.g. the fields a velocity transfer adds).
template <class Store, class... Extra>
struct AppendFields;
template <FieldTag... Tags, FieldTag... Extra>
struct AppendFields<Store<Tags...>, Extra...> {
  using type = Store<Tags..., Extra...>;
};
template <class S, class... Extra>
using append_fields_t = typename AppendFields<S, Extra...>::type;

}  // namespace cosmpm::particles
