#pragma once
// Shortest text that reads back to the same double (std::to_chars round trip), so text
// outputs (CSV, XDMF times) lose nothing.
#include <charconv>
#include <string>
#include <system_error>

namespace cosmpm::io::detail {

inline std::string format_number_exact(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (result.ec != std::errc{}) return "nan";  // unreachable: 64 chars hold any double
  return std::string(buffer, result.ptr);
}

}  // namespace cosmpm::io::detail
