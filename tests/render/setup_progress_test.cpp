// The set-up's progress lines (base/setup_progress.h): a stage longer than a second says what it is
// doing while it runs and how long it took; a short one, or a quiet reporter, says nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "base/setup_progress.h"

namespace svbrdf {
namespace {

std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) s += buf;
  return s;
}

TEST(SetupProgress, LongStagesSayWhatAndHowLongShortOnesNothing) {
  std::FILE* f = std::tmpfile();  // not a terminal: plain lines
  ASSERT_NE(f, nullptr);
  {
    SetupProgress p("prog", false, f);
    {
      const SetupProgress::Stage s(&p, "quick work");
    }
    {
      const SetupProgress::Stage s(&p, "slow work", 3);
      p.step();
      // Well past the one second after which a stage speaks, so a busy machine still sees the line.
      std::this_thread::sleep_for(std::chrono::milliseconds(2500));
      p.step(2);
    }
  }
  const std::string out = contents(f);
  std::fclose(f);
  EXPECT_EQ(out.find("quick work"), std::string::npos) << out;
  // One line while it ran (after a second, one of three steps done) and one when it ended.
  EXPECT_NE(out.find("prog: slow work, 1/3, "), std::string::npos) << out;
  EXPECT_NE(out.find("prog: slow work, 3/3, done in 2."), std::string::npos) << out;
}

TEST(SetupProgress, QuietSaysNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    SetupProgress p("prog", true, f);
    const SetupProgress::Stage s(&p, "slow work");
    std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  }
  EXPECT_EQ(contents(f), "");
  std::fclose(f);
}

}  // namespace
}  // namespace svbrdf
