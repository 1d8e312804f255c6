#pragma once
// Checks on where an output will go, made before the work that produces it: a render of an hour
// must not end with "cannot write" because the path names a folder or the folder is read-only.
// Every program checks the outputs it knows of before its work begins; base/atomic_file.h removes
// the temporaries a killed run left.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <system_error>

#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {

// Makes sure the folder `dir` takes new files: it exists (made if missing) and `probe` can be created
// and removed in it. Throws bad input for a path that is not a folder, Error::Kind::environment for
// a folder the machine does not let us make or write; `where` and `what` say it ("out/o.exr",
// "cannot write a file in its folder").
inline void check_folder_takes_files(const std::filesystem::path& dir, const std::filesystem::path& probe,
                                     const std::string& where, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    if (fs::exists(dir, ec)) throw input_error(dir.string(), "is not a folder, so " + where + " cannot go in it");
    fs::create_directories(dir, ec);
    if (ec) throw creation_error(dir.string(), "cannot create the output folder", ec.value());
  }
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0 && errno != EEXIST) throw creation_error(where, what, errno);
  if (fd >= 0) {
    ::close(fd);
    ::unlink(probe.c_str());
  }
}

// Makes sure a file can be written at `path` later: it is not a folder or a device, and its folder
// takes new files. The probe has the temporary's own name: the one the real write will create.
inline void check_output_location(const std::filesystem::path& path) {
  check_file_target(path);
  check_folder_takes_files(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."), temp_path_for(path),
                           path.string(), "cannot write a file in its folder");
}

// The same for an output folder whose files are named as the work goes on (a baked texture set or
// scene, a report), without making it: bad input found later in the run must leave nothing behind. A
// folder not there yet is checked by its nearest existing parent, in which it will be made.
inline void check_output_folder(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path existing = dir;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  check_folder_takes_files(existing, temp_path_for(existing / "folder-check"), dir.string(),
                           "cannot make or write the output folder");
}

}  // namespace svbrdf
