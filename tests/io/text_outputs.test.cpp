// CSV time series and the progress line: exact text, checked against hand-written
// expectations.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/xdmf.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Everything written to a FILE*, read back.
std::string file_text(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  char buffer[512];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, n);
  return text;
}
}  // namespace

TEST_CASE("CSV rows are complete on disk after each row, in shortest round-trip text") {
  const auto dir = test_io::output_dir("csv");
  const auto path = dir / "forces.csv";
  io::CsvWriter csv(path, {"time", "draft_force", "step"});
  CHECK(read_text(path) == "time,draft_force,step\n");
  csv.write_row({0.0, -12.5, 0.0});
  // Read while the writer is still open: the row is already there (flushed).
  CHECK(read_text(path) == "time,draft_force,step\n0,-12.5,0\n");
  // 0.1 + 0.2 = 0.30000000000000004 needs 17 digits to read back; 1e-300 and 12345 are exact.
  csv.write_row({0.1 + 0.2, 1e-300, 12345.0});
  const std::string text = read_text(path);
  CHECK(text == "time,draft_force,step\n0,-12.5,0\n0.30000000000000004,1e-300,12345\n");
  CHECK(std::stod("0.30000000000000004") == 0.1 + 0.2);
  // A row of the wrong width is refused, naming the file and both counts.
  try {
    csv.write_row({1.0, 2.0});
    FAIL("no error");
  } catch (const Error& error) {
    const std::string message = error.what();
    CHECK(message.find("forces.csv") != std::string::npos);
    CHECK(message.find("2 values but the file has 3 columns") != std::string::npos);
  }
  CHECK_THROWS_AS(io::CsvWriter(dir / "bad.csv", {"a,b"}), Error);
  CHECK_THROWS_AS(io::CsvWriter(dir / "none.csv", {}), Error);
}

TEST_CASE("CSV resume keeps the rows up to the restart time and appends after them") {
  const auto dir = test_io::output_dir("csv_resume");
  const auto path = dir / "series.csv";
  {
    io::CsvWriter csv(path, {"time", "value"});
    for (int i = 0; i < 5; ++i) csv.write_row({0.5 * i, 10.0 * i});
  }
  {
    // Restart at t = 1.0: rows at 0, 0.5, 1.0 stay, 1.5 and 2.0 go.
    auto csv = io::CsvWriter::resume(path, {"time", "value"}, 1.0);
    csv.write_row({1.25, -1.0});
  }
  CHECK(read_text(path) == "time,value\n0,0\n0.5,10\n1,20\n1.25,-1\n");
  // Another header is refused.
  CHECK_THROWS_AS(io::CsvWriter::resume(path, {"time", "other"}, 1.0), Error);
}

TEST_CASE("progress line format") {
  using io::ProgressReporter;
  // The example line.
  CHECK(ProgressReporter::format_line("flat_blade", 0.452, 1.234, 3.5, 12345, 3.1e6, 42.0) ==
        "[flat_blade] 45.2% t=1.234/3.500 s step 12345 | 3.1e6 particle-steps/s | ETA 0:42");
  CHECK(ProgressReporter::format_rate(3.14159e6) == "3.1e6");
  CHECK(ProgressReporter::format_rate(9.96e5) == "1.0e6");  // rounds up into the next decade
  CHECK(ProgressReporter::format_rate(250.0) == "2.5e2");
  CHECK(ProgressReporter::format_duration(59.4) == "0:59");
  CHECK(ProgressReporter::format_duration(3725.0) == "1:02:05");  // 1 h 2 min 5 s
  CHECK(ProgressReporter::format_duration(-1.0) == "--");
}

TEST_CASE("progress on a non-terminal prints a plain line every 10 percent") {
  std::FILE* out = std::tmpfile();
  REQUIRE(out != nullptr);
  using Clock = io::ProgressReporter::Clock;
  io::ProgressReporter progress("run", 1.0, 100, out, io::ProgressReporter::Style::plain);
  const Clock::time_point start{};
  // 100 steps of 0.01 s, one wall-clock second each: 100 particle-steps/s.
  for (int step = 0; step <= 100; ++step) {
    progress.report(0.01 * step, step, start + std::chrono::seconds(step), false);
  }
  progress.report(1.0, 100, start + std::chrono::seconds(100), true);
  const std::string text = file_text(out);
  std::fclose(out);
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  // 10 %, 20 %, ..., 100 %; the final report repeats the 100 % step, so it prints nothing;
  // no carriage returns.
  REQUIRE(lines.size() == 10);
  CHECK(text.find('\r') == std::string::npos);
  CHECK(lines[0].rfind("[run] 10.0% t=0.100/1.000 s step 10 | 1.0e2 particle-steps/s", 0) == 0);
  // At 10 % after 10 s, 90 % remains: ETA 90 s.
  CHECK(lines[0].find("ETA 1:30") != std::string::npos);
  CHECK(lines[9].rfind("[run] 100.0%", 0) == 0);
}

TEST_CASE("progress in a log prints the final line once when the last update reached it") {
  std::FILE* out = std::tmpfile();
  REQUIRE(out != nullptr);
  using Clock = io::ProgressReporter::Clock;
  io::ProgressReporter progress("run", 1.0, 100, out, io::ProgressReporter::Style::plain);
  const Clock::time_point start{};
  for (int step = 1; step <= 10; ++step) {
    progress.report(0.1 * step, step, start + std::chrono::seconds(step), false);
  }
  // The update at step 10 printed 100 %; finishing at the same step adds nothing.
  progress.report(1.0, 10, start + std::chrono::seconds(10), true);
  const std::string text = file_text(out);
  std::fclose(out);
  std::size_t lines = 0;
  std::size_t full = 0;
  for (std::size_t at = 0; (at = text.find('\n', at)) != std::string::npos; ++at) ++lines;
  for (std::size_t at = 0; (at = text.find("100.0%", at)) != std::string::npos; ++at) ++full;
  CHECK(lines == 10);
  CHECK(full == 1);
}

TEST_CASE("progress on a terminal redraws in place at most twice a second") {
  std::FILE* out = std::tmpfile();
  REQUIRE(out != nullptr);
  using Clock = io::ProgressReporter::Clock;
  io::ProgressReporter progress("run", 1.0, 10, out, io::ProgressReporter::Style::terminal);
  const Clock::time_point start{};
  // 1000 updates over 2 s of wall clock: the first, then one per 0.5 s -> 5 redraws.
  for (int i = 0; i < 1000; ++i) {
    progress.report(0.001 * i, i, start + std::chrono::milliseconds(2 * i), false);
  }
  progress.report(1.0, 1000, start + std::chrono::milliseconds(2000), true);
  const std::string text = file_text(out);
  std::fclose(out);
  std::size_t redraws = 0;
  for (const char c : text) redraws += c == '\r' ? 1 : 0;
  CHECK(redraws == 4 + 1);  // at 0, 0.5, 1.0, 1.5 s, then the final one
  CHECK(text.back() == '\n');
  CHECK(text.find('\n') == text.size() - 1);  // only the final report ends the line
}

TEST_CASE("XDMF text escapes names and lists frames with exact times") {
  io::XdmfFrame frame;
  frame.file = "a&b_000000.h5";
  frame.time = 0.1;
  io::XdmfMesh mesh;
  mesh.name = "particles";
  mesh.points = 2;
  mesh.geometry_dataset = "/position3";
  frame.meshes.push_back(mesh);
  const std::string xml = io::render_xdmf({frame});
  CHECK(xml.find("a&amp;b_000000.h5:/position3") != std::string::npos);
  CHECK(xml.find("<Time Value=\"0.1\"/>") != std::string::npos);
}
