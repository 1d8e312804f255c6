#pragma once
// Progress of the stages before a program's main work (reading a scene and decoding its images,
// building MIP maps): a stage that lasts more than a second says so on stderr while it runs — a line
// redrawn in place on a terminal, a plain line every ten seconds otherwise (logs, CI) — and how long
// it took when it ends. Stages shorter than a second print nothing, nor does a quiet reporter.
//
// A watcher thread does the printing, so a stage made of one long call (a MIP build) still shows
// that it is alive; step() may be called from any thread. It writes to a duplicate of the output's
// descriptor taken when the reporter is made: the image decoder points descriptor 2 at /dev/null
// while a PNG is decoded (textures/image.cpp), and a line printed then must not be lost with libpng's.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace svbrdf {

class SetupProgress {
 public:
  SetupProgress(std::string program, bool quiet, std::FILE* out = stderr);
  ~SetupProgress();
  SetupProgress(const SetupProgress&) = delete;
  SetupProgress& operator=(const SetupProgress&) = delete;

  // Starts a stage named as an activity ("building the brdf MIP maps"), of `total` steps counted by
  // step() (0: not counted). Ends the stage before it, if any.
  void begin(const std::string& activity, std::size_t total = 0);
  void step(std::size_t n = 1) { done_.fetch_add(n, std::memory_order_relaxed); }
  // Ends the current stage (nothing when none runs).
  void end();

  // A stage as a scope: begins on construction, ends on destruction (also when an exception leaves).
  class Stage {
   public:
    Stage(SetupProgress* p, const std::string& activity, std::size_t total = 0) : p_(p) {
      if (p_) p_->begin(activity, total);
    }
    ~Stage() {
      if (p_) p_->end();
    }
    Stage(const Stage&) = delete;
    Stage& operator=(const Stage&) = delete;

   private:
    SetupProgress* p_;
  };

 private:
  using Clock = std::chrono::steady_clock;
  void watch();
  void print_locked(bool final);  // mutex_ held

  std::string program_;
  bool quiet_, tty_;
  std::FILE* out_;
  int fd_ = -1;  // the duplicate written to; −1 where none could be made (then out_ itself)
  std::mutex mutex_;
  std::condition_variable wake_;
  bool running_ = false, stop_ = false;
  std::string activity_;
  std::size_t total_ = 0;
  std::atomic<std::size_t> done_{0};
  Clock::time_point start_{}, last_line_{};
  bool printed_ = false;  // this stage has printed a line (so its end is reported)
  bool drawn_ = false;    // a terminal line is open (no newline yet)
  std::thread watcher_;
};

}  // namespace svbrdf
