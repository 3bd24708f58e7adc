#pragma once
// Option parsing shared by the programs: Boost.Program_options with --config scene.ini
// (INI sections map to dotted option names; the command line wins), --help and --version.
#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "powderbed/bed/domain.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::app {

namespace po = boost::program_options;

// Adds --help, --version, --config FILE and --json.
void add_common_options(po::options_description& desc);

// Parses argv and, when --config is given, the scene file. Returns false when --help or
// --version was printed (the program then exits 0). Throws po::error / InputError on bad input.
bool parse_options(const char* app, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& positional, int argc, char** argv,
                   po::variables_map& vm);

// The value of a required option; throws InputError "--<name>: missing (required)".
template <class T>
T required(const po::variables_map& vm, const char* name) {
  if (!vm.count(name)) throw InputError(std::string("--") + name + ": missing (required)");
  return vm[name].as<T>();
}

// "a,b,c" -> numbers; throws InputError naming `option` unless there are between min_count
// and max_count finite numbers.
std::vector<double> parse_number_list(const std::string& text, std::size_t min_count,
                                      std::size_t max_count, const std::string& option);

// "LX,LY[,LZ]" -> the box [0, L] (2D or 3D); throws InputError naming `option`.
bed::Domain parse_domain_lengths(const std::string& text, const std::string& option);
// "xlo,ylo,zlo,xhi,yhi,zhi" -> that box (3D; zlo == zhi == 0 makes it 2D).
bed::Domain parse_domain_bounds(const std::string& text, const std::string& option);

// The resolved options as INI text (key = value per line, full precision; --config, --json,
// --help and --version left out): what a bed's or run's /provenance scene records.
std::string scene_text(const po::variables_map& vm);

}  // namespace powderbed::app
