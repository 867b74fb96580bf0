// Output folders: created and checked up front, locked against a second run, never mixed
// with another run's results, cleaned of a killed run's temporary files; and the stop
// request that SIGINT and SIGTERM raise.
#include <doctest/doctest.h>

#include <csignal>
#include <fstream>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;
using Mode = io::RunDirectory::Mode;

std::string error_of(auto&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}
bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
}  // namespace

TEST_CASE("a run folder refuses another run's results unless replacing or continuing them") {
  const auto root = test_io::output_dir("run_directory");
  const auto dir = root / "run";
  {
    io::RunDirectory run(dir, Mode::fresh, "prog", "--out");
    std::ofstream(run.claim("forces.csv")) << "a\n";
    std::ofstream(run.claim("frames/f_000000.h5")) << "b\n";
    run.claim("never_written.csv");
    // Only files that exist are reported as written.
    CHECK(run.written() ==
          std::vector<std::filesystem::path>{dir / "forces.csv", dir / "frames/f_000000.h5"});
    // A second run into the same folder meets the lock.
    CHECK(contains(error_of([&] { io::RunDirectory(dir, Mode::replace, "prog", "--out"); }),
                   "is in use by another run (process"));
  }
  // The lock is gone with the run; the results stay and are refused to a fresh run.
  CHECK_FALSE(std::filesystem::exists(dir / io::RunDirectory::lock_name));
  CHECK(error_of([&] { io::RunDirectory(dir, Mode::fresh, "prog", "--out (default)"); }) ==
        "--out (default): output folder '" + dir.string() +
            "' holds the results of an earlier run (e.g. 'forces.csv'); choose another folder, "
            "or replace them (--replace true) or continue that run (--restart true)");
  // A killed run left a temporary file and its lock (of a process that no longer runs).
  std::ofstream(dir / "frames" / "f_000001.h5.tmp4242") << "partial";
  std::ofstream(dir / io::RunDirectory::lock_name) << "999999999\n";
  {
    io::RunDirectory resumed(dir, Mode::resume, "prog", "--out");
    CHECK_FALSE(std::filesystem::exists(dir / "frames" / "f_000001.h5.tmp4242"));
    CHECK(resumed.written().size() == 2);
  }
  {
    // Replacing deletes exactly the earlier run's files.
    io::RunDirectory replaced(dir, Mode::replace, "prog", "--out");
    CHECK_FALSE(std::filesystem::exists(dir / "forces.csv"));
    CHECK_FALSE(std::filesystem::exists(dir / "frames/f_000000.h5"));
    CHECK(replaced.written().empty());
  }
  // Another program's run is not continued.
  CHECK(contains(error_of([&] { io::RunDirectory(dir, Mode::resume, "other", "--out"); }),
                 "holds a run of prog, not of other"));
  // Files no run wrote are never deleted, not even with replace.
  std::ofstream(dir / "notes.txt") << "mine";
  CHECK(contains(error_of([&] { io::RunDirectory(dir, Mode::replace, "prog", "--out"); }),
                 "holds files no cosmpm run wrote (e.g. 'notes.txt')"));
  CHECK(std::filesystem::exists(dir / "notes.txt"));
  CHECK(contains(error_of([&] { io::RunDirectory(root / "none", Mode::resume, "prog", "--out"); }),
                 "holds no earlier run to continue"));
}

TEST_CASE("an output folder that cannot be made or written names the reason") {
  const auto root = test_io::output_dir("run_directory_bad");
  std::ofstream(root / "file") << "x";
  CHECK(error_of([&] { io::RunDirectory(root / "file", Mode::fresh, "prog", "--out"); }) ==
        "--out: output folder '" + (root / "file").string() + "' is a file, not a folder");
  CHECK(contains(
      error_of([&] { io::RunDirectory(root / "file" / "sub", Mode::fresh, "p", "--out"); }),
      "cannot create it (Not a directory)"));
  CHECK(contains(
      error_of([&] { io::RunDirectory(root / std::string(300, 'x'), Mode::fresh, "p", "--out"); }),
      "cannot create it (File name too long)"));
  if (std::filesystem::exists("/proc/version")) {
    // A folder the process cannot write into (procfs refuses new files even to root).
    CHECK(contains(error_of([&] { io::RunDirectory("/proc", Mode::fresh, "p", "--out"); }),
                   "cannot write into it"));
  }
}

TEST_CASE("SIGINT and SIGTERM become a stop request with the signal's name and exit status") {
  {
    io::StopRequest stop;
    CHECK_FALSE(stop.requested());
    std::raise(SIGTERM);
    CHECK(stop.requested());
    CHECK(stop.signal_name() == std::string("SIGTERM"));
    CHECK(stop.exit_status() == 128 + SIGTERM);
  }
  io::StopRequest stop;
  CHECK_FALSE(stop.requested());  // a new request starts clear
  std::raise(SIGINT);
  CHECK(stop.signal_name() == std::string("SIGINT"));
}
