// Fuzzing the command-line and case-file parsers for a bounded time: random and mutated
// inputs (from the sample case files and a dictionary of troublesome values) against the
// generic options and the real option tables of examples 02 and 03, with their checks. Each
// input must end in success or a cosmpm::Error, never another exception, a crash, undefined
// behaviour (the sanitizer build checks float-cast-overflow too) or a hang (each input has
// 0.5 s); a successful parse's case file must read back to itself. The seeds are fixed, so a
// failure names its input and repeats. COSMPM_FUZZ_SECONDS sets the time per target (CI runs
// the sanitizer build with more).
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../../examples/02_earth_pressure/case.hpp"
#include "../../examples/03_flat_blade/case.hpp"
#include "../../examples/03_flat_blade/feasibility.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/options.hpp"

namespace {
using namespace cosmpm;
using Clock = std::chrono::steady_clock;

double fuzz_seconds() {
  const char* text = std::getenv("COSMPM_FUZZ_SECONDS");
  if (text == nullptr) return 1.0;
  const auto value = io::detail::parse_real(text);
  return value && *value > 0.0 ? *value : 1.0;
}

const std::vector<std::string> dictionary{"0",
                                          "-0",
                                          "1",
                                          "-1",
                                          "+1",
                                          "1e308",
                                          "1e309",
                                          "-1e308",
                                          "1e-300",
                                          "4.9e-324",
                                          "nan",
                                          "inf",
                                          "-inf",
                                          "NaN",
                                          "0x10",
                                          "1e20",
                                          "9223372036854775807",
                                          "9223372036854775808",
                                          "-9223372036854775809",
                                          "4.5",
                                          "40.6x24.4",
                                          "120x70",
                                          "100000x100000",
                                          "4x4",
                                          "x",
                                          "1x",
                                          "true",
                                          "false",
                                          "yes",
                                          "2",
                                          "on",
                                          "\"",
                                          "\"a # b\"",
                                          "\\",
                                          "#",
                                          " #",
                                          "=",
                                          "==",
                                          "\r",
                                          "\n",
                                          "\t",
                                          "\xEF\xBB\xBF",
                                          std::string("\0", 1),
                                          "\xff",
                                          "\xc3\xa9",
                                          "--",
                                          "---",
                                          "-",
                                          "",
                                          " ",
                                          "mohr-coulomb",
                                          "cosserat-drucker-prager",
                                          "gimp",
                                          "usf",
                                          "plane-strain",
                                          "0.15,0.25",
                                          ",",
                                          "0.1,,0.2",
                                          "/dev/zero",
                                          "/nonexistent/case",
                                          "."};

std::string random_text(std::mt19937_64& random, std::size_t max_length) {
  std::uniform_int_distribution<std::size_t> length(0, max_length);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string text(length(random), ' ');
  for (char& c : text) c = static_cast<char>(byte(random));
  return text;
}

template <class T>
const T& pick(std::mt19937_64& random, const std::vector<T>& items) {
  return items[std::uniform_int_distribution<std::size_t>(0, items.size() - 1)(random)];
}

// One byte-level change of `text`: flip, insert, delete, repeat a line, or splice a word.
void mutate(std::mt19937_64& random, std::string& text) {
  std::uniform_int_distribution<int> kind(0, 5);
  auto at = [&] { return std::uniform_int_distribution<std::size_t>(0, text.size())(random); };
  switch (kind(random)) {
    case 0:
      if (!text.empty()) text[at() % text.size()] ^= static_cast<char>(1 << (random() % 8));
      break;
    case 1:
      text.insert(at(), pick(random, dictionary));
      break;
    case 2: {
      const std::size_t from = at();
      text.erase(from, std::uniform_int_distribution<std::size_t>(0, 40)(random));
      break;
    }
    case 3: {
      const std::size_t from = text.rfind('\n', at());
      const std::size_t start = from == std::string::npos ? 0 : from + 1;
      const std::size_t end = std::min(text.find('\n', start), text.size());
      text.insert(start, text.substr(start, end - start) + "\n");
      break;
    }
    case 4:
      text.insert(at(), random_text(random, 8));
      break;
    default: {
      // Replace a value after '=' with a word of the dictionary.
      const std::size_t eq = text.find('=', at());
      if (eq != std::string::npos) {
        const std::size_t end = std::min(text.find('\n', eq), text.size());
        text.replace(eq + 1, end - eq - 1, " " + pick(random, dictionary));
      }
    }
  }
}

// A program's option table: fills `options` for a fresh settings object and checks after a
// parse (throwing cosmpm::Error on bad combinations).
struct Target {
  std::string name;
  std::function<void(const std::function<void(io::Options&)>&)> with_options;
};

std::vector<std::string> option_names(const io::Options& options) {
  std::vector<std::string> names{"case", "help"};
  std::istringstream help(options.help());
  for (std::string word; help >> word;) {
    if (word.rfind("--", 0) == 0 && word.size() > 2 && word.find('=') == std::string::npos) {
      names.push_back(word.substr(2));
    }
  }
  return names;
}

std::vector<std::string> seed_case_files() {
  std::vector<std::string> seeds;
  const auto cases = std::filesystem::path(__FILE__).parent_path() / ".." / ".." / "examples" /
                     "03_flat_blade" / "cases";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(cases, error)) {
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    seeds.push_back(text.str());
  }
  seeds.push_back("depth = 0.1\ncells-x = 8\nout = a\n");
  return seeds;
}

// Runs `input` through a fresh option table; returns false (with a message) if it ended in
// anything but success or a cosmpm::Error, took too long, or failed to read back.
bool survives(const Target& target, const std::function<void(io::Options&)>& input,
              std::string& failure, long& accepted) {
  const auto start = Clock::now();
  try {
    target.with_options([&](io::Options& options) {
      try {
        input(options);
      } catch (const Error&) {
        return;  // the expected outcome of a bad input
      }
      ++accepted;
      const std::string text = options.case_text("fuzz");
      target.with_options([&](io::Options& again) {
        try {
          again.read_case_text(text, "round trip");
        } catch (const Error& error) {
          failure = std::string("the case file written after the parse fails to read back: ") +
                    error.what();
          return;
        }
        if (again.case_text("fuzz") != text) {
          failure = "the case file written after the parse reads back to other values";
        }
      });
    });
  } catch (const std::exception& error) {
    failure = std::string("a non-cosmpm exception: ") + error.what();
  }
  if (failure.empty() && Clock::now() - start > std::chrono::milliseconds(500)) {
    failure = "took more than 0.5 s";
  }
  return failure.empty();
}

void fuzz(const Target& target, unsigned seed) {
  std::mt19937_64 random(seed);
  std::vector<std::string> names;
  target.with_options([&](io::Options& options) { names = option_names(options); });
  const std::vector<std::string> seeds = seed_case_files();
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(fuzz_seconds()));
  long inputs = 0;
  long accepted = 0;
  while (Clock::now() < deadline) {
    ++inputs;
    std::string failure;
    std::string shown;
    if (inputs % 2 == 0) {
      // A command line of options, values, tricky words and garbage.
      std::vector<std::string> args{"prog"};
      const int count = std::uniform_int_distribution<int>(0, 10)(random);
      for (int i = 0; i < count; ++i) {
        switch (std::uniform_int_distribution<int>(0, 4)(random)) {
          case 0:
            args.push_back("--" + pick(random, names));
            break;
          case 1:
            args.push_back("--" + pick(random, names) + "=" + pick(random, dictionary));
            break;
          case 2:
            args.push_back(pick(random, dictionary));
            break;
          case 3:
            args.push_back(random_text(random, 12));
            break;
          default:
            args.push_back("--" + pick(random, names));
            args.push_back(pick(random, dictionary));
        }
      }
      std::vector<const char*> argv;
      for (const auto& a : args) argv.push_back(a.c_str());
      for (const auto& a : args) {
        // Appended piece by piece: GCC 12 warns (-Wrestrict) on "literal" + std::string&&.
        shown += '[';
        shown += io::detail::printable(a);
        shown += "] ";
      }
      survives(
          target,
          [&](io::Options& options) { options.parse(static_cast<int>(argv.size()), argv.data()); },
          failure, accepted);
    } else {
      // A sample case file with a few mutations.
      std::string text = pick(random, seeds);
      const int changes = std::uniform_int_distribution<int>(1, 6)(random);
      for (int i = 0; i < changes; ++i) mutate(random, text);
      shown = io::detail::printable(text);
      survives(
          target, [&](io::Options& options) { options.read_case_text(text, "fuzz.case"); }, failure,
          accepted);
    }
    if (!failure.empty()) {
      FAIL_CHECK(target.name << ", input " << inputs << " (seed " << seed << "): " << failure
                             << "\n  input: " << shown);
      return;
    }
  }
  MESSAGE(target.name << ": " << inputs << " inputs in " << fuzz_seconds() << " s (" << accepted
                      << " parsed, the others refused with a cosmpm::Error)");
  CHECK(inputs > 10);
  CHECK(accepted > 0);  // the fuzzer reaches the paths past parsing too
}
}  // namespace

TEST_CASE("fuzz: the options of example 03 (flat blade) with their checks") {
  fuzz({"example 03",
        [](const std::function<void(io::Options&)>& use) {
          flat_blade::Case c;
          io::Options options("example_03_flat_blade", "fuzz");
          flat_blade::declare_options(options, c);
          use(options);
          // The checks that follow parsing in the program must end cleanly too.
          try {
            flat_blade::validate(options, c);
            flat_blade::check_memory(c, options);
            (void)flat_blade::seeded_particles(c);
            (void)c.tag();
          } catch (const Error&) {
          }
        }},
       20260101u);
}

TEST_CASE("fuzz: the options of example 02 (earth pressure) with their checks") {
  fuzz({"example 02",
        [](const std::function<void(io::Options&)>& use) {
          earth_pressure::Case c;
          io::Options options("example_02_earth_pressure", "fuzz");
          earth_pressure::declare_options(options, c);
          use(options);
          try {
            earth_pressure::validate(options, c);
            (void)earth_pressure::estimated_seconds_per_depth(c);
          } catch (const Error&) {
          }
        }},
       20260102u);
}
