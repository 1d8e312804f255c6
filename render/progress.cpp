#include "render/progress.h"

#include <algorithm>
#include <string>
#include <unistd.h>

namespace svbrdf {

namespace {
std::string clock_text(double s) {
  if (!(s >= 0.0) || s > 359999.0) return "--:--";
  const long t = long(s + 0.5);
  char buf[32];
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%02ld:%02ld", t / 60, t % 60);
  return buf;
}
}  // namespace

ProgressPrinter::ProgressPrinter(bool quiet, std::FILE* out)
    : out_(out), quiet_(quiet), tty_(::isatty(::fileno(out)) != 0) {}

void ProgressPrinter::update(const ProgressInfo& p) {
  if (quiet_ || p.samples_total == 0) return;
  const double frac = double(p.samples_done) / double(p.samples_total);
  const double eta = frac > 0.0 ? p.seconds * (1.0 - frac) / frac : -1.0;
  const double mrays = p.seconds > 0.0 ? double(p.rays) / p.seconds * 1e-6 : 0.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = std::clamp(int(frac * kWidth), 0, kWidth);
    std::fprintf(out_, "\r[%s%s] %3d%%  %s elapsed  ETA %s  %.2f Mrays/s ", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), int(frac * 100.0), clock_text(p.seconds).c_str(),
                 clock_text(eta).c_str(), mrays);
    std::fflush(out_);
    drew_ = true;
  } else if (last_line_ < 0.0 || p.seconds - last_line_ >= 10.0) {
    last_line_ = p.seconds;
    std::fprintf(out_, "svbrdf-render: %d%% after %s, ETA %s, %.2f Mrays/s\n", int(frac * 100.0),
                 clock_text(p.seconds).c_str(), clock_text(eta).c_str(), mrays);
    std::fflush(out_);
  }
}

void ProgressPrinter::finish(const ProgressInfo& p) {
  if (quiet_) return;
  if (drew_) std::fputc('\n', out_);
  const double mrays = p.seconds > 0.0 ? double(p.rays) / p.seconds * 1e-6 : 0.0;
  std::fprintf(out_, "svbrdf-render: %llu samples, %llu rays in %.2f s (%.2f Mrays/s)\n",
               static_cast<unsigned long long>(p.samples_done), static_cast<unsigned long long>(p.rays), p.seconds,
               mrays);
}

}  // namespace svbrdf
