// build's LIGGGHTS spreading engine (spread_engine_liggghts.hpp, docs/build.md).
#include "spread_engine_liggghts.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include "powderbed/bed/deck.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/dem/recoater.hpp"
#include "deposit_spread.hpp"
#include "spread_deck.hpp"

namespace powderbed::app {

namespace fs = std::filesystem;

namespace {

constexpr const char* kData = "spread.data";  // the deck's files in the layer's folder

// The executable `name` on PATH, or "" (what a shell's command lookup finds).
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path p = fs::path(dir.empty() ? "." : dir) / name;
    if (::access(p.c_str(), X_OK) == 0 && !fs::is_directory(p)) return p.string();
  }
  return "";
}

// Runs argv in `folder` with stdout and stderr to folder/screen.txt; returns the exit status
// (-1 when it could not start, 128 + N when killed by signal N).
int run_in(const std::vector<std::string>& args, const std::string& folder) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string screen = (fs::path(folder) / "screen.txt").string();
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::open(screen.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::chdir(folder.c_str()) != 0) ::_exit(127);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// How many atoms LIGGGHTS's delete_atoms took (the overflow), from its screen output.
std::size_t deleted_atoms(const std::string& screen) {
  static const std::regex deleted(R"(Deleted (\d+) atoms)");
  std::size_t n = 0;
  for (auto it = std::sregex_iterator(screen.begin(), screen.end(), deleted); it != std::sregex_iterator(); ++it)
    n += std::stoull((*it)[1]);
  return n;
}

// The bed after the layer: the particles the dump holds (by id) with its centres and velocities,
// the rest of each particle (material, temperature, phase) as it was; the domain stays the
// bed's (LIGGGHTS prints a dump's box with %g).
void take_back(bed::Bed& bed, const bed::Bed& dump) {
  std::unordered_map<std::uint64_t, std::size_t> at;
  for (std::size_t i = 0; i < dump.n(); ++i) at[dump.id[i]] = i;
  std::vector<char> keep(bed.n(), 0);
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const auto it = at.find(bed.id[i]);
    if (it == at.end()) continue;
    const std::size_t k = it->second;
    keep[i] = 1;
    bed.x[i] = dump.x[k];
    bed.y[i] = dump.y[k];
    bed.z[i] = dump.z[k];
    bed.vx[i] = dump.vx.empty() ? 0.0 : dump.vx[k];
    bed.vy[i] = dump.vy.empty() ? 0.0 : dump.vy[k];
    bed.vz[i] = dump.vz.empty() ? 0.0 : dump.vz[k];
  }
  dem::SpreadState none;  // no state to trim yet: it is made for what stays
  none.wx.assign(bed.n(), 0.0);
  none.wy.assign(bed.n(), 0.0);
  none.wz.assign(bed.n(), 0.0);
  none.wall_history.assign(bed.n() * dem::kWallHistoryValues, 0.0);
  dem::remove_particles(bed, none, keep);
}

std::uint64_t steps_of(double seconds, double dt) {  // as run_spread counts them
  return static_cast<std::uint64_t>(std::ceil(seconds / dt - 1e-9));
}

}  // namespace

void add_spread_engine_options(po::options_description& desc) {
  desc.add_options()
      ("spread-engine", po::value<std::string>()->default_value("deposit"),
       "what spreads each layer: deposit (dem::run_spread, in-process) or liggghts (a LIGGGHTS "
       "deck per layer, run with the `liggghts` on PATH; docs/build.md)")
      ("mpi", po::value<unsigned>()->default_value(1),
       "with --spread-engine liggghts: MPI ranks (N > 1: mpirun --allow-run-as-root "
       "--oversubscribe -np N liggghts)");
}

std::optional<LiggghtsEngine> spread_engine(const po::variables_map& vm, const po::variables_map& spread,
                                            std::uint64_t seed) {
  const std::string name = vm["spread-engine"].as<std::string>();
  const unsigned ranks = vm["mpi"].as<unsigned>();
  if (name != "deposit" && name != "liggghts")
    throw InputError(fmt::format("--spread-engine: '{}' (accepted: deposit, liggghts)", name));
  if (ranks == 0) throw InputError("--mpi: 0 (accepted: N >= 1 ranks)");
  if (name == "deposit") {
    if (!vm["mpi"].defaulted())
      throw InputError("--mpi: given with --spread-engine deposit (accepted: with --spread-engine liggghts)");
    return std::nullopt;
  }
  if (spread["recoater.until-rest"].as<bool>()) {
    throw InputError("recoater.until-rest: true with --spread-engine liggghts (accepted: false; "
                     "its decks settle for the fixed recoater.settle)");
  }
  if (spread["sleep.on"].as<bool>()) {
    throw InputError("sleep.on: true with --spread-engine liggghts (accepted: false; its decks "
                     "integrate every particle)");
  }
  if (spread.count("supply.platform-edge")) {
    throw InputError("supply.platform-edge: set with --spread-engine liggghts (accepted: unset; its "
                     "decks' supply falls on the plate or the powder there)");
  }
  LiggghtsEngine e;
  e.ranks = ranks;
  e.liggghts = on_path("liggghts");
  if (e.liggghts.empty())
    throw InputError("--spread-engine liggghts: no `liggghts` on PATH (accepted: LIGGGHTS 3.8 "
                     "installed, e.g. Debian's liggghts package; or --spread-engine deposit)");
  if (ranks > 1) {
    e.mpirun = on_path("mpirun");
    if (e.mpirun.empty())
      throw InputError(fmt::format("--mpi {}: no `mpirun` on PATH (accepted: --mpi 1, or an MPI "
                                   "installed, e.g. Debian's openmpi-bin)", ranks));
  }
  e.seed = seed;
  e.psd = bed::Psd::parse(required<std::string>(spread, "psd"), "--psd");
  // Layers 2.. of a deck (each deck's first layer is supplied by deposit's maker).
  const SupplyAmount later = supply_amount(spread, 2, spread_box(spread).length(1));
  e.supply_count = later.count;
  e.supply_volume = later.volume;
  return e;
}

dem::SpreadSummary liggghts_spread_layer(const LiggghtsEngine& engine, bed::Bed& bed,
                                         const dem::Scene& scene, const dem::SpreadSettings& settings,
                                         const std::optional<dem::SpreadState>& state,
                                         std::uint64_t layer, const std::string& folder) {
  const auto started = std::chrono::steady_clock::now();
  SpreadDeckRequest r;
  r.floor = settings.floor.empty() && state ? state->floor : settings.floor;
  dem::LayerSummary out;
  out.layer = layer;
  out.supplied = dem::add_layer_supply(bed, settings, r.floor, layer);
  r.bed = &bed;
  r.scene = &scene;
  r.settings = &settings;
  r.psd = &engine.psd;
  r.seed = engine.seed;
  r.first = layer;
  r.dt = state && state->dt > 0 ? state->dt : spread_time_step(bed, scene, settings);
  r.supply_count = engine.supply_count;
  r.supply_volume = engine.supply_volume;
  r.made_by = "build --spread-engine liggghts, layer " + std::to_string(layer);
  fs::create_directories(folder);
  const std::string data = (fs::path(folder) / kData).string();
  write_spread_deck(r, data);

  const std::string input = fs::path(bed::deck_files(data, bed::DeckEngine::liggghts).input).filename().string();
  std::vector<std::string> args{engine.liggghts, "-in", input, "-log", "log.liggghts"};
  if (engine.ranks > 1)
    args.insert(args.begin(), {engine.mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
                               std::to_string(engine.ranks)});
  const int status = run_in(args, folder);
  const std::string dump = bed::spread_layer_dump(data, 1, bed::DeckEngine::liggghts);
  if (status != 0 || !fs::exists(dump))
    throw NumericalError(fmt::format("--spread-engine liggghts: layer {}: LIGGGHTS exited {} (see {}/screen.txt "
                                     "and log.liggghts)", layer, status, folder));
  const std::size_t before = bed.n();
  take_back(bed, bed::read_lammps_dump(dump));
  out.overflow = deleted_atoms(read_text((fs::path(folder) / "screen.txt").string()));
  out.lost = before - bed.n() > out.overflow ? before - bed.n() - out.overflow : 0;

  const dem::Recoater& t = settings.tool;
  out.n = bed.n();
  out.steps = steps_of(t.delay, r.dt) + steps_of((t.end - t.start) / t.speed, r.dt) + steps_of(t.settle, r.dt);
  out.tool_bottom = bed.domain.lower[2] + t.gap + static_cast<double>(layer - 1) * settings.layer_thickness;
  dem::SpreadSummary summary;
  summary.state.layers_done = layer;
  summary.state.step = (state ? state->step : 0) + out.steps;
  summary.state.dt = summary.dt = r.dt;
  summary.state.time = summary.sim_time = static_cast<double>(summary.state.step) * r.dt;
  out.sim_time = summary.sim_time;
  summary.state.tool_x = t.end;
  summary.state.plate_offset = static_cast<double>(layer - 1) * settings.layer_thickness;
  summary.state.wx.assign(bed.n(), 0.0);
  summary.state.wy.assign(bed.n(), 0.0);
  summary.state.wz.assign(bed.n(), 0.0);
  summary.state.wall_history.assign(bed.n() * dem::kWallHistoryValues, 0.0);
  summary.state.floor = r.floor;
  summary.steps = out.steps;
  out.wall_time = summary.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  summary.particle_steps_per_s = static_cast<double>(before) * static_cast<double>(out.steps) / summary.wall_time;
  summary.layers.push_back(out);
  return summary;
}

}  // namespace powderbed::app
