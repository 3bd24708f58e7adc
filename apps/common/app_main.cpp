#include "common/app_main.hpp"

#include <boost/program_options/errors.hpp>
#include <iostream>

#include <fmt/format.h>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/json.hpp"

namespace powderbed::app {

int run_app(const char* app, int /*argc*/, char** /*argv*/, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << fmt::format("{}: {}\n", app, e.what());
    return 2;
  } catch (const boost::program_options::error& e) {
    std::cerr << fmt::format("{0}: {1} (see {0} --help)\n", app, e.what());
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << fmt::format("{}: numerical failure: {}\n", app, e.what());
    return 3;
  } catch (const std::exception& e) {
    std::cerr << fmt::format("{}: internal error: {}\n", app, e.what());
    return 1;
  }
}

std::string version_string(const char* app) { return fmt::format("{} {}", app, POWDERBED_VERSION); }

std::string version_json(const char* app) {
  bed::JsonWriter json;
  json.begin_object().value("program", app).value("version", POWDERBED_VERSION).end_object();
  return json.str();
}

std::string command_line(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (i) out += ' ';
    if (arg.find_first_of(" \t\"'") != std::string::npos) {
      out += '\'' + arg + '\'';
    } else {
      out += arg;
    }
  }
  return out;
}

}  // namespace powderbed::app
