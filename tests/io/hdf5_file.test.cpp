// The HDF5 file API: a new file is assembled in memory and written in one checked write; the
// superblock checksum that HDF5 1.10 leaves stale in file images is recomputed.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/detail/superblock.hpp"
#include "cosmpm/io/hdf5_file.hpp"
#include "helpers.hpp"

using namespace cosmpm;

TEST_CASE("lookup3 gives the published test values") {
  // The self-test values of Bob Jenkins' lookup3.c (driver5).
  const auto hash = [](const char* text, std::uint32_t initial) {
    return io::detail::lookup3(reinterpret_cast<const unsigned char*>(text), std::strlen(text),
                               initial);
  };
  CHECK(hash("", 0) == 0xdeadbeefU);
  CHECK(hash("", 0xdeadbeefU) == 0xbd5b7ddeU);
  CHECK(hash("Four score and seven years ago", 0) == 0x17770551U);
  CHECK(hash("Four score and seven years ago", 1) == 0xcd628161U);
}

TEST_CASE("files in both formats are written whole and read back") {
  const auto dir = test_io::output_dir("hdf5_file");
  for (const bool checksummed : {false, true}) {
    const auto path = dir / (checksummed ? "checksummed.h5" : "plain.h5");
    {
      io::Hdf5File file = io::Hdf5File::create(path, checksummed);
      const std::vector<double> values{1.5, -0.0, 1e300};
      file.write("/values", values.data(), {3});
      file.set_attribute("time", 0.25);
      file.set_attribute("label", std::string("frame"));
      // Nothing is on disk before close(): the file is assembled in memory.
      CHECK_FALSE(std::filesystem::exists(path));
      file.close();
    }
    CHECK(std::filesystem::exists(path));
    const io::Hdf5File file = io::Hdf5File::open_read(path);
    std::vector<double> back(3);
    file.read("/values", back.data(), {3}, true);
    CHECK(back == std::vector<double>{1.5, -0.0, 1e300});
    CHECK(file.attribute<double>("time") == 0.25);
    CHECK(file.string_attribute("label") == "frame");
    // The checksummed format has a version 3 superblock (with its checksum), the plain one
    // version 0.
    CHECK(test_io::read_raw(path, "/values").ok);
  }
  // A path that cannot be written names the file and the reason.
  std::string message;
  try {
    io::Hdf5File file = io::Hdf5File::create(dir / "missing" / "dir" / "x.h5");
    file.close();
  } catch (const Error& error) {
    message = error.what();
  }
  CHECK(message.find("x.h5") != std::string::npos);
  CHECK(message.find("No such file or directory") != std::string::npos);
}
