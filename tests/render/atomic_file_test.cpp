// base/atomic_file.h, base/output_location.h and base/temp_file_registry.h: outputs appear whole or
// not at all, a failed write is the environment's error, and temporaries are found again.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/output_location.h"
#include "base/temp_file_registry.h"
#include "tests/common/run_command.h"
#include "tests/common/spawn.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

std::vector<std::byte> bytes_of(const std::string& s) {
  std::vector<std::byte> b(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) b[i] = std::byte(static_cast<unsigned char>(s[i]));
  return b;
}

int temp_count(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

TEST(AtomicFile, AStagedSetIsRenamedWholeOrNotAtAll) {
  testing::TempDir dir;
  const fs::path a = dir / "a.exr", b = dir / "a.png";
  write_bytes_atomically(a, bytes_of("old a"));
  write_bytes_atomically(b, bytes_of("old b"));
  {
    StagedFiles files;
    files.stage(a, bytes_of("new a"));
    EXPECT_THROW(files.stage_with(b, [](const fs::path&) { throw Error("the encoder failed", Error::Kind::internal); }), Error);
  }
  EXPECT_EQ(testing::slurp(a), "old a");
  EXPECT_EQ(testing::slurp(b), "old b");
  EXPECT_EQ(temp_count(dir.path()), 0);
  StagedFiles files;
  files.stage(a, bytes_of("new a"));
  files.stage(b, bytes_of("new b"));
  EXPECT_EQ(testing::slurp(a), "old a") << "nothing is replaced before commit";
  files.commit();
  EXPECT_EQ(testing::slurp(a), "new a");
  EXPECT_EQ(testing::slurp(b), "new b");
  EXPECT_EQ(temp_count(dir.path()), 0);
}

// A file-size limit makes write(2) fail with EFBIG, as a full disk makes it fail with ENOSPC.
TEST(AtomicFile, AFailedWriteIsAnEnvironmentErrorAndLeavesNoFile) {
  testing::TempDir dir;
  const fs::path target = dir / "big.bin";
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGXFSZ, &ignore, &previous);
  rlimit small = old;
  small.rlim_cur = 1000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  Error::Kind kind = Error::Kind::bad_input;
  std::string message;
  try {
    write_bytes_atomically(target, std::vector<std::byte>(4096, std::byte{7}));
  } catch (const Error& e) {
    threw = true;
    kind = e.kind();
    message = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  ::sigaction(SIGXFSZ, &previous, nullptr);
  ASSERT_TRUE(threw);
  EXPECT_EQ(kind, Error::Kind::environment);
  EXPECT_EQ(Error("x", kind).exit_code(), 1);
  EXPECT_NE(message.find("big.bin"), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(target));
  EXPECT_EQ(temp_count(dir.path()), 0);
}

TEST(AtomicFile, AFolderOrADeviceAsTheTargetIsBadInput) {
  testing::TempDir dir;
  fs::create_directories(dir / "d.exr");
  for (const fs::path& target : {dir / "d.exr", fs::path("/dev/null")}) {
    try {
      write_bytes_atomically(target, bytes_of("x"));
      ADD_FAILURE() << target << " was written";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::bad_input) << e.what();
      EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_directory(dir / "d.exr"));
  EXPECT_EQ(temp_count(dir.path()), 0);
}

TEST(OutputLocation, MissingFoldersAreMadeAndWrongPathsRefused) {
  testing::TempDir dir;
  EXPECT_NO_THROW(check_output_location(dir / "a" / "b" / "o.exr"));
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  EXPECT_EQ(temp_count(dir / "a" / "b"), 0) << "the probe is removed";
  std::ofstream(dir / "file") << "x";
  try {
    check_output_location(dir / "file" / "o.exr");
    ADD_FAILURE() << "a file taken for a folder";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::bad_input) << e.what();
  }
}

TEST(OutputLocation, StaleTemporariesAreThoseOfProcessesThatAreGone) {
  const std::string dead = std::to_string(testing::dead_pid()), alive = std::to_string(::getpid()),
                    parent = std::to_string(::getppid());
  const fs::path out = "dir/render.exr";
  EXPECT_TRUE(is_stale_temp_of(".render.tmp" + dead + ".exr", out));
  EXPECT_FALSE(is_stale_temp_of(".render.tmp" + alive + ".exr", out)) << "this process's own";
  EXPECT_FALSE(is_stale_temp_of(".render.tmp" + parent + ".exr", out)) << "a live process's";
  EXPECT_FALSE(is_stale_temp_of(".render.tmp" + dead + ".png", out)) << "another output's";
  EXPECT_FALSE(is_stale_temp_of(".other.tmp" + dead + ".exr", out));
  EXPECT_FALSE(is_stale_temp_of(".render.tmp.exr", out));
  EXPECT_FALSE(is_stale_temp_of(".render.tmp12x4.exr", out));
  EXPECT_FALSE(is_stale_temp_of("render.exr", out));
}

// What a signal handler calls before _exit (base/interrupt.h).
TEST(TempFileRegistry, RegisteredFilesAreRemovedUnregisteredKept) {
  testing::TempDir dir;
  std::ofstream(dir / "a") << "a";
  std::ofstream(dir / "b") << "b";
  const int a = register_temp_file(dir / "a");
  ASSERT_GE(a, 0);
  {
    RegisteredTempFile b(dir / "b");
  }
  remove_registered_temp_files();
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_TRUE(fs::exists(dir / "b"));
  unregister_temp_file(a);
}

}  // namespace
}  // namespace svbrdf
