#pragma once
// Checks on where an output will go, made before the work that produces it: a render of an hour
// must not end with "cannot write" because the path names a folder or the folder is read-only.
// Also removes the temporaries that a killed run left there (SIGKILL, a power cut: nothing of the
// program ran to remove them).
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <system_error>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

// Makes sure a file can be written at `path` later: it is not a folder or a device, its folder
// exists (created if missing) and a file can be created and removed there. Throws bad input for a
// wrong path, Error::Kind::environment for a folder the machine does not let us write.
inline void check_output_location(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  check_file_target(path);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    if (fs::exists(dir, ec)) throw input_error(dir.string(), "is not a folder, so " + path.filename().string() + " cannot go in it");
    fs::create_directories(dir, ec);
    if (ec) throw creation_error(dir.string(), "cannot create the output folder", ec.value());
  }
  // The probe has the temporary's own name: the one the real write will create.
  const fs::path probe = temp_path_for(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0 && errno != EEXIST) throw creation_error(path.string(), "cannot write a file in its folder", errno);
  if (fd >= 0) {
    ::close(fd);
    ::unlink(probe.c_str());
  }
}

// Whether `name` is ".STEM.tmpPID.EXT" for `path` (temp_path_for's pattern) with PID a process that
// no longer exists. A PID that exists may be an unrelated process that reused it; such a file is
// left alone rather than risk removing a file another run is writing.
inline bool is_stale_temp_of(const std::string& name, const std::filesystem::path& path) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "." + std::string.
  std::string prefix = ".";
  prefix += path.stem().string();
  prefix += ".tmp";
  const std::string suffix = path.extension().string();
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
  const long pid = std::stol(digits);
  if (pid <= 0 || pid == ::getpid()) return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Removes the stale temporaries of `path` in its folder; returns how many. Best effort: a folder
// that cannot be listed is left to the write to report.
inline int remove_stale_temp_files(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!is_stale_temp_of(it->path().filename().string(), path)) continue;
    std::error_code rm;
    if (fs::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace svbrdf
