#pragma once
// Where tests write files. ctest passes the directory in the environment (tests/CMakeLists.txt)
// rather than as a compiled-in path, so no object file depends on where the build tree lives
// and a compiler cache can share objects between clones.
#include <cstdlib>
#include <filesystem>

namespace cosmpm::test {

inline std::filesystem::path output_root() {
  if (const char* dir = std::getenv("COSMPM_TEST_OUTPUT_DIR"); dir != nullptr && *dir != '\0') {
    return dir;
  }
  return std::filesystem::temp_directory_path() / "cosmpm_test_output";
}

}  // namespace cosmpm::test
