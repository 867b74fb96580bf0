#pragma once
// Options of a program from its command line and a case file, declared once with their
// meaning, unit, default and valid range, which --help prints and every error repeats.
//
//   io::Options options("example_03_flat_blade", "The flat blade of Coetzee (2014).");
//   options.group("Soil");
//   options.real("youngs-modulus", c.youngs_modulus, io::RealRange::positive(), "Pa",
//                "Young's modulus E");
//   options.integer("cells-x", c.cells_x, 4, 100000, "cells along x");
//   if (options.parse(argc, argv) == io::Options::Outcome::help) {
//     std::fputs(options.help().c_str(), stdout);
//     return 0;
//   }
//
// Command line: --name value or --name=value; a flag alone means true. --case FILE reads a
// case file first and the command line overrides it. Case file (UTF-8 text, at most 1 MiB):
// one `name = value` per line; `#` begins a comment at the start of a line or after a blank;
// a value in double quotes keeps blanks and `#` ("\"" and "\\" inside). Every error is a
// cosmpm::Error naming the option, the value, the valid range and where it was given; an
// option given twice (on the command line, or in one case file) is an error.
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/detail/option_values.hpp"

namespace cosmpm::io {

// The valid values of a real option (always finite).
struct RealRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  Bounds bounds = Bounds::open;

  static RealRange positive() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static RealRange non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), Bounds::left_closed};
  }
  bool contains(double v) const {
    const bool left = bounds == Bounds::closed || bounds == Bounds::left_closed;
    const bool right = bounds == Bounds::closed || bounds == Bounds::right_closed;
    return (left ? v >= lo : v > lo) && (right ? v <= hi : v < hi);
  }
  std::string text() const {
    const bool left = bounds == Bounds::closed || bounds == Bounds::left_closed;
    const bool right = bounds == Bounds::closed || bounds == Bounds::right_closed;
    return std::string(left ? "[" : "(") + detail::format_number_exact(lo) + ", " +
           detail::format_number_exact(hi) + (right ? "]" : ")");
  }
};

class Options {
 public:
  enum class Outcome { run, help };
  // A setting is part of the run (recorded in case files written by case_text); a control
  // option only steers it (output folder, threads, restart); a shorthand sets other options
  // (which are recorded instead).
  enum class Role { setting, control, shorthand };
  enum class Origin { default_value, case_file, command_line };

  Options(std::string program, std::string summary)
      : program_(std::move(program)), summary_(std::move(summary)) {}

  // Options added after this call are listed under `title` in --help and case files.
  void group(std::string title) { groups_.push_back(std::move(title)); }

  void real(std::string name, double& target, RealRange range, std::string unit,
            std::string meaning, Role role = Role::setting) {
    auto set = [&target, range, unit](std::string_view value, const std::string& where) {
      const auto parsed = detail::parse_real(value);
      if (!parsed) {
        throw Error(where + " = '" + detail::printable(value) + "' is not a finite number");
      }
      if (!range.contains(*parsed)) {
        throw Error(where + " = " + detail::format_number_exact(*parsed) +
                    (unit.empty() ? "" : " " + unit) + " is outside the valid range " +
                    range.text());
      }
      target = *parsed;
    };
    auto show = [&target] { return detail::format_number_exact(target); };
    std::string hint = "<" + (unit.empty() ? std::string("number") : unit) + ">";
    add(std::move(name), std::move(hint), std::move(meaning), std::move(unit),
        "valid " + range.text(), role, set, show);
  }

  // A whole number, parsed as an integer and checked before it is stored.
  template <class Int>
  requires std::is_integral_v<Int>
  void integer(std::string name, Int& target, std::int64_t lo, std::int64_t hi, std::string meaning,
               Role role = Role::setting) {
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    auto set = [&target, lo, hi, range](std::string_view value, const std::string& where) {
      std::int64_t parsed = 0;
      const auto status = detail::parse_integer(value, parsed);
      if (status == detail::IntegerParse::not_integer) {
        throw Error(where + " = '" + detail::printable(value) +
                    "' is not a whole number written as digits (valid " + range + ")");
      }
      if (status == detail::IntegerParse::out_of_range || parsed < lo || parsed > hi) {
        throw Error(where + " = " + detail::printable(value) + " is outside the valid range " +
                    range);
      }
      target = static_cast<Int>(parsed);  // lo and hi fit Int: checked when declared
    };
    auto show = [&target] { return std::to_string(target); };
    require(lo >= static_cast<std::int64_t>(std::numeric_limits<Int>::min()) &&
                hi <= static_cast<std::int64_t>(std::numeric_limits<Int>::max()),
            "Options::integer: the range of '" + name + "' does not fit its type");
    add(std::move(name), "<integer>", std::move(meaning), "", "valid " + range, role, set, show);
  }

  void flag(std::string name, bool& target, std::string meaning, Role role = Role::setting) {
    auto set = [&target](std::string_view value, const std::string& where) {
      if (value == "true" || value == "yes" || value == "on" || value == "1") {
        target = true;
      } else if (value == "false" || value == "no" || value == "off" || value == "0") {
        target = false;
      } else {
        throw Error(where + " = '" + detail::printable(value) +
                    "' is not true or false (valid: true, false, yes, no, on, off, 1, 0)");
      }
    };
    auto show = [&target] { return std::string(target ? "true" : "false"); };
    add(std::move(name), "<true|false>", std::move(meaning), "", "", role, set, show);
    options_.back().is_flag = true;
  }

  void choice(std::string name, std::string& target, std::vector<std::string> choices,
              std::string meaning, Role role = Role::setting) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    auto set = [&target, choices, list](std::string_view value, const std::string& where) {
      for (const auto& c : choices) {
        if (value == c) {
          target = c;
          return;
        }
      }
      throw Error(where + " = '" + detail::printable(value) + "' is not one of " + list);
    };
    auto show = [&target] { return target; };
    add(std::move(name), "<choice>", std::move(meaning), "", "one of " + list, role, set, show);
  }

  void text(std::string name, std::string& target, std::string hint, std::string meaning,
            Role role = Role::setting) {
    auto set = [&target](std::string_view value, const std::string& where) {
      if (value.empty()) throw Error(where + " is empty");
      for (const char c : value) {
        if (static_cast<unsigned char>(c) < 0x20) {
          throw Error(where + " = '" + detail::printable(value) + "' contains control characters");
        }
      }
      target = std::string(value);
    };
    auto show = [&target] { return target; };
    add(std::move(name), "<" + hint + ">", std::move(meaning), "", "", role, set, show);
  }

  // An option with its own parser (`set` throws an Error starting with `where`).
  void custom(std::string name, std::string hint, std::string meaning, std::string valid,
              std::function<void(std::string_view, const std::string&)> set,
              std::function<std::string()> show, Role role = Role::setting) {
    add(std::move(name), "<" + hint + ">", std::move(meaning), "", std::move(valid), role,
        std::move(set), std::move(show));
  }

  // Reads --case FILE (if given) and then the other command-line options.
  Outcome parse(int argc, const char* const* argv) {
    for (int i = 1; i < argc; ++i) {
      const std::string_view arg = argv[i];
      if (arg == "--help" || arg == "-h") return Outcome::help;
    }
    std::vector<std::pair<std::string, std::string>> given;  // name, value
    std::string case_file;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
        throw Error("command line: unexpected argument '" + detail::printable(arg) +
                    "' (options are --name value; see --help)");
      }
      std::string name = arg.substr(2);
      std::string value;
      const auto eq = name.find('=');
      const Option* option = nullptr;
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name.resize(eq);
      }
      if (name != "case") option = &find(name, "command line --" + detail::printable(name));
      if (eq == std::string::npos) {
        const bool next_is_option =
            i + 1 >= argc || std::string_view(argv[i + 1]).rfind("--", 0) == 0;
        if (option != nullptr && option->is_flag && next_is_option) {
          value = "true";
        } else if (i + 1 < argc) {
          value = argv[++i];
        } else {
          throw Error("command line --" + name + " needs a value" +
                      (option != nullptr ? " " + option->hint : std::string(" <FILE>")));
        }
      }
      for (const auto& [earlier, earlier_value] : given) {
        if (earlier == name) {
          throw Error("command line --" + name + " is given twice ('" +
                      detail::printable(earlier_value) + "' and '" + detail::printable(value) +
                      "'); give it once");
        }
      }
      given.emplace_back(name, value);
      if (name == "case") case_file = value;
    }
    if (!case_file.empty()) read_case_file(case_file);
    for (const auto& [name, value] : given) {
      if (name != "case") set(name, value, "command line --" + name, Source::command_line);
    }
    return Outcome::run;
  }

  // Reads a case file (see the top of this header); errors name the file and the line.
  void read_case_file(const std::filesystem::path& path) {
    const std::string name = "case file '" + path.string() + "'";
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error) throw Error(name + ": cannot open it (" + error.message() + ")");
    if (std::filesystem::is_directory(status)) throw Error(name + " is a folder, not a file");
    if (!std::filesystem::is_regular_file(status)) throw Error(name + " is not a regular file");
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) throw Error(name + ": cannot open it (" + std::strerror(errno) + ")");
    std::string text(std::size_t{1} << 20, '\0');
    const std::size_t read = std::fread(text.data(), 1, text.size(), file);
    const bool more = std::fgetc(file) != EOF;
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) throw Error(name + ": cannot read it");
    if (more) throw Error(name + " is larger than 1 MiB, too large for a case file");
    text.resize(read);
    read_case_text(text, path.string());
  }

  void read_case_text(std::string_view text, const std::string& file_name) {
    if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.remove_prefix(3);  // UTF-8 byte order mark
    std::vector<std::pair<std::string, int>> seen;                  // name, line
    int line_number = 0;
    while (!text.empty()) {
      ++line_number;
      const std::size_t end = std::min(text.find('\n'), text.size());
      const std::string_view line = text.substr(0, end);
      text.remove_prefix(std::min(end + 1, text.size()));
      const std::string where = "case file '" + file_name + "' line " + std::to_string(line_number);
      auto [name, value] = split_line(line, where);
      if (name.empty()) continue;
      if (name == "case") throw Error(where + ": a case file cannot name another case file");
      for (const auto& [earlier, earlier_line] : seen) {
        if (earlier == name) {
          throw Error(where + ": '" + name + "' is already set on line " +
                      std::to_string(earlier_line) + "; set it once");
        }
      }
      seen.emplace_back(name, line_number);
      set(name, value, where + " (" + name + ")", Source::case_file);
    }
  }

  std::string help() const;
  // A case file of the current values of the settings (not the control options), grouped,
  // each with its meaning; reading it back gives the same values bit for bit.
  std::string case_text(const std::string& header) const;

  bool given(std::string_view name) const { return option(name).source != Source::default_value; }
  Origin origin(std::string_view name) const {
    const Source s = option(name).source;
    return s == Source::default_value ? Origin::default_value
           : s == Source::case_file   ? Origin::case_file
                                      : Origin::command_line;
  }
  // Given with a value other than the default (a case file written by case_text gives every
  // setting, most of them at their defaults).
  bool changed(std::string_view name) const {
    const Option& o = option(name);
    return o.source != Source::default_value && o.show() != o.default_text;
  }
  // Where the value came from: "command line --depth", "case file 'a.case' line 3 (depth)"
  // or "default".
  std::string where(std::string_view name) const {
    const Option& o = option(name);
    return o.source == Source::default_value ? "default --" + o.name : o.where;
  }
  // The option, its value and its origin, for messages: "--depth = 0.25 (default)".
  std::string describe(std::string_view name) const {
    const Option& o = option(name);
    std::string text = "--" + o.name + " = " + o.show() + (o.unit.empty() ? "" : " " + o.unit);
    if (o.source == Source::default_value) return text + " (default)";
    return text + " (" + (o.source == Source::command_line ? "command line" : o.where) + ")";
  }
  // Throws an Error that names the option with its value and origin, then `message`.
  [[noreturn]] void fail(std::string_view name, const std::string& message) const {
    throw Error(describe(name) + ": " + message);
  }

 private:
  enum class Source { default_value, case_file, command_line };
  struct Option {
    std::string name;
    std::size_t group = 0;
    std::string hint;
    std::string meaning;
    std::string unit;
    std::string valid;
    std::string default_text;
    Role role = Role::setting;
    bool is_flag = false;
    std::function<void(std::string_view, const std::string&)> set;
    std::function<std::string()> show;
    Source source = Source::default_value;
    std::string where;
  };

  void add(std::string name, std::string hint, std::string meaning, std::string unit,
           std::string valid, Role role,
           std::function<void(std::string_view, const std::string&)> set,
           std::function<std::string()> show) {
    require(!groups_.empty(), "Options: call group() before adding '" + name + "'");
    for (const auto& o : options_) {
      require(o.name != name, "Options: '" + name + "' is declared twice");
    }
    Option o;
    o.name = std::move(name);
    o.group = groups_.size() - 1;
    o.hint = std::move(hint);
    o.meaning = std::move(meaning);
    o.unit = std::move(unit);
    o.valid = std::move(valid);
    o.role = role;
    o.default_text = show();
    o.set = std::move(set);
    o.show = std::move(show);
    options_.push_back(std::move(o));
  }

  const Option& option(std::string_view name) const {
    for (const auto& o : options_) {
      if (o.name == name) return o;
    }
    throw Error("Options: no option '" + std::string(name) + "' is declared");
  }

  Option& find(const std::string& name, const std::string& where) {
    for (auto& o : options_) {
      if (o.name == name) return o;
    }
    std::vector<std::string> names{"case", "help"};
    for (const auto& o : options_) names.push_back(o.name);
    const std::string near = detail::nearest_name(name, names);
    throw Error(where + ": unknown option '" + detail::printable(name) + "'" +
                (near.empty() ? "" : " (did you mean --" + near + "?)") + "; --help lists them");
  }

  void set(const std::string& name, std::string_view value, const std::string& where,
           Source source) {
    Option& o = find(name, where);
    o.set(value, where);
    o.source = source;
    o.where = where;
  }

  // Name and value of one case-file line; both empty for a blank or comment line.
  static std::pair<std::string, std::string> split_line(std::string_view line,
                                                        const std::string& where);

  std::string program_;
  std::string summary_;
  std::vector<std::string> groups_;
  std::vector<Option> options_;
};

}  // namespace cosmpm::io

#include "cosmpm/io/detail/options_text.hpp"
