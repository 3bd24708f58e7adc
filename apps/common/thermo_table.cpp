#include "common/thermo_table.hpp"

#include <unistd.h>

#include <cstdio>
#include <utility>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_output.hpp"

namespace powderbed::app {

void add_thermo_options(po::options_description& desc) {
  desc.add_options()
      ("thermo", po::value<std::uint64_t>(),
       "steps between two rows of the thermo table on stderr (Step Time KinEng MaxOverlap "
       "Contacts Lost; spreads: Layer ToolX; default: about 30 rows over the run; 0: none)")
      ("log", po::value<std::string>(),
       "also write the thermo table and the run's summary to this file (as LAMMPS's log.lammps)");
}

ThermoTable::ThermoTable(bool spread, std::optional<std::string> log)
    : spread_(spread), log_(std::move(log)), terminal_(::isatty(STDERR_FILENO) != 0) {}

// The columns' widths: every row as wide as the header, so the columns line up.
std::string ThermoTable::header(bool spread) {
  std::string h = fmt::format("{:>10} {:>13} {:>13} {:>11} {:>9} {:>6}", "Step", "Time", "KinEng",
                              "MaxOverlap", "Contacts", "Lost");
  if (spread) h += fmt::format(" {:>6} {:>13}", "Layer", "ToolX");
  return h;
}

std::string ThermoTable::format(const dem::ThermoRow& r, bool spread) {
  std::string line = fmt::format("{:>10} {:>13.6e} {:>13.6e} {:>11.4e} {:>9} {:>6}", r.step, r.time,
                                 r.kinetic_energy, r.overlap.relative, r.overlap.contacts, r.lost);
  if (spread) line += fmt::format(" {:>6} {:>13.6e}", r.layer, r.tool_x);
  return line;
}

void ThermoTable::row(const dem::ThermoRow& r) {
  std::string lines;
  if (!header_done_) {
    lines = header(spread_) + '\n';
    header_done_ = true;
  }
  lines += format(r, spread_) + '\n';
  std::fprintf(stderr, "%s%s", terminal_ ? "\r\033[K" : "", lines.c_str());
  std::fflush(stderr);
  text_ += lines;
  write_log();
}

void ThermoTable::summary(const std::string& text) {
  text_ += text;
  if (!text.empty() && text.back() != '\n') text_ += '\n';
  write_log();
}

void ThermoTable::write_log() const {
  if (log_) bed::write_text_file(*log_, text_);
}

std::optional<PathArg> log_path(const po::variables_map& vm) {
  if (!vm.count("log")) return std::nullopt;
  return PathArg{"--log", vm["log"].as<std::string>()};
}

std::shared_ptr<ThermoTable> attach_thermo(const po::variables_map& vm, bool spread,
                                           dem::ThermoFn& hook, std::uint64_t& every) {
  const std::uint64_t asked = vm.count("thermo") ? vm["thermo"].as<std::uint64_t>() : 0;
  const bool rows = !vm.count("thermo") || asked > 0;
  const std::optional<PathArg> log = log_path(vm);
  if (!rows && !log) return nullptr;
  auto table = std::make_shared<ThermoTable>(spread, log ? std::optional(log->path) : std::nullopt);
  if (rows) {
    hook = [table](const dem::ThermoRow& r) { table->row(r); };
    every = asked;  // 0: the solver's default
  }
  return table;
}

}  // namespace powderbed::app
