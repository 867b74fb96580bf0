#pragma once
// The output folder of one run: created and checked before the run starts, locked while it
// runs, and never mixed with another run's results.
//
//   io::RunDirectory run(out, io::RunDirectory::Mode::fresh, "example_03_flat_blade", "--out");
//   io::CsvWriter forces(run.claim("forces.csv"), {...});
//   ...
//   for (const auto& file : run.written()) std::printf("  %s\n", file.c_str());
//
// A lock file (.cosmpm-lock, holding the process id) keeps a second run out while this one
// writes; a lock left by a process that no longer runs is taken over. The manifest
// (.cosmpm-run) lists every file the run claims, before it is written. A fresh run refuses
// a folder that holds an earlier run's files (replace deletes exactly those first; resume
// continues them) or files no run wrote (never deleted). Temporary files left by a killed
// run (*.tmp<pid>) are removed.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/atomic_file.hpp"

#if COSMPM_IO_HAVE_POSIX
#include <signal.h>  // kill(pid, 0): is the process that holds the lock still running?
#endif

namespace cosmpm::io {

class RunDirectory {
 public:
  enum class Mode { fresh, replace, resume };
  static constexpr const char* lock_name = ".cosmpm-lock";
  static constexpr const char* manifest_name = ".cosmpm-run";

  // `where` names the option that chose the folder, for messages ("--out (default)").
  RunDirectory(std::filesystem::path path, Mode mode, std::string program, std::string where)
      : path_(std::move(path)), program_(std::move(program)), where_(std::move(where)) {
    create();
    lock();
    try {
      take_over(mode);
    } catch (...) {
      unlock();
      throw;
    }
  }
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;
  ~RunDirectory() { unlock(); }

  const std::filesystem::path& path() const { return path_; }

  // Lists `relative` as an output of this run (before it is written), creates the folder it
  // goes in, and returns its path.
  std::filesystem::path claim(const std::filesystem::path& relative) {
    const std::string name = relative.lexically_normal().generic_string();
    require(!relative.is_absolute() && name.rfind("..", 0) != 0,
            "RunDirectory::claim: '" + name + "' must lie inside the run folder");
    if (relative.has_parent_path()) {
      create_directories(path_ / relative.parent_path(), where_);
    }
    bool listed = false;
    for (const auto& file : files_) listed = listed || file == name;
    if (!listed) {
      files_.push_back(name);
      write_manifest();
    }
    return path_ / relative;
  }

  // The claimed files that exist now, in the order they were claimed.
  std::vector<std::filesystem::path> written() const {
    std::vector<std::filesystem::path> out;
    for (const auto& file : files_) {
      std::error_code error;
      if (std::filesystem::is_regular_file(path_ / file, error)) out.push_back(path_ / file);
    }
    return out;
  }

 private:
  std::string folder() const { return where_ + ": output folder '" + path_.string() + "'"; }

  void create() {
    std::error_code error;
    if (std::filesystem::exists(path_, error) && !std::filesystem::is_directory(path_, error)) {
      throw Error(folder() + " is a file, not a folder");
    }
    std::filesystem::create_directories(path_, error);
    if (error || !std::filesystem::is_directory(path_)) {
      throw Error(folder() + ": cannot create it (" +
                  (error ? error.message() : std::string("not a folder")) + ")");
    }
  }

  static bool process_alive(long pid) {
#if COSMPM_IO_HAVE_POSIX
    return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
#else
    (void)pid;
    return true;
#endif
  }

  void lock() {
    const std::filesystem::path lock_path = path_ / lock_name;
    for (int attempt = 0; attempt < 2; ++attempt) {
#if COSMPM_IO_HAVE_POSIX
      const int fd = ::open(lock_path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
      if (fd >= 0) {
        const std::string pid = std::to_string(detail::process_id()) + "\n";
        const bool ok = ::write(fd, pid.data(), pid.size()) == static_cast<ssize_t>(pid.size());
        ::close(fd);
        if (!ok) {
          std::filesystem::remove(lock_path);
          throw Error(folder() + ": cannot write into it (" + std::strerror(errno) + ")");
        }
        locked_ = true;
        return;
      }
      if (errno != EEXIST) {
        throw Error(folder() + ": cannot write into it (" + std::strerror(errno) + ")");
      }
#else
      if (!std::filesystem::exists(lock_path)) {
        write_file_atomically(lock_path, "0\n");
        locked_ = true;
        return;
      }
#endif
      long pid = 0;
      std::ifstream(lock_path) >> pid;
      if (process_alive(pid)) {
        throw Error(folder() + " is in use by another run (process " + std::to_string(pid) +
                    ", lock file " + lock_name +
                    "); wait for it to end or choose another folder (if no run is active, "
                    "delete the lock file)");
      }
      std::error_code ignored;
      std::filesystem::remove(lock_path, ignored);  // left by a process that ended
    }
    throw Error(folder() + ": cannot take the lock file " + std::string(lock_name));
  }

  void unlock() {
    if (!locked_) return;
    std::error_code ignored;
    std::filesystem::remove(path_ / lock_name, ignored);
    locked_ = false;
  }

  static bool is_temporary(const std::string& name) {
    const auto at = name.rfind(".tmp");
    return at != std::string::npos && at + 4 < name.size() &&
           name.find_first_not_of("0123456789", at + 4) == std::string::npos;
  }

  void take_over(Mode mode) {
    std::vector<std::string> earlier;
    std::string earlier_program;
    const bool has_manifest = read_manifest(earlier, earlier_program);
    std::vector<std::string> foreign;
    std::vector<std::string> ours;
    std::error_code error;
    for (auto it = std::filesystem::recursive_directory_iterator(path_, error);
         !error && it != std::filesystem::recursive_directory_iterator(); it.increment(error)) {
      if (!it->is_regular_file() && !it->is_symlink()) continue;
      const std::string name = std::filesystem::relative(it->path(), path_).generic_string();
      if (name == lock_name || name == manifest_name) continue;
      if (is_temporary(name)) {
        std::error_code ignored;
        std::filesystem::remove(it->path(), ignored);  // the lock says no one writes it now
        continue;
      }
      bool listed = false;
      for (const auto& file : earlier) listed = listed || file == name;
      (listed ? ours : foreign).push_back(name);
    }
    if (error) throw Error(folder() + ": cannot list it (" + error.message() + ")");
    std::sort(ours.begin(), ours.end());
    std::sort(foreign.begin(), foreign.end());
    if (mode == Mode::resume) {
      if (!has_manifest) {
        throw Error(folder() + " holds no earlier run to continue (no " +
                    std::string(manifest_name) + ")");
      }
      if (earlier_program != program_) {
        throw Error(folder() + " holds a run of " + earlier_program + ", not of " + program_);
      }
      files_ = earlier;
      return;
    }
    if (!foreign.empty()) {
      throw Error(folder() + " holds files no cosmpm run wrote (e.g. '" + foreign.front() +
                  "'); choose an empty or new folder");
    }
    if (!ours.empty() && mode == Mode::fresh) {
      throw Error(folder() + " holds the results of an earlier run (e.g. '" + ours.front() +
                  "'); choose another folder, or replace them (--replace true) or continue "
                  "that run (--restart true)");
    }
    for (const auto& name : ours) {
      std::error_code remove_error;
      std::filesystem::remove(path_ / name, remove_error);
      if (remove_error) {
        throw Error(folder() + ": cannot delete the earlier run's '" + name + "' (" +
                    remove_error.message() + ")");
      }
    }
    files_.clear();
    write_manifest();
  }

  bool read_manifest(std::vector<std::string>& files, std::string& program) const {
    std::ifstream in(path_ / manifest_name);
    if (!in) return false;
    std::string line;
    std::getline(in, line);
    const std::string prefix = "cosmpm run of ";
    program = line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : "an unknown program";
    while (std::getline(in, line)) {
      if (!line.empty()) files.push_back(line);
    }
    return true;
  }

  void write_manifest() const {
    std::string text = "cosmpm run of " + program_ + "\n";
    for (const auto& file : files_) text += file + "\n";
    write_file_atomically(path_ / manifest_name, text);
  }

  std::filesystem::path path_;
  std::string program_;
  std::string where_;
  std::vector<std::string> files_;
  bool locked_ = false;
};

}  // namespace cosmpm::io
