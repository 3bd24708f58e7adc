#pragma once
// What every program's main shares: error-to-exit-status mapping and version text
// (README "The programs": bad input exits 2 with one line, numerics 3).
#include <functional>
#include <string>

namespace powderbed::app {

// Runs `body`; InputError and option-parsing errors print "<app>: <message>" on stderr and
// return 2, NumericalError returns 3, anything else 1. Never lets an exception escape.
int run_app(const char* app, int argc, char** argv, const std::function<int()>& body);

// "<app> <version>", the created_by attribute of a bed.
std::string version_string(const char* app);
// {"program": "<app>", "version": "<version>"}: --version --json.
std::string version_json(const char* app);
// The command line as typed (arguments quoted where they contain spaces).
std::string command_line(int argc, char** argv);

}  // namespace powderbed::app
