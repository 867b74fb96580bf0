#pragma once
// The composition signature of checkpoints (io/checkpoint.hpp): the type of every particle
// field, exact texts of doubles, and the first difference between two signatures in words.
#include <algorithm>
#include <cstdio>
#include <string>
#include <typeinfo>
#include <vector>

#include "cosmpm/io/field_layout.hpp"

#if __has_include(<cxxabi.h>)
#include <cxxabi.h>

#include <cstdlib>
#define COSMPM_IO_HAVE_CXXABI 1
#endif

namespace cosmpm::io::detail {

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

}  // namespace cosmpm::io::detail
