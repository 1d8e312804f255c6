#include "base/setup_progress.h"

#include <fcntl.h>
#include <cerrno>
#include <unistd.h>

namespace svbrdf {

namespace {

constexpr auto kQuietFor = std::chrono::seconds(1);            // a stage this short says nothing
constexpr auto kTerminalEvery = std::chrono::milliseconds(500);
constexpr auto kLogEvery = std::chrono::seconds(10);

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

SetupProgress::SetupProgress(std::string program, bool quiet, std::FILE* out)
    : program_(std::move(program)), quiet_(quiet), tty_(::isatty(::fileno(out)) != 0), out_(out) {
  if (!quiet_) fd_ = ::fcntl(::fileno(out), F_DUPFD_CLOEXEC, 3);
  if (!quiet_) watcher_ = std::thread([this] { watch(); });
}

SetupProgress::~SetupProgress() {
  end();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (watcher_.joinable()) watcher_.join();
  if (fd_ >= 0) ::close(fd_);
}

void SetupProgress::begin(const std::string& activity, std::size_t total) {
  end();
  const std::lock_guard<std::mutex> lock(mutex_);
  activity_ = activity;
  total_ = total;
  done_.store(0, std::memory_order_relaxed);
  start_ = Clock::now();
  printed_ = false;
  running_ = true;
  wake_.notify_all();
}

void SetupProgress::end() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!running_) return;
  if (printed_ && !quiet_) print_locked(true);
  running_ = false;
}

void SetupProgress::print_locked(bool final) {
  const double s = seconds(Clock::now() - start_);
  const std::size_t done = done_.load(std::memory_order_relaxed);
  std::string count;
  if (total_ > 0) count = ", " + std::to_string(final ? total_ : std::min(done, total_)) + "/" + std::to_string(total_);
  char time[32];
  std::snprintf(time, sizeof time, final ? "done in %.1f s" : "%.0f s", s);
  std::string line;
  if (tty_) {
    line = "\r" + program_ + ": " + activity_ + count + ", " + time + "\x1b[K" + (final ? "\n" : "");
    drawn_ = !final;
  } else {
    line = program_ + ": " + activity_ + count + ", " + time + "\n";
  }
  std::fflush(out_);  // what the program wrote through out_ before comes first
  if (fd_ < 0) {
    std::fputs(line.c_str(), out_);
    std::fflush(out_);
  } else {
    for (std::size_t at = 0; at < line.size();) {
      const ssize_t n = ::write(fd_, line.data() + at, line.size() - at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // a progress line that cannot be written is not worth failing the run for
      at += std::size_t(n);
    }
  }
  printed_ = true;
  last_line_ = Clock::now();
}

void SetupProgress::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (!running_) {
      wake_.wait(lock, [&] { return stop_ || running_; });
      continue;
    }
    const Clock::time_point due = printed_ ? last_line_ + (tty_ ? kTerminalEvery : kLogEvery) : start_ + kQuietFor;
    const Clock::time_point started = start_;
    if (wake_.wait_until(lock, due, [&] { return stop_ || !running_ || start_ != started; })) continue;
    print_locked(false);
  }
}

}  // namespace svbrdf
