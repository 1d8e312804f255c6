#pragma once
// A folder in which no new file can be made, for the tests of outputs the machine refuses (exit 1).
// Root writes through permission bits, so for root it is sysfs, which takes no new files from anyone;
// otherwise a folder of the test's own with its write permission removed (given back at the end).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

namespace svbrdf::testing {

class ReadOnlyFolder {
 public:
  // `scratch`: a folder of the test's own, in which a non-root user's folder is made.
  explicit ReadOnlyFolder(const std::filesystem::path& scratch) {
    namespace fs = std::filesystem;
    if (::geteuid() == 0) {
      if (fs::is_directory("/sys/kernel")) path_ = "/sys/kernel";
      return;
    }
    path_ = scratch / "read-only";
    fs::create_directories(path_);
    fs::permissions(path_, fs::perms::owner_read | fs::perms::owner_exec);
    made_ = true;
  }
  ~ReadOnlyFolder() {
    std::error_code ec;
    if (made_) std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ec);
  }
  ReadOnlyFolder(const ReadOnlyFolder&) = delete;
  ReadOnlyFolder& operator=(const ReadOnlyFolder&) = delete;

  // Empty when the machine offers none (root without /sys): the test is then skipped.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  bool made_ = false;
};

}  // namespace svbrdf::testing
