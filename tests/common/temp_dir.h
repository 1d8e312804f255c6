#pragma once
// A fresh directory per test under the system temp dir, named after the process and the test, removed
// when the test ends. One header for every module's tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace svbrdf::testing {

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string suite = info ? std::string(info->test_suite_name()) : "x";
    const std::string name = info ? std::string(info->name()) : "x";
    std::string stem = "svbrdf_" + std::to_string(::getpid()) + "_" + suite + "_" + name;
    for (char& c : stem)  // parameterized tests have '/' in their names
      if (c == '/') c = '_';
    path_ = std::filesystem::temp_directory_path() / stem;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace svbrdf::testing
