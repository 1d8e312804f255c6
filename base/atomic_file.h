#pragma once
// Output files are written to a temporary name beside the target and renamed into place, so an
// interrupted or failed run never leaves a half-written file (DESIGN.md, "Conventions").
//
// Every byte goes through write(2) here, each return checked, then fsync(2) and a checked close(2),
// before the rename: a full disk or a quota must end the run with an error, not with a truncated
// file under the real name. (OpenImageIO's PNG writer does not report a failed write, so images
// are encoded to memory and written here: textures/image.h.) A failure of the machine rather than
// the input is Error::Kind::environment (exit 1); a target that is a folder is bad input (exit 2).
//
// Several outputs that belong together (a render's EXR and PNG) are staged first and renamed only
// when every one of them is complete (StagedFiles): a failure while writing any leaves none of the
// new files. The renames themselves are checked beforehand as far as they can be (the targets are
// files in folders we have just written into); rename(2) within a folder fails after that only on
// an I/O error.
//
// A process killed outright (SIGKILL, a power cut) runs none of this: each target is then its previous
// content or the new one, whole, because rename(2) replaces it atomically (POSIX.1-2017, rename()),
// and the temporary stays behind until the next run that writes the same output removes it (its name
// carries the process id, and a temporary whose process is gone is stale). A set's renames are one
// system call each: a kill in the microseconds between two of them is the one case that leaves a set
// mixed.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "base/error.h"
#include "base/temp_file_registry.h"

namespace svbrdf {

// errno's text, thread-safe (std::strerror is not).
inline std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

// Whether an errno of creating a file says the path is wrong (the user's to fix: exit 2) rather
// than the machine refusing (permissions, a read-only or full file system: exit 1).
inline bool path_errno(int error) {
  return error == ENOENT || error == ENOTDIR || error == EISDIR || error == ENAMETOOLONG || error == ELOOP;
}

inline Error creation_error(const std::string& where, const std::string& what, int error) {
  return path_errno(error) ? input_error(where, what + ": " + errno_text(error))
                           : environment_error(where, what + ": " + errno_text(error));
}

// The file beside `path` that this process owns under `tag`: ".STEM" TAG "PID.EXT". The temporary a
// writer renames into place has the tag ".tmp" (temp_path_for); it keeps the target's extension, so
// writers that choose a format by extension (OpenImageIO) see the right one; the process id lets the
// next run tell a stale one of a killed run from one in use now (is_stale_temp_of).
inline std::filesystem::path process_path_for(const std::filesystem::path& path, const char* tag) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "." + std::string.
  std::string name = ".";
  name += path.stem().string();
  name += tag;
  name += std::to_string(::getpid());
  name += path.extension().string();
  return dir / name;
}
inline std::filesystem::path temp_path_for(const std::filesystem::path& path) { return process_path_for(path, ".tmp"); }

// Whether `name` is ".STEM" TAG "PID.EXT" for `path` (process_path_for's pattern; the tag ".tmp" by
// default) with PID a process that no longer exists. A PID that exists may be an unrelated process
// that reused it; such a file is left alone rather than risk removing a file another run is using.
inline bool is_stale_temp_of(const std::string& name, const std::filesystem::path& path, const char* tag = ".tmp") {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "." + std::string.
  std::string prefix = ".";
  prefix += path.stem().string();
  prefix += tag;
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

// Throws the error for a target that cannot take a file: an existing folder (bad input), or
// something other than a regular file (a device: renaming onto /dev/null would replace the node).
inline void check_file_target(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;  // absent: fine; a symlink is replaced, not followed
  if (S_ISDIR(st.st_mode))
    throw input_error(path.string(), "is a folder; the output must be a file name inside it");
  if (!S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
    throw input_error(path.string(), "exists and is not a regular file; refusing to replace it");
}

// Flushes `file` to the disk: a write error that the kernel reports only at writeback (NFS, some
// quotas) surfaces here rather than after the rename.
inline void sync_file(const std::filesystem::path& file, const std::string& where) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw environment_error(where, "cannot reopen the written file to sync it: " + errno_text(errno));
  const int synced = ::fsync(fd);
  const int error = errno;
  if (::close(fd) != 0 && synced == 0) throw environment_error(where, "cannot close the written file: " + errno_text(errno));
  if (synced != 0 && error != EINVAL && error != EROFS)  // EINVAL/EROFS: a file system without sync
    throw environment_error(where, "cannot write the file to disk: " + errno_text(error));
}

// Writes `bytes` as the whole content of `file` (created or truncated): every write(2) checked, then
// fsync and close checked. `where` names the output in the message ("out/render.png").
inline void write_file_durably(const std::filesystem::path& file, std::span<const std::byte> bytes,
                               const std::string& where) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw creation_error(where, "cannot create the file", errno);
  const auto fail = [&](const std::string& what, int error) {
    ::close(fd);
    return environment_error(where, what + ": " + errno_text(error));
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw fail("cannot write the file (" + std::to_string(done) + " of " + std::to_string(bytes.size()) + " bytes written)", errno);
    if (n == 0) throw fail("cannot write the file (the disk took no more bytes)", ENOSPC);
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) throw fail("cannot write the file to disk", errno);
  if (::close(fd) != 0) throw environment_error(where, "cannot close the file: " + errno_text(errno));
}

// Renames the finished temporary onto `path`.
inline void move_into_place(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  check_file_target(path);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int error = errno;
    if (error == EISDIR) throw input_error(path.string(), "is a folder; the output must be a file name inside it");
    throw environment_error(path.string(), "cannot move the finished file into place: " + errno_text(error));
  }
}

// A set of outputs written together: each is written to its temporary by stage(), and commit()
// renames them all. Until commit() the targets are untouched; a set destroyed uncommitted (an
// exception while staging a later file) removes its temporaries.
class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles() { discard(); }

  // Writes `bytes` to the temporary of `path`.
  void stage(const std::filesystem::path& path, std::span<const std::byte> bytes) {
    add(path, [&](const std::filesystem::path& tmp) { write_file_durably(tmp, bytes, path.string()); });
  }

  // Lets `write` write the temporary itself (a library that writes files by name), then syncs it.
  void stage_with(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
    add(path, [&](const std::filesystem::path& tmp) {
      write(tmp);
      sync_file(tmp, path.string());
    });
  }

  // Renames every staged file into place, in the order staged.
  void commit() {
    for (const Staged& f : files_) check_file_target(f.path);
    for (Staged& f : files_) {
      move_into_place(f.tmp, f.path);
      f.registration.reset();
      f.committed = true;
    }
    files_.clear();
  }

  // Removes the temporaries not yet renamed.
  void discard() noexcept {
    for (const Staged& f : files_) {
      if (f.committed) continue;
      std::error_code ec;
      std::filesystem::remove(f.tmp, ec);
    }
    files_.clear();
  }

 private:
  void add(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
    check_file_target(path);
    // Every program's outputs come through here, so this is where the temporaries of an earlier run
    // of any of them that was killed (SIGKILL, a power cut: nothing of it ran to remove them) go.
    remove_stale_temp_files(path);
    const std::filesystem::path tmp = temp_path_for(path);
    // Registered before it exists: a signal from here on removes it (base/interrupt.h).
    files_.push_back({path, tmp, std::make_unique<RegisteredTempFile>(tmp)});
    write(tmp);
  }

  struct Staged {
    std::filesystem::path path, tmp;
    std::unique_ptr<RegisteredTempFile> registration;
    bool committed = false;
  };
  std::vector<Staged> files_;
};

// Calls write(temporary_path) and renames the temporary onto `path` when it returns; removes the
// temporary when it throws.
inline void write_atomically(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path&)>& write) {
  StagedFiles files;
  files.stage_with(path, write);
  files.commit();
}

// `bytes` as the content of `path`, atomically.
inline void write_bytes_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  StagedFiles files;
  files.stage(path, bytes);
  files.commit();
}

}  // namespace svbrdf
