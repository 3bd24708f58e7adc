#pragma once
// Runs a program of the build end to end and captures its exit status, stdout and stderr.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace powderbed::test {

struct CommandResult {
  int status = -1;  // exit status of the program
  std::string out, err;
  // Lines of stderr (without the trailing newline), for "one clear line" checks.
  int err_lines() const {
    int n = 0;
    for (char c : err) n += c == '\n';
    return n;
  }
};

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `args` is appended to POWDERBED_APPS_DIR/<app> and run through the shell, under coreutils'
// timeout: a program still running after `timeout_s` seconds is sent SIGTERM (SIGKILL 5 s
// later) and the result has status 124 (137 when killed), so a program that hangs (a reader
// blocked on a FIFO) fails its test instead of hanging the suite.
inline CommandResult run_app(const std::string& app, const std::string& args, int timeout_s = 600) {
  const std::string stem = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_" + app;
  const std::string cmd = "timeout --kill-after=5 " + std::to_string(timeout_s) + " " +
                          std::string(POWDERBED_APPS_DIR) + "/" + app + " " + args + " >" + stem +
                          ".out 2>" + stem + ".err </dev/null";
  CommandResult r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_text(stem + ".out");
  r.err = read_text(stem + ".err");
  std::remove((stem + ".out").c_str());
  std::remove((stem + ".err").c_str());
  return r;
}

// A fresh scratch directory for one test, removed by the caller if it wants.
inline std::string scratch_dir(const std::string& name) {
  const std::string dir = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_" + name;
  const std::string cmd = "rm -rf '" + dir + "' && mkdir -p '" + dir + "'";
  if (std::system(cmd.c_str()) != 0) return "/tmp";
  return dir;
}

// The number after the first "key": in a one-line JSON summary (NaN when the key is missing
// or its value is null, which is how the writer prints a non-finite number).
inline double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  const char* start = json.c_str() + at + key.size() + 3;
  char* end = nullptr;
  const double v = std::strtod(start, &end);
  return end == start ? NAN : v;
}

}  // namespace powderbed::test
