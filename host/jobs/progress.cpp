#include "jobs/progress.h"

#include <unistd.h>

#include <cstdio>

namespace seasim {

bool stderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(int total, bool tty) : total_(total), tty_(tty), t0_(std::chrono::steady_clock::now()) {}

void Progress::drawBar(const std::string& label) {
  const int width = 30;
  const int filled = total_ > 0 ? handled_ * width / total_ : width;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "\r[%s] %d/%d %5.1fs %-40.40s", bar.c_str(), handled_, total_, elapsed, label.c_str());
  std::fflush(stderr);
}

void Progress::start(const std::string& item) {
  if (tty_) {
    drawBar(item);
  } else {
    std::fprintf(stderr, "[%d/%d] %s ...\n", handled_ + 1, total_, item.c_str());
  }
}

void Progress::finish(const std::string& item, const std::string& outcome) {
  ++handled_;
  if (tty_) {
    drawBar(item + ": " + outcome);
  } else {
    std::fprintf(stderr, "[%d/%d] %s: %s\n", handled_, total_, item.c_str(), outcome.c_str());
  }
}

void Progress::done() {
  if (tty_) std::fprintf(stderr, "\n");
}

}  // namespace seasim
