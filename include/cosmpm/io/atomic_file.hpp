#pragma once
// Write-then-rename: every output file is written under a temporary name next to its final
// name and renamed into place only when complete, so a crash never leaves a half-written file
// under the final name (rename within one directory is atomic on POSIX file systems).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "cosmpm/core/error.hpp"

#if __has_include(<unistd.h>)
#include <fcntl.h>
#include <unistd.h>
#define COSMPM_IO_HAVE_POSIX 1
#else
#define COSMPM_IO_HAVE_POSIX 0
#endif

namespace cosmpm::io {

namespace detail {
inline long process_id() {
#if COSMPM_IO_HAVE_POSIX
  return static_cast<long>(::getpid());
#else
  return 0;
#endif
}

// Pushes the file's data to the disk before the rename, so the renamed file is complete even
// after a power loss. Best effort: a failing fsync is reported, a missing one is not.
inline void sync_file(const std::filesystem::path& path) {
#if COSMPM_IO_HAVE_POSIX
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  const int status = ::fsync(fd);
  ::close(fd);
  if (status != 0) {
    throw Error("io: cannot flush '" + path.string() + "' to disk (fsync failed)");
  }
#else
  (void)path;
#endif
}
}  // namespace detail

// Writes `size` bytes to `path` (created or truncated) and closes it, checking every call;
// the Error names the file and the operating system's reason (e.g. "No space left on
// device"). Without POSIX calls, a checked std::ofstream does the same with a vaguer reason.
inline void write_bytes(const std::filesystem::path& path, const char* data, std::size_t size) {
#if COSMPM_IO_HAVE_POSIX
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    throw Error("io: cannot open '" + path.string() + "' for writing (" + std::strerror(errno) +
                ")");
  }
  std::size_t written = 0;
  while (written < size) {
    const auto n = ::write(fd, data + written, size - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = n < 0 ? std::strerror(errno) : "nothing written";
      ::close(fd);
      throw Error("io: writing '" + path.string() + "' failed after " + std::to_string(written) +
                  " of " + std::to_string(size) + " bytes (" + reason + ")");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    throw Error("io: closing '" + path.string() + "' failed (" + std::strerror(errno) + ")");
  }
#else
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error("io: cannot open '" + path.string() + "' for writing");
  out.write(data, static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw Error("io: writing '" + path.string() + "' failed (disk full?)");
#endif
}

// The temporary name used while `final_path` is being written: same directory, so the
// rename stays within one file system; the process id keeps two writers apart.
inline std::filesystem::path temporary_path(const std::filesystem::path& final_path) {
  std::filesystem::path tmp = final_path;
  tmp += ".tmp" + std::to_string(detail::process_id());
  return tmp;
}

// Creates `directory` (and its parents) if missing; `where` names the caller.
inline void create_directories(const std::filesystem::path& directory, std::string_view where) {
  if (directory.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    throw Error(std::string(where) + ": cannot create the output directory '" + directory.string() +
                "'" + (error ? " (" + error.message() + ")" : ""));
  }
}

// Owns the temporary file of one write: commit() syncs and renames it to the final name; if
// commit() is never reached (an exception), the destructor removes the temporary file.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path final_path)
      : final_(std::move(final_path)), temporary_(temporary_path(final_)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (committed_) return;
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }

  const std::filesystem::path& path() const { return temporary_; }
  const std::filesystem::path& final_path() const { return final_; }

  void commit() {
    detail::sync_file(temporary_);
    std::error_code error;
    std::filesystem::rename(temporary_, final_, error);
    if (error) {
      throw Error("io: cannot rename '" + temporary_.string() + "' to '" + final_.string() + "' (" +
                  error.message() + ")");
    }
    committed_ = true;
  }

 private:
  std::filesystem::path final_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

// Writes `content` to `path` through a temporary file and a rename.
inline void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  TemporaryFile file(path);
  write_bytes(file.path(), content.data(), content.size());
  file.commit();
}

}  // namespace cosmpm::io
