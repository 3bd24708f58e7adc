#pragma once
// The bad-input check of the end-to-end tests (docs/architecture.md "Command-line programs": exit 2, one line naming the problem,
// no partial output): shared by the programs that write into a scratch folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <string>

#include "run_command.hpp"

namespace powderbed::test {

// Whether anything named out.* (the output, its sidecar or a temporary) is in `dir`.
inline bool left_output(const std::string& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().rfind("out.", 0) == 0) return true;
  return false;
}

// Exit 2, exactly one line on stderr containing every part, nothing on stdout, no out.* file.
inline void expect_refused(const CommandResult& r, const std::string& dir,
                           std::initializer_list<std::string> parts) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err_lines(), 1) << r.err;
  for (const auto& part : parts)
    EXPECT_NE(r.err.find(part), std::string::npos) << part << " in " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(left_output(dir));
}

}  // namespace powderbed::test
