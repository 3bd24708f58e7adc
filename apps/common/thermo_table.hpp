#pragma once
// deposit's thermo table (docs/deposit-thermo.md), after LAMMPS's `thermo N` and
// log.lammps: a header once, then one aligned row per report of the solver (dem::ThermoRow),
// Step Time KinEng MaxOverlap Contacts Lost (spreads: Layer ToolX), on stderr; with --log FILE
// the same rows and the run's summary in FILE. The drop and the spreads (deposit's and build's,
// through spread_settings) share it.
#include <memory>
#include <optional>
#include <string>

#include "common/options.hpp"
#include "powderbed/dem/diagnostics.hpp"

namespace powderbed::app {

// --thermo N (steps between rows; default: about dem::kThermoRows rows over the run; 0: none)
// and --log FILE.
void add_thermo_options(po::options_description& desc);

class ThermoTable {
 public:
  // `spread`: with the Layer and ToolX columns; `log`: the log file's path, if any.
  ThermoTable(bool spread, std::optional<std::string> log);
  // The row (the header first, once). On stderr: on a terminal the progress bar's line is
  // cleared first and the bar comes back at its next update, so the two never share a line.
  // The log is rewritten whole (temporary + rename) after each row: never half-written, and a
  // run that stops leaves the rows so far.
  void row(const dem::ThermoRow& r);
  // The run's summary (what stdout prints), appended to the log, which is then written.
  void summary(const std::string& text);

  static std::string header(bool spread);
  static std::string format(const dem::ThermoRow& r, bool spread);

 private:
  void write_log() const;

  bool spread_;
  std::optional<std::string> log_;
  bool terminal_;
  bool header_done_ = false;
  std::string text_;  // the log's content so far
};

// The table the options ask for (none with --thermo 0 and no --log), with the solver's hook:
// `hook` and `every` are set when rows are asked for (RunSettings / SpreadSettings::thermo,
// thermo_every). `log_output`: the log's PathArg for check_paths, when --log is given.
std::shared_ptr<ThermoTable> attach_thermo(const po::variables_map& vm, bool spread,
                                           dem::ThermoFn& hook, std::uint64_t& every);
std::optional<PathArg> log_path(const po::variables_map& vm);

}  // namespace powderbed::app
