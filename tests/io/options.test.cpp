// Command-line and case-file options: every kind of value, its checks and messages, the
// rules for repeats, comments, quotes and byte order marks, --help, and case files written
// from the values that read back to the same values bit for bit.
#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/options.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;

struct Settings {
  double depth = 0.25;
  double gravity = 9.81;
  long cells = 120;
  int threads = 0;
  bool polar = false;
  std::string shape = "linear";
  std::string out;
};

void declare(io::Options& options, Settings& s) {
  options.group("Rig");
  options.real("depth", s.depth, {0.0, 0.7, Bounds::right_closed}, "m", "soil depth h");
  options.real("gravity", s.gravity, io::RealRange::non_negative(), "m/s^2", "gravity");
  options.group("Numerics");
  options.integer("cells", s.cells, 4, 100000, "cells along x");
  options.integer("threads", s.threads, 0, 4096, "threads (0: all)", io::Options::Role::control);
  options.flag("polar", s.polar, "Cosserat soil");
  options.choice("shape", s.shape, {"linear", "gimp"}, "shape function");
  options.text("out", s.out, "DIR", "output folder", io::Options::Role::control);
}

// Options bound to settings; parse() returns the error text or "".
struct Harness {
  Settings s;
  io::Options options{"prog", "A test program."};
  Harness() { declare(options, s); }
  std::string parse(const std::vector<std::string>& args) {
    std::vector<const char*> argv{"prog"};
    for (const auto& a : args) argv.push_back(a.c_str());
    try {
      options.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  }
};

std::string parse(const std::vector<std::string>& args) {
  return Harness().parse(args);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string write_case(const std::string& name, const std::string& text) {
  const auto path = test_io::output_dir("options_" + name) / (name + ".case");
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}
}  // namespace

TEST_CASE("options parse every kind of value from the command line") {
  Harness h;
  auto& s = h.s;
  CHECK(h.parse({"--depth", "0.15", "--cells=80", "--polar", "--shape", "gimp", "--threads", "2",
                 "--gravity", "+1e1", "--out", "a b"}) == "");
  CHECK(s.depth == 0.15);
  CHECK(s.cells == 80);
  CHECK(s.polar);
  CHECK(s.shape == "gimp");
  CHECK(s.threads == 2);
  CHECK(s.gravity == 10.0);
  CHECK(s.out == "a b");
  CHECK(parse({"--polar", "false", "--depth", "-0"}) ==
        "command line --depth = -0 m is outside the valid range (0, 0.7]");
}

TEST_CASE("bad values name the option, the value, the valid range and where") {
  // Integers are parsed as integers: no rounding, no cast of a huge double.
  CHECK(parse({"--cells", "1e20"}) ==
        "command line --cells = '1e20' is not a whole number written as digits (valid [4, "
        "100000])");
  CHECK(parse({"--cells", "40.6"}) ==
        "command line --cells = '40.6' is not a whole number written as digits (valid [4, "
        "100000])");
  CHECK(parse({"--cells", "99999999999999999999"}) ==
        "command line --cells = 99999999999999999999 is outside the valid range [4, 100000]");
  CHECK(parse({"--threads", "nan"}) ==
        "command line --threads = 'nan' is not a whole number written as digits (valid [0, "
        "4096])");
  CHECK(parse({"--depth", "nan"}) == "command line --depth = 'nan' is not a finite number");
  CHECK(parse({"--depth", "1e400"}) == "command line --depth = '1e400' is not a finite number");
  CHECK(parse({"--depth", "0.25m"}) == "command line --depth = '0.25m' is not a finite number");
  CHECK(parse({"--polar", "maybe"}) ==
        "command line --polar = 'maybe' is not true or false (valid: true, false, yes, no, on, "
        "off, 1, 0)");
  CHECK(parse({"--shape", "cubic"}) == "command line --shape = 'cubic' is not one of linear, gimp");
  CHECK(contains(parse({"--dept", "0.1"}), "unknown option 'dept' (did you mean --depth?)"));
  CHECK(contains(parse({"--depth"}), "command line --depth needs a value <m>"));
  CHECK(contains(parse({"0.25"}), "unexpected argument '0.25'"));
  CHECK(contains(parse({"--out", "a\tb"}), "contains control characters"));
  // Repeats are errors, not "the last one wins".
  CHECK(parse({"--depth", "0.1", "--depth", "0.2"}) ==
        "command line --depth is given twice ('0.1' and '0.2'); give it once");
}

TEST_CASE("case files: comments, quotes, byte order marks, repeats and the command line") {
  Harness h;
  auto& s = h.s;
  const std::string good = write_case("good",
                                      "\xEF\xBB\xBF# a comment\n"
                                      "depth = 0.35   # inline comment after a blank\n"
                                      "\n"
                                      "out = runs/hash#dir\n"
                                      "shape=gimp\r\n"
                                      "cells = 60\n");
  CHECK(h.parse({"--case", good, "--cells", "70"}) == "");
  CHECK(s.depth == 0.35);
  CHECK(s.out == "runs/hash#dir");  // '#' inside a value is kept
  CHECK(s.shape == "gimp");
  CHECK(s.cells == 70);  // the command line wins over the case file
  Harness q;
  CHECK(q.parse({"--case", write_case("quoted", "out = \"a # b \\\"c\\\" \"  # note\n")}) == "");
  CHECK(q.s.out == "a # b \"c\" ");

  const std::string twice = write_case("twice", "depth = 0.1\n\ncells = 8\ndepth = 0.2\n");
  CHECK(contains(parse({"--case", twice}),
                 "twice.case' line 4: 'depth' is already set on line 1; set it once"));
  CHECK(contains(parse({"--case", write_case("bad", "cells = 12\ndepth 0.1\n")}),
                 "bad.case' line 2: expected 'name = value', found 'depth 0.1'"));
  CHECK(contains(parse({"--case", write_case("range", "depth = 2\n")}),
                 "range.case' line 1 (depth) = 2 m is outside the valid range (0, 0.7]"));
  // A byte order mark in the middle of a file is shown, not hidden.
  CHECK(contains(parse({"--case", write_case("mark",
                                             "cells = 8\n\xEF\xBB\xBF"
                                             "depth = 0.1\n")}),
                 "'\\xef\\xbb\\xbfdepth' is not an option name"));
  CHECK(contains(parse({"--case", write_case("empty", "depth =   # nothing\n")}),
                 "'depth' has no value after '='"));
  CHECK(contains(parse({"--case", write_case("open", "out = \"abc\n")}),
                 "the quoted value of 'out' is not closed"));
  CHECK(contains(parse({"--case", write_case("nested", "case = other.case\n")}),
                 "a case file cannot name another case file"));
  // Files that are not case files.
  const auto dir = test_io::output_dir("options_files");
  CHECK(contains(parse({"--case", dir.string()}), "is a folder, not a file"));
  CHECK(contains(parse({"--case", (dir / "missing.case").string()}),
                 "cannot open it (No such file or directory)"));
  if (std::filesystem::exists("/dev/zero")) {
    CHECK(contains(parse({"--case", "/dev/zero"}), "is not a regular file"));
  }
  CHECK(contains(parse({"--case", good, "--case", good}), "--case is given twice"));
}

TEST_CASE("help lists every option with meaning, unit, default and range, by group") {
  Harness h;
  const std::string help = h.options.help();
  MESSAGE(help);
  CHECK(contains(help, "usage: prog [--case FILE] [--name value ...]"));
  CHECK(contains(help, "\nRig:\n"));
  CHECK(contains(help, "\nNumerics:\n"));
  CHECK(contains(help, "--depth <m>"));
  CHECK(contains(help, "soil depth h [m]. Default: 0.25; valid (0, 0.7]"));
  CHECK(contains(help, "cells along x. Default: 120; valid [4, 100000]"));
  CHECK(contains(help, "shape function. Default: linear; one of linear, gimp"));
  CHECK(contains(help, "(steers the"));
  std::vector<const char*> argv{"prog", "--depth", "bad", "--help"};
  CHECK(h.options.parse(4, argv.data()) == io::Options::Outcome::help);
}

TEST_CASE("a case file written from the values reads back to the same values bit for bit") {
  Harness h;
  const Settings& s = h.s;
  const io::Options* options = &h.options;
  CHECK(h.parse({"--depth", "0.30000000000000004", "--gravity", "9.806649999999999", "--out",
                 "somewhere"}) == "");
  const std::string text = options->case_text("written by a test");
  MESSAGE(text);
  CHECK(contains(text, "# written by a test\n"));
  CHECK(contains(text, "depth = 0.30000000000000004\n"));
  CHECK_FALSE(contains(text, "out ="));  // control options are not part of the case
  CHECK_FALSE(contains(text, "threads ="));
  Harness back;
  CHECK(back.parse({"--case", write_case("round_trip", text)}) == "");
  CHECK(std::bit_cast<std::uint64_t>(back.s.depth) == std::bit_cast<std::uint64_t>(s.depth));
  CHECK(back.s.gravity == s.gravity);
  CHECK(back.s.cells == s.cells);
  // Given and origin of each value, for messages about options that depend on each other.
  CHECK(options->given("depth"));
  CHECK_FALSE(options->given("cells"));
  CHECK(options->describe("depth") == "--depth = 0.30000000000000004 m (command line)");
  CHECK(options->describe("cells") == "--cells = 120 (default)");
  try {
    options->fail("cells", "must exceed --depth / 0.01");
    FAIL("no error");
  } catch (const Error& error) {
    CHECK(std::string(error.what()) == "--cells = 120 (default): must exceed --depth / 0.01");
  }
}
