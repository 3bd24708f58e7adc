#pragma once
// The two error kinds of docs/architecture.md "House style": every app's main maps them to exit 2 / 3.
#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace powderbed {

// Bad input: a file, option, field or scene value. The message is one line naming what is
// wrong (file/dataset/option), the value given and what is accepted.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A run that went non-finite or otherwise broke numerically; names the particle/node and step.
class NumericalError : public std::runtime_error {
 public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

// The scene check shared by the stages: throws "<field>: <value> is out of range (accepted:
// <accepted>)" unless `ok`.
inline void require_in_range(bool ok, const char* field, double value, const char* accepted) {
  if (ok) return;
  throw InputError(
      fmt::format("{}: {:g} is out of range (accepted: {})", field, value, accepted));
}

}  // namespace powderbed
