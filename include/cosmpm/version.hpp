#pragma once
// The one place the version is written; CMakeLists.txt parses these three lines.
#define COSMPM_VERSION_MAJOR 0
#define COSMPM_VERSION_MINOR 1
#define COSMPM_VERSION_PATCH 0

namespace cosmpm {
inline constexpr int version_major = COSMPM_VERSION_MAJOR;
inline constexpr int version_minor = COSMPM_VERSION_MINOR;
inline constexpr int version_patch = COSMPM_VERSION_PATCH;
}  // namespace cosmpm
