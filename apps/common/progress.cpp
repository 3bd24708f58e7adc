#include "common/progress.hpp"

#include <algorithm>
#include <cstdio>

namespace powderbed::app {

void ProgressBar::draw(double fraction, const std::string& detail) const {
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  const int filled = static_cast<int>(30 * fraction);
  std::fprintf(stderr, "\r[%s%s] %3d %%  %s  ETA %.0f s ",
               std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(30 - filled), '.').c_str(),
               static_cast<int>(100 * fraction), detail.c_str(), eta);
  if (fraction >= 1) std::fputc('\n', stderr);
}

}  // namespace powderbed::app
