#include "common/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace powderbed::app {

ProgressBar::ProgressBar(std::string app, double batch_interval)
    : app_(std::move(app)),
      interval_(batch_interval),
      terminal_(::isatty(STDERR_FILENO) != 0),
      next_line_(batch_interval) {}

double ProgressBar::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::draw(double fraction, const std::string& detail) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double t = elapsed();
  const double eta = fraction > 0 ? t * (1 - fraction) / fraction : 0;
  const int percent = static_cast<int>(100 * fraction);
  if (!terminal_) {
    if (interval_ <= 0 || t < next_line_) return;
    next_line_ = t + interval_;
    std::fprintf(stderr, "%s: %3d %%  %s  elapsed %.0f s  ETA %.0f s\n", app_.c_str(), percent,
                 detail.c_str(), t, eta);
    return;
  }
  const int filled = static_cast<int>(30 * fraction);
  std::fprintf(stderr, "\r[%s%s] %3d %%  %s  ETA %.0f s ",
               std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(30 - filled), '.').c_str(), percent,
               detail.c_str(), eta);
  open_line_ = fraction < 1;
  if (!open_line_) std::fputc('\n', stderr);
}

void ProgressBar::finish() {
  if (open_line_) std::fputc('\n', stderr);
  open_line_ = false;
}

}  // namespace powderbed::app
