#pragma once
// Progress on stderr: a bar redrawn in place when stderr is a terminal (percent, elapsed, ETA,
// Mrays/s), a plain line every ten seconds when it is not (logs, CI), nothing with --quiet.
#include <cstdio>

#include "render/renderer.h"

namespace svbrdf {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool quiet, std::FILE* out = stderr);
  void update(const ProgressInfo& info);
  // Ends the bar's line and prints the summary.
  void finish(const ProgressInfo& info);

 private:
  std::FILE* out_;
  bool quiet_, tty_;
  double last_line_ = -1.0;
  bool drew_ = false;
};

}  // namespace svbrdf
