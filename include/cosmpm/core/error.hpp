#pragma once
// cosmpm::Error and the checks that raise it. Every message names the value, the valid
// range and where the value came from, so a user can fix the input without a debugger.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cosmpm {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
inline std::string format_number(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}
}  // namespace detail

// Whether the ends of a range belong to it.
enum class Bounds { open, closed, left_closed, right_closed };

// Throws unless `value` lies in the range (lo, hi) with the given ends. `where` names the
// caller or input source ("MohrCoulomb", "case file line 12"), `name` the parameter.
inline void require_in_range(std::string_view where, std::string_view name, double value, double lo,
                             double hi, Bounds bounds = Bounds::open) {
  const bool lo_ok =
      (bounds == Bounds::closed || bounds == Bounds::left_closed) ? value >= lo : value > lo;
  const bool hi_ok =
      (bounds == Bounds::closed || bounds == Bounds::right_closed) ? value <= hi : value < hi;
  if (lo_ok && hi_ok && std::isfinite(value)) return;
  const char left = (bounds == Bounds::closed || bounds == Bounds::left_closed) ? '[' : '(';
  const char right = (bounds == Bounds::closed || bounds == Bounds::right_closed) ? ']' : ')';
  throw Error(std::string(where) + ": " + std::string(name) + " = " + detail::format_number(value) +
              " is outside the valid range " + left + detail::format_number(lo) + ", " +
              detail::format_number(hi) + right);
}

inline void require_positive(std::string_view where, std::string_view name, double value) {
  if (value > 0.0 && std::isfinite(value)) return;
  throw Error(std::string(where) + ": " + std::string(name) + " = " + detail::format_number(value) +
              " must be positive and finite (valid range (0, inf))");
}

inline void require_non_negative(std::string_view where, std::string_view name, double value) {
  if (value >= 0.0 && std::isfinite(value)) return;
  throw Error(std::string(where) + ": " + std::string(name) + " = " + detail::format_number(value) +
              " must be non-negative and finite (valid range [0, inf))");
}

inline void require(bool condition, std::string_view message) {
  if (!condition) throw Error(std::string(message));
}

}  // namespace cosmpm
