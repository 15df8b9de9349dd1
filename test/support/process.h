// SPDX-License-Identifier: GPL-3.0-or-later
// The command-line tools run as a user runs them: as a process through the shell, its
// stdout and stderr caught in files and read back, and checked against what every tool
// promises. Free of PCL, so that the test of the renderer needs nothing but GTest and
// zlib.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

/** What a tool run left behind. */
struct ToolRun
{
  int exit_code = -1; // -1 when the process did not exit normally
  std::string out;
  std::string err;

  std::size_t errLines() const;
};

/** \a text as one shell word: single-quoted, nothing in it interpreted. */
std::string shellQuote(const std::string& text);

/** The bytes of the file at \a path; empty when it cannot be read. */
std::string readText(const std::filesystem::path& path);

/** Runs \a program with \a args (each one argument, no shell interpretation), with
 * stdout and stderr written to \a out and \a err. \a launcher is shell text put before
 * the program (for instance "env -u DISPLAY "), empty for none. */
ToolRun runTool(const std::string& launcher, const std::filesystem::path& program,
                const std::vector<std::string>& args, const std::filesystem::path& out,
                const std::filesystem::path& err);

/** The failure every bad case must give: exit code 1 and exactly one line on stderr,
 * mentioning \a expected. */
void expectOneLineFailure(const ToolRun& result, const std::string& expected);

/** Exit code 0 and nothing on stderr. */
void expectSuccess(const ToolRun& result);

} // namespace test
} // namespace cocone
} // namespace pcl
