#include "build_pictures.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

extern char** environ;

namespace powderbed::app {

namespace fs = std::filesystem;

namespace {

constexpr const char* kKinds[] = {"top", "fusion", "height", "section"};  // plot_build_layer.py's pictures

struct Finished {
  int status = -1;     // waitpid's status; -1: could not start
  std::string stderr_text;
};

// Runs `argv` with stdout discarded and stderr captured (the plotter's one-line reason when it
// fails). posix_spawn rather than fork: the build may hold an OpenMP team.
Finished run_captured(const std::vector<std::string>& argv) {
  Finished done;
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    done.stderr_text = fmt::format("cannot make a pipe: {}", std::strerror(errno));
    return done;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (spawned != 0) {
    ::close(pipe_fds[0]);
    done.stderr_text = fmt::format("cannot run {}: {}", argv[0], std::strerror(spawned));
    return done;
  }
  std::array<char, 4096> buffer;
  for (ssize_t got; (got = ::read(pipe_fds[0], buffer.data(), buffer.size())) != 0;) {
    if (got > 0) done.stderr_text.append(buffer.data(), static_cast<std::size_t>(got));
    else if (errno != EINTR) break;
  }
  ::close(pipe_fds[0]);
  while (::waitpid(pid, &done.status, 0) < 0 && errno == EINTR) {
  }
  return done;
}

// The last non-empty line of a program's stderr: its reason (a traceback ends with the error).
std::string last_line(const std::string& text) {
  const std::size_t end = text.find_last_not_of("\r\n ");
  if (end == std::string::npos) return "";
  const std::size_t newline = text.rfind('\n', end);
  const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
  return text.substr(begin, end + 1 - begin);
}

std::string failure(const Finished& done) {
  const std::string why = last_line(done.stderr_text);
  if (done.status == -1) return why;
  if (WIFSIGNALED(done.status))
    return fmt::format("the plotter was killed by signal {}", WTERMSIG(done.status));
  return fmt::format("the plotter exited with status {}{}{}", WEXITSTATUS(done.status),
                     why.empty() ? "" : ": ", why);
}

}  // namespace

std::string find_plotter(const char* name, std::string& looked) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    looked = "/proc/self/exe (unreadable)";
    return "";
  }
  const fs::path root = exe.parent_path().parent_path();
  looked.clear();
  for (const fs::path& candidate : {root / "scripts" / name, root / "libexec" / "powderbed" / name}) {
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    looked += (looked.empty() ? "" : " or ") + candidate.string();
  }
  return "";
}

std::string draw_map(const std::string& json, const std::string& png) {
  std::string looked;
  const std::string plotter = find_plotter("plot_build_map", looked);
  if (plotter.empty())
    return fmt::format("no plotter beside the program (looked for {}; configure with "
                       "POWDERBED_BUILD_PYTHON=ON and python3-matplotlib)", looked);
  const Finished done = run_captured({plotter, json, png});
  return done.status == 0 ? "" : failure(done);
}

LayerPictures::LayerPictures(bool on) : on_(on) {
  if (!on_) return;
  std::string looked;
  plotter_ = find_plotter("plot_build_layer", looked);
  if (plotter_.empty())
    missing_ = fmt::format("no plotter beside the program (looked for {}; configure with "
                           "POWDERBED_BUILD_PYTHON=ON and python3-matplotlib)", looked);
}

void LayerPictures::give_up(std::uint64_t layer, const std::string& why) {
  std::cerr << fmt::format("build: warning: no pictures from layer {} on: {} (the build goes on "
                           "without them; --pictures false does not ask)\n", layer, why);
  on_ = false;
}

LayerPictureFiles LayerPictures::draw(const std::string& scan_file, const std::string& out,
                                      std::uint64_t layer) {
  if (!on_) return {};
  if (!missing_.empty()) {
    give_up(layer, missing_);
    return {};
  }
  char prefix[32];
  std::snprintf(prefix, sizeof prefix, "layer-%03llu", static_cast<unsigned long long>(layer));
  const Finished done = run_captured({plotter_, scan_file, (fs::path(out) / prefix).string(),
                                      "--layer", std::to_string(layer)});
  // What was drawn is listed even when a later picture failed: each appeared by rename, whole.
  LayerPictureFiles files;
  for (const char* kind : kKinds) {
    const std::string name = fmt::format("{}-{}.png", prefix, kind);
    if (fs::exists(fs::path(out) / name)) files.emplace_back(kind, name);
  }
  if (done.status != 0)
    give_up(layer, failure(done));
  else if (files.size() != std::size(kKinds))
    give_up(layer, fmt::format("the plotter wrote {} of the {} pictures", files.size(),
                               std::size(kKinds)));
  return files;
}

}  // namespace powderbed::app
