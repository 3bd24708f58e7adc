// A full disk and a kill in the rename window, for every program that writes (issue 36;
// docs/hardening.md "Full disk and the rename window"). The programs run under the LD_PRELOAD'd
// fault injector tests/shim/io_fault.cpp (POWDERBED_FAULT_PRELOAD), which needs no mount and so
// runs in CI everywhere:
// - FullDisk: the scratch folder's files may take only N bytes, for N from 0 to past what the
//   run writes. Each run exits 0 with every output whole, or 2/3 with ONE line naming the file
//   and the system's reason; never a signal; every file is its old bytes or the whole new ones;
//   no temporary is left.
// - RenameWindow: the program stops itself just before the k-th rename of a layer file into
//   place and is killed there (SIGKILL, or SIGINT then SIGCONT): every layer file present has its
//   /restart (build --in takes it), the old out.h5 is the old one or the whole new one, and the
//   next run removes what the SIGKILLed one left.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "powderbed/bed/bed.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/lattice.hpp"
#include "powderbed/dem/spread.hpp"
#include "run_command.hpp"

namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;  // file name -> bytes
using Env = std::vector<std::pair<std::string, std::string>>;

const std::string kSmall = std::string(POWDERBED_TEST_DATA) + "/build-small";
const std::string kScenes = std::string(POWDERBED_SOURCE_DIR) + "/data/scenes";

// Every file of `dir` (not in sub-folders' names: a build's folder is listed on its own).
Files snapshot(const std::string& dir) {
  Files files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    files[fs::relative(e.path(), dir).string()] = powderbed::test::read_text(e.path().string());
  }
  return files;
}

// Puts `dir` back to `files` exactly (removes the rest).
void restore(const std::string& dir, const Files& files) {
  fs::remove_all(dir);
  for (const auto& [name, bytes] : files) {
    fs::create_directories((fs::path(dir) / name).parent_path());
    std::ofstream(fs::path(dir) / name, std::ios::binary) << bytes;
  }
}

struct Outcome {
  bool stopped = false;   // stopped itself at the rename (only with wait_stop)
  int status = -1;        // exit status, or -1 when killed by a signal
  int signal = 0;         // the signal that ended it
  std::string err;        // stderr
};

// Starts `app args` (split at spaces) under the fault injector with `env`; stdout goes to
// /dev/null, stderr to a file outside the scratch folder.
pid_t spawn(const std::string& app, const std::string& args, const Env& env, const std::string& err) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  ::setenv("LD_PRELOAD", POWDERBED_FAULT_PRELOAD, 1);
  for (const auto& [k, v] : env) ::setenv(k.c_str(), v.c_str(), 1);
  std::vector<std::string> all = {std::string(POWDERBED_APPS_DIR) + "/" + app};
  std::istringstream words(args);
  for (std::string w; words >> w;) all.push_back(w);
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (!std::freopen("/dev/null", "w", stdout) || !std::freopen(err.c_str(), "w", stderr)) std::_Exit(126);
  ::execv(argv[0], argv.data());
  std::_Exit(127);
}

Outcome finish(pid_t pid, const std::string& err, bool wait_stop) {
  Outcome o;
  int raw = 0;
  ::waitpid(pid, &raw, wait_stop ? WUNTRACED : 0);
  if (WIFSTOPPED(raw)) {
    o.stopped = true;
    return o;
  }
  if (WIFEXITED(raw)) o.status = WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) o.signal = WTERMSIG(raw);
  o.err = powderbed::test::read_text(err);
  return o;
}

Outcome run(const std::string& app, const std::string& args, const Env& env) {
  const std::string err = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_fault.err";
  Outcome o = finish(spawn(app, args, env, err), err, false);
  fs::remove(err);
  return o;
}

bool is_temporary(const std::string& name) { return name.find(".tmp.") != std::string::npos; }

// One program that writes: its arguments ("{dir}" is the scratch folder), the files it needs
// beforehand (inputs and the user's old output, made by `prepare`).
struct Writer {
  std::string name, app, args;
  std::function<void(const std::string& dir)> prepare;
};

void PrintTo(const Writer& w, std::ostream* out) { *out << w.app << " " << w.args; }

std::string expand(std::string args, const std::string& dir) {
  for (std::size_t at; (at = args.find("{dir}")) != std::string::npos;) args.replace(at, 5, dir);
  return args;
}

void old_output(const std::string& dir) {
  powderbed::bed::write_bed_h5(powderbed::bed::simple_cubic_lattice(2, 1e-5), dir + "/out.h5");
}

std::vector<Writer> writers() {
  namespace bed = powderbed::bed;
  const auto good = [](const std::string& dir) {
    bed::write_bed_h5(bed::simple_cubic_lattice(3, 1e-5), dir + "/good.h5");
    old_output(dir);
  };
  const auto wide = [](const std::string& dir) {  // resting on the floor, wider than the spot
    bed::Bed b;
    b.domain.upper = {4e-4, 4e-4, 1e-4};
    for (int i = 0; i < 8; ++i) b.add(2e-5 + 4e-5 * i, 2e-4, 1.5e-5 * (1 - 1e-4), 1.5e-5);
    bed::write_bed_h5(b, dir + "/wide.h5");
    old_output(dir);
  };
  return {
      {"packgen", "packgen", "--dim 3 --domain 1e-4,1e-4,1e-4 --psd mono:d=2e-5 --seed 1 --out {dir}/out.h5",
       old_output},
      // --thermo 0: the one line a refused run prints is the promise; the table's rows would
      // come before it.
      {"deposit_drop", "deposit", "--in {dir}/good.h5 --t-end 1e-5 --seed 1 --thermo 0 --out {dir}/out.h5", good},
      {"deposit_spread", "deposit",
       "--config " + kSmall + "/spread.ini --seed 1 --layers 2 --thermo 0 --out {dir}/out.h5", old_output},
      {"sinter", "sinter",
       "--config " + kScenes + "/gz2016-sinter.ini --bed {dir}/wide.h5 --substrate.nodes 21,11,11 "
       "--substrate.depth 0.1e-3 --fuse --fused-bed {dir}/fused.h5 --out {dir}/out.h5",
       wide},
      {"keff", "keff", "--bed {dir}/good.h5 --out {dir}/out.h5", good},
      {"bedconv_csv", "bedconv", "{dir}/good.h5 {dir}/out.csv",
       [&](const std::string& dir) {
         good(dir);
         bed::write_bed_csv(bed::simple_cubic_lattice(2, 1e-5), dir + "/out.csv");
       }},
      {"build", "build", "--config " + kSmall + "/build.ini --layers 1 --spread-args --thermo=0 --out {dir}/run",
       old_output},
  };
}

// Budgets from nothing to past the whole run, so the disk fills at the start, in the middle of
// each file and at the closing flushes.
std::vector<long long> budgets(long long written) {
  std::vector<long long> b = {0, 1, 600};
  for (int k = 1; k < 10; ++k) b.push_back(written * k / 10);
  for (long long d : {4096, 512, 1}) b.push_back(written - d);
  b.push_back(written * 4);
  return b;
}

long long new_bytes(const Files& before, const Files& after) {
  long long n = 0;
  for (const auto& [name, bytes] : after) {
    const auto it = before.find(name);
    if (it == before.end() || it->second != bytes) n += static_cast<long long>(bytes.size());
  }
  return n;
}

void check_full_disk(const Writer& w) {
  const std::string dir = powderbed::test::scratch_dir("full_disk_" + w.name);
  w.prepare(dir);
  const Files before = snapshot(dir);
  const std::string args = expand(w.args, dir);
  const Env frozen = {{"POWDERBED_FAULT_CLOCK", "1"}};  // the same bytes every run
  const Outcome whole = run(w.app, args, frozen);
  ASSERT_EQ(whole.status, 0) << w.name << ": " << whole.err;
  const Files after = snapshot(dir);
  const long long written = new_bytes(before, after);
  ASSERT_GT(written, 0) << w.name;
  int refused = 0;
  for (const long long budget : budgets(written)) {
    restore(dir, before);
    const Outcome o = run(w.app, args, {{"POWDERBED_FAULT_CLOCK", "1"},
                                        {"POWDERBED_FAULT_PATH", dir + "/*"},
                                        {"POWDERBED_FAULT_BYTES", std::to_string(budget)}});
    const std::string what = w.name + " with " + std::to_string(budget) + " of " +
                             std::to_string(written) + " bytes: ";
    ASSERT_EQ(o.signal, 0) << what << "killed by signal " << o.signal << "; " << o.err;
    const Files now = snapshot(dir);
    for (const auto& [name, bytes] : now) {
      EXPECT_FALSE(is_temporary(name)) << what << "left " << name;
      const auto old_it = before.find(name);
      const bool old = old_it != before.end() && old_it->second == bytes;
      const bool whole_new = after.count(name) && after.at(name) == bytes;
      EXPECT_TRUE(old || whole_new) << what << name << " is neither the old file nor the whole new one";
    }
    if (o.status == 0) {  // then every output is there, whole
      for (const auto& [name, bytes] : after)
        EXPECT_TRUE(now.count(name) && now.at(name) == bytes) << what << "exit 0 but " << name << " is not whole";
      continue;
    }
    ++refused;
    EXPECT_TRUE(o.status == 2 || o.status == 3) << what << "exit " << o.status << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << what << o.err;
    EXPECT_NE(o.err.find(dir + "/"), std::string::npos) << what << "the file is not named: " << o.err;
    EXPECT_NE(o.err.find("No space left on device"), std::string::npos) << what << o.err;
    for (const auto& [name, bytes] : before)  // the user's files, the old output included
      EXPECT_TRUE(now.count(name) && now.at(name) == bytes) << what << name << " changed";
  }
  EXPECT_GE(refused, 10) << w.name << ": the disk never filled: the budgets miss the run";
  fs::remove_all(dir);
}

}  // namespace

class FullDisk : public ::testing::TestWithParam<Writer> {};

TEST_P(FullDisk, OldFileIntactOneLineNoTemporaryNoSignal) { check_full_disk(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Writers, FullDisk, ::testing::ValuesIn(writers()),
                         [](const ::testing::TestParamInfo<Writer>& p) { return p.param.name; });

namespace {

// A program that spreads layers and the names of its layer files.
struct Spreader {
  std::string app, args;  // "{dir}" is the scratch folder
  std::string renames;    // fnmatch pattern of the renames it stops at
  std::regex layer;       // the layer files that must carry /restart
};

// Every layer file present carries its /restart whole (what build --in and deposit --in need).
void expect_layers_restartable(const std::string& dir, const Spreader& s, const std::string& what) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (!std::regex_match(name, s.layer)) continue;
    const std::string path = e.path().string();
    EXPECT_NO_THROW({
      const powderbed::bed::Bed b = powderbed::bed::read_bed_h5(path);
      powderbed::dem::read_spread_state(path, b);
    }) << what << name << " has no whole /restart";
  }
}

// Stops the run just before each rename of a layer file in turn and kills it there with `sig`
// (SIGINT: delivered when it is continued, so the handler runs).
void kill_in_rename_window(const Spreader& s, int sig) {
  const std::string dir = powderbed::test::scratch_dir("rename_window_" + s.app + std::to_string(sig));
  old_output(dir);
  const Files before = snapshot(dir);
  const std::string args = expand(s.args, dir);
  const Env frozen = {{"POWDERBED_FAULT_CLOCK", "1"}};
  const Outcome whole = run(s.app, args, frozen);
  ASSERT_EQ(whole.status, 0) << whole.err;
  const Files after = snapshot(dir);
  const std::string err = "/tmp/powderbed_test_" + std::to_string(::getpid()) + "_window.err";
  int killed = 0;
  for (int k = 1; k < 20; ++k) {
    restore(dir, before);
    const pid_t pid = spawn(s.app, args, {{"POWDERBED_FAULT_CLOCK", "1"},
                                          {"POWDERBED_FAULT_STOP_RENAME", s.renames},
                                          {"POWDERBED_FAULT_STOP_AT", std::to_string(k)}}, err);
    const Outcome stop = finish(pid, err, true);
    if (!stop.stopped) {  // past the last rename: the run ends as without the injector
      EXPECT_EQ(stop.status, 0) << stop.err;
      break;
    }
    ::kill(pid, sig);
    ::kill(pid, SIGCONT);
    const Outcome o = finish(pid, err, false);
    const std::string what = s.app + " killed by " + std::to_string(sig) + " before rename " +
                             std::to_string(k) + ": ";
    EXPECT_EQ(o.signal, sig) << what << "exit " << o.status << " " << o.err;
    ++killed;
    expect_layers_restartable(dir, s, what);
    const Files now = snapshot(dir);
    for (const auto& [name, bytes] : now) {
      if (is_temporary(name)) {
        EXPECT_EQ(sig, SIGKILL) << what << "left " << name;
        EXPECT_NE(name.find(".tmp." + std::to_string(pid)), std::string::npos) << what << name;
        continue;
      }
      const bool old = before.count(name) && before.at(name) == bytes;
      const bool whole_new = after.count(name) && after.at(name) == bytes;
      EXPECT_TRUE(old || whole_new) << what << name << " is neither the old file nor the whole new one";
    }
    if (sig == SIGKILL && s.app == "deposit") {
      // The next run of the same outputs removes what the killed one left.
      const Outcome next = run(s.app, args, frozen);
      EXPECT_EQ(next.status, 0) << what << next.err;
      for (const auto& [name, bytes] : snapshot(dir)) EXPECT_FALSE(is_temporary(name)) << what << "left " << name;
    }
    if (sig == SIGKILL && s.app == "build" && k == 1) {
      // A build folder holding only the killed run's temporaries is taken by the next build.
      const Outcome next = run(s.app, args, frozen);
      EXPECT_EQ(next.status, 0) << what << next.err;
      for (const auto& [name, bytes] : snapshot(dir)) EXPECT_FALSE(is_temporary(name)) << what << "left " << name;
    }
  }
  fs::remove(err);
  EXPECT_GE(killed, 3) << s.app << ": too few renames stopped at";
  fs::remove_all(dir);
}

const Spreader kDepositSpread{"deposit", "--config " + kSmall + "/spread.ini --seed 1 --layers 2 --out {dir}/out.h5",
                              "*/out*.h5", std::regex(R"(out-\d{3}\.h5)")};
const Spreader kBuild{"build", "--config " + kSmall + "/build.ini --layers 2 --out {dir}/run",
                      "*/run/layer-*.h5", std::regex(R"(layer-\d{3}\.h5)")};

}  // namespace

TEST(RenameWindow, DepositSpreadSigkill) { kill_in_rename_window(kDepositSpread, SIGKILL); }
TEST(RenameWindow, DepositSpreadSigint) { kill_in_rename_window(kDepositSpread, SIGINT); }
TEST(RenameWindow, BuildSigkill) { kill_in_rename_window(kBuild, SIGKILL); }
TEST(RenameWindow, BuildSigint) { kill_in_rename_window(kBuild, SIGINT); }

// build --in takes the last layer file a build killed in its last rename window left behind.
TEST(RenameWindow, BuildContinuesFromTheLayerFileAKillLeft) {
  const std::string dir = powderbed::test::scratch_dir("rename_window_continue");
  const std::string args = "--config " + kSmall + "/build.ini --layers 2 --out " + dir + "/run";
  const std::string err = dir + "/../rename_window_continue.err";
  // The 6th layer-file rename is layer-002.h5 (spread, scan, layer, for each layer).
  const pid_t pid = spawn("build", args, {{"POWDERBED_FAULT_STOP_RENAME", "*/run/layer-*.h5"},
                                          {"POWDERBED_FAULT_STOP_AT", "6"}}, err);
  ASSERT_TRUE(finish(pid, err, true).stopped);
  ::kill(pid, SIGKILL);
  finish(pid, err, false);
  ASSERT_TRUE(fs::exists(dir + "/run/layer-002-scan.h5"));
  ASSERT_FALSE(fs::exists(dir + "/run/layer-002.h5"));
  const powderbed::test::CommandResult next = powderbed::test::run_app(
      "build", "--config " + kSmall + "/build.ini --layers 1 --in " + dir + "/run/layer-001.h5 --out " + dir + "/more");
  EXPECT_EQ(next.status, 0) << next.err;
  EXPECT_TRUE(fs::exists(dir + "/more/layer-002.h5"));
  fs::remove(err);
  fs::remove_all(dir);
}
