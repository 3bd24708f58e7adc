#pragma once
// Progress of long runs on stderr (README "The programs"). On a terminal a bar with an ETA,
// redrawn in place: "[#####.....]  45 %  <detail>  ETA 12 s". In a batch run (stderr not a
// terminal: a cluster job, a pipe, a log file) one line every --progress seconds instead,
// "<app>: 45 %  <detail>  elapsed 20 s  ETA 24 s", so a log shows the run is alive.
#include <chrono>
#include <string>

namespace powderbed::app {

class ProgressBar {
 public:
  // `batch_interval` (s): the time between two lines in a batch run; 0 = no lines.
  ProgressBar(std::string app, double batch_interval);

  // Reports `fraction` (0..1) done with the program's own `detail`; the ETA extrapolates the
  // wall time since construction. On a terminal a newline follows once the fraction reaches 1.
  void draw(double fraction, const std::string& detail);
  // Ends the bar's line on a terminal when the run stopped before reaching 1.
  void finish();

 private:
  double elapsed() const;

  std::string app_;
  double interval_;
  bool terminal_;
  bool open_line_ = false;  // a bar is drawn on the terminal without its newline
  double next_line_;        // elapsed time of the next batch line
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace powderbed::app
