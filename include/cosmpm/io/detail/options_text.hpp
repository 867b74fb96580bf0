#pragma once
// The text formats of io::Options: --help, case files written (case.used) and case-file
// lines read. Included by io/options.hpp.
#include <string>
#include <string_view>
#include <utility>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/detail/option_values.hpp"
#include "cosmpm/io/options.hpp"  // the class whose members this file defines

namespace cosmpm::io {

namespace detail {
// Appends `text` wrapped at `width` columns, continuation lines indented by `indent`.
inline void append_wrapped(std::string& out, std::string_view text, std::size_t column,
                           std::size_t indent, std::size_t width = 96) {
  while (!text.empty()) {
    std::size_t room = width > column ? width - column : 20;
    std::size_t cut = text.size();
    if (cut > room) {
      cut = text.rfind(' ', room);
      if (cut == std::string_view::npos || cut == 0) cut = std::min(room, text.size());
    }
    out += std::string(text.substr(0, cut)) + "\n";
    text.remove_prefix(cut);
    while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    if (!text.empty()) out += std::string(indent, ' ');
    column = indent;
  }
}

// A value as a case file holds it: quoted (with \" and \\) when it has blanks at its ends,
// a '#' that would begin a comment, or quotes.
inline std::string case_value(const std::string& value) {
  bool quote = value.empty() || value.front() == ' ' || value.back() == ' ' ||
               value.front() == '#' || value.find('"') != std::string::npos ||
               value.find('\\') != std::string::npos || value.find(" #") != std::string::npos ||
               value.find('\t') != std::string::npos;
  if (!quote) return value;
  std::string out = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}
}  // namespace detail

inline std::string Options::help() const {
  std::string out = "usage: " + program_ + " [--case FILE] [--name value ...]\n";
  detail::append_wrapped(out, summary_, 0, 0);
  out +=
      "\nEach option is --name value or --name=value (a flag alone means true). --case FILE "
      "reads\nname = value lines from a case file first; the command line overrides them. "
      "Giving an\noption twice is an error. --help prints this.\n";
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    out += "\n" + groups_[g] + ":\n";
    for (const auto& o : options_) {
      if (o.group != g) continue;
      std::string head = "  --" + o.name + " " + o.hint;
      constexpr std::size_t column = 36;
      if (head.size() + 2 > column) {
        out += head + "\n" + std::string(column, ' ');
      } else {
        out += head + std::string(column - head.size(), ' ');
      }
      std::string text = o.meaning;
      if (!o.unit.empty()) text += " [" + o.unit + "]";
      text += ". Default: " + (o.default_text.empty() ? std::string("none") : o.default_text);
      if (!o.valid.empty()) text += "; " + o.valid;
      if (o.role == Role::control) text += " (steers the run; not part of its case)";
      if (o.role == Role::shorthand) text += " (a shorthand; case files hold what it sets)";
      detail::append_wrapped(out, text, column, column);
    }
  }
  return out;
}

inline std::string Options::case_text(const std::string& header) const {
  std::string out;
  std::string_view rest = header;
  while (!rest.empty()) {
    const std::size_t end = std::min(rest.find('\n'), rest.size());
    out += "# " + std::string(rest.substr(0, end)) + "\n";
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  out += "# One `name = value` per line; `#` begins a comment. Read it with --case FILE.\n";
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    bool first = true;
    for (const auto& o : options_) {
      if (o.group != g || o.role != Role::setting) continue;
      if (first) out += "\n# --- " + groups_[g] + "\n";
      first = false;
      std::string comment = o.meaning;
      if (!o.unit.empty()) comment += " [" + o.unit + "]";
      if (!o.valid.empty()) comment += "; " + o.valid;
      out += "# " + comment + "\n";
      out += o.name + " = " + detail::case_value(o.show()) + "\n";
    }
  }
  return out;
}

inline std::pair<std::string, std::string> Options::split_line(std::string_view line,
                                                               const std::string& where) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const auto first = line.find_first_not_of(" \t");
  if (first == std::string_view::npos || line[first] == '#') return {};
  const auto eq = line.find('=');
  if (eq == std::string_view::npos) {
    throw Error(where + ": expected 'name = value', found '" + detail::printable(line) + "'");
  }
  const std::string name = detail::trim(line.substr(0, eq));
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != std::string::npos) {
    throw Error(where + ": '" + detail::printable(name) +
                "' is not an option name (lower-case letters, digits and '-')");
  }
  std::string_view rest = line.substr(eq + 1);
  while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
  std::string value;
  if (!rest.empty() && rest.front() == '"') {
    std::size_t i = 1;
    for (; i < rest.size() && rest[i] != '"'; ++i) {
      if (rest[i] == '\\') {
        if (i + 1 >= rest.size() || (rest[i + 1] != '"' && rest[i + 1] != '\\')) {
          throw Error(where + ": only \\\" and \\\\ may follow a backslash inside quotes");
        }
        ++i;
      }
      value += rest[i];
    }
    if (i >= rest.size()) throw Error(where + ": the quoted value of '" + name + "' is not closed");
    const std::string after = detail::trim(rest.substr(i + 1));
    if (!after.empty() && after.front() != '#') {
      throw Error(where + ": unexpected text after the quoted value of '" + name + "': '" +
                  detail::printable(after) + "'");
    }
    return {name, value};
  }
  std::size_t end = rest.size();
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] == '#' && (i == 0 || rest[i - 1] == ' ' || rest[i - 1] == '\t')) {
      end = i;
      break;
    }
  }
  value = detail::trim(rest.substr(0, end));
  if (value.empty()) throw Error(where + ": '" + name + "' has no value after '='");
  return {name, value};
}

}  // namespace cosmpm::io
