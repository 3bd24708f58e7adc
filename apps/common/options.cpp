#include "common/options.hpp"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "common/app_main.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::app {

void add_common_options(po::options_description& desc) {
  desc.add_options()("help,h", "print this help and exit")("version", "print the version and exit")(
      "config", po::value<std::string>(),
      "scene file (INI; [section] key = value sets --section.key); the command line wins")(
      "json", "print one JSON summary object on stdout");
}

bool parse_options(const char* app, const std::string& usage, po::options_description& desc,
                   const po::positional_options_description& positional, int argc, char** argv,
                   po::variables_map& vm) {
  po::store(po::command_line_parser(argc, argv).options(desc).positional(positional).run(), vm);
  if (vm.count("help")) {
    std::cout << "usage: " << usage << "\n\n" << desc << '\n';
    return false;
  }
  if (vm.count("version")) {
    std::cout << version_string(app) << '\n';
    return false;
  }
  if (vm.count("config")) {
    const std::string path = vm["config"].as<std::string>();
    std::ifstream in(path);
    if (!in) throw InputError("--config: cannot open scene file '" + path + "'");
    // Stored after the command line, so command-line values win (first store wins).
    po::store(po::parse_config_file(in, desc, false), vm);
  }
  po::notify(vm);
  return true;
}

std::vector<double> parse_number_list(const std::string& text, std::size_t min_count,
                                      std::size_t max_count, const std::string& option) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  auto range = [&] {
    return min_count == max_count ? std::to_string(min_count)
                                  : std::to_string(min_count) + " to " + std::to_string(max_count);
  };
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
      values.push_back(v);
    } catch (const std::exception&) {
      throw InputError(option + ": '" + text + "' is not a comma-separated list of numbers (" +
                       range() + " expected)");
    }
  }
  if (values.size() < min_count || values.size() > max_count) {
    throw InputError(option + ": '" + text + "' has " + std::to_string(values.size()) +
                     " numbers (accepted: " + range() + ")");
  }
  return values;
}

bed::Domain parse_domain_lengths(const std::string& text, const std::string& option) {
  const auto lengths = parse_number_list(text, 2, 3, option);
  bed::Domain d;
  d.dimension = static_cast<int>(lengths.size());
  d.upper = {lengths[0], lengths[1], d.dimension == 3 ? lengths[2] : 0.0};
  d.validate(option.c_str());
  return d;
}

bed::Domain parse_domain_bounds(const std::string& text, const std::string& option) {
  const auto b = parse_number_list(text, 6, 6, option);
  bed::Domain d;
  d.lower = {b[0], b[1], b[2]};
  d.upper = {b[3], b[4], b[5]};
  d.dimension = (b[2] == 0 && b[5] == 0) ? 2 : 3;
  d.validate(option.c_str());
  return d;
}

std::string scene_text(const po::variables_map& vm) {
  std::ostringstream out;
  out.precision(17);
  for (const auto& [key, value] : vm) {
    if (key == "config" || key == "json" || key == "help" || key == "version") continue;
    const auto& v = value.value();
    out << key << " = ";
    if (const auto* s = boost::any_cast<std::string>(&v)) out << *s;
    else if (const auto* d = boost::any_cast<double>(&v)) out << *d;
    else if (const auto* b = boost::any_cast<bool>(&v)) out << (*b ? "true" : "false");
    else if (const auto* u = boost::any_cast<std::uint64_t>(&v)) out << *u;
    else if (const auto* z = boost::any_cast<std::size_t>(&v)) out << *z;
    else if (const auto* i = boost::any_cast<int>(&v)) out << *i;
    out << '\n';
  }
  return out.str();
}

}  // namespace powderbed::app
