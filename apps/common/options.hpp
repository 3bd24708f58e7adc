#pragma once
// Option parsing shared by the programs: Boost.Program_options with --config scene.ini
// (INI sections map to dotted option names; the command line wins), --help and --version.
#include <boost/program_options.hpp>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "powderbed/bed/domain.hpp"
#include "powderbed/bed/errors.hpp"

// Numbers at the command line and in scene files are parsed with their sign and range checked
// (docs/hardening.md): Boost's default (lexical_cast) turns "-5" into 2^64 - 5 for an unsigned
// option and accepts "nan" for a double. These overloads are found by argument-dependent lookup
// (boost::any) from Boost's typed_value<T>::xparse in every program that includes this header,
// and throw a validation_error whose message names the option, the value and what is accepted:
//   unsigned (std::size_t, std::uint64_t, unsigned): whole numbers >= 0 up to the type's maximum
//     ("1e6" is accepted when it is a whole number; "-5", "2.5", "1e30" are refused)
//   int: whole numbers in the int range; double: finite numbers (no nan, inf).
namespace boost {
void validate(boost::any& v, const std::vector<std::string>& xs, unsigned long*, int);
void validate(boost::any& v, const std::vector<std::string>& xs, unsigned int*, int);
void validate(boost::any& v, const std::vector<std::string>& xs, int*, int);
void validate(boost::any& v, const std::vector<std::string>& xs, double*, int);
}  // namespace boost

namespace powderbed::app {

namespace po = boost::program_options;

// Adds --help, --version, --config FILE, --json and --print-config (parse_options prints the
// resolved options as a scene file and returns false).
void add_common_options(po::options_description& desc);

// Adds --progress SECONDS: the time between progress lines of a batch run (common/progress.hpp).
void add_progress_option(po::options_description& desc);
// --progress checked: a finite number of seconds >= 0; throws InputError naming the option.
double progress_interval(const po::variables_map& vm);

// Parses argv and, when --config is given, the scene file; then fills the options a --material
// file gives (common/material_options.hpp). Returns false when --help, --version,
// --list-materials or --print-config was printed (the program then exits 0). Throws po::error /
// InputError on bad input.
bool parse_options(const char* app, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& positional, int argc, char** argv,
                   po::variables_map& vm);

// A scene file stored into `vm` after what `vm` holds (which wins): Boost's INI syntax
// ([section] sets the prefix "section.", key = value, '#' starts a comment) read one line at a
// time, so that every error names the file and the line: "<file>:<line>: <what>" (a line
// without '=', an unclosed [section, an unknown key of `desc`, a value its option refuses, a
// nested config). `option` names the file in the messages about the file itself (not a regular
// file, cannot be opened). parse_options reads --config with it.
void store_scene_file(const std::string& path, const po::options_description& desc,
                      po::variables_map& vm, const std::string& option = "--config");

// The value of a required option; throws InputError "--<name>: missing (required)".
template <class T>
T required(const po::variables_map& vm, const char* name) {
  if (!vm.count(name)) throw InputError(fmt::format("--{}: missing (required)", name));
  return vm[name].as<T>();
}

// The value of option `name` (with its default) checked against [lo, hi]; throws InputError
// "--<name>: <value> is out of range (accepted: <lo> to <hi>[, <why>])".
template <class T>
T option_in_range(const po::variables_map& vm, const char* name, T lo, T hi,
                  const std::string& why = "") {
  const T v = vm[name].as<T>();
  if (!(v >= lo && v <= hi)) {
    const auto text = [](T x) {  // as a stream of precision 6 writes it: %g for a double
      if constexpr (std::is_floating_point_v<T>) return fmt::format("{:g}", x);
      else return fmt::format("{}", x);
    };
    throw InputError(fmt::format("--{}: {} is out of range (accepted: {} to {}{}{})", name,
                                 text(v), text(lo), text(hi), why.empty() ? "" : "; ", why));
  }
  return v;
}

// An input or output path and the option (or positional name) it came from.
struct PathArg {
  std::string option;  // "--out", "--bed", "BED"
  std::string path;
};

// The check every program makes BEFORE its work starts (docs/hardening.md): each input exists
// and is a file; each output is not a folder, its folder exists and is writable, it is not one
// of the inputs (nor the .xmf sidecar of an .h5 input or output), and no two outputs are the
// same file. Throws InputError "<option>: '<path>' <what is wrong> (accepted: ...)".
void check_paths(const std::vector<PathArg>& inputs, const std::vector<PathArg>& outputs);

// Throws InputError "<option>: '<path>' has extension '<ext>' (accepted: .h5, ...)" unless the
// path ends (case-insensitively) with one of `accepted`; `hint` is appended to the accepted list.
void check_extension(const PathArg& path, std::initializer_list<const char*> accepted,
                     const std::string& hint = "");

// "a,b,c" -> numbers; throws InputError naming `option` unless there are between min_count
// and max_count finite numbers.
std::vector<double> parse_number_list(const std::string& text, std::size_t min_count,
                                      std::size_t max_count, const std::string& option);

// "LX,LY[,LZ]" -> the box [0, L] (2D or 3D); throws InputError naming `option`.
bed::Domain parse_domain_lengths(const std::string& text, const std::string& option);
// "xlo,ylo,zlo,xhi,yhi,zhi" -> that box (3D; zlo == zhi == 0 makes it 2D).
bed::Domain parse_domain_bounds(const std::string& text, const std::string& option);

// A value as a scene file writes it: a double as the shortest decimal that reads back to the
// same double (5.4e-05), a bool as true/false, whole numbers and strings as they are; nullopt
// for a type no option has.
std::optional<std::string> value_text(const boost::any& v);

// The resolved options as INI text (key = value per line, full precision; --config, --json,
// --help and --version left out): what a bed's or run's /provenance scene records.
std::string scene_text(const po::variables_map& vm);

// What --print-config prints after its header line: a scene file that --config reads back to
// the same options from any folder (docs/hardening.md "Scene files"). Given values as
// key = value; defaults and the values a --material file filled (`from_material`) commented
// out with "(default)" / "(from --material)", so a reread does not turn them into given values;
// paths absolute (as the program resolves them); a value holding '#', a line break, a leading
// quote or spaces at its ends "quoted" with \\ \" \n \r \t escapes; a switch given as true.
std::string print_config_text(const po::options_description& desc, const po::variables_map& vm,
                              const std::set<std::string>& from_material);

// Restates every double and bool default of `desc` as value_text writes it, for --help.
void scene_style_defaults(po::options_description& desc);

}  // namespace powderbed::app
