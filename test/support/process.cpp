// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/process.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace pcl {
namespace cocone {
namespace test {

std::size_t
ToolRun::errLines() const
{
  return static_cast<std::size_t>(std::count(err.begin(), err.end(), '\n'));
}

std::string
shellQuote(const std::string& text)
{
  std::string quoted = "'";
  for (const char c : text)
    quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string
readText(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ToolRun
runTool(const std::string& launcher, const std::filesystem::path& program,
        const std::vector<std::string>& args, const std::filesystem::path& out,
        const std::filesystem::path& err)
{
  std::string command = launcher + shellQuote(program.string());
  for (const std::string& arg : args)
    command += " " + shellQuote(arg);
  command += " > " + shellQuote(out.string()) + " 2> " + shellQuote(err.string());
  const int status = std::system(command.c_str());
  ToolRun result;
  if (status != -1 && WIFEXITED(status))
    result.exit_code = WEXITSTATUS(status);
  result.out = readText(out);
  result.err = readText(err);
  return result;
}

void
expectOneLineFailure(const ToolRun& result, const std::string& expected)
{
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.errLines(), 1u) << "stderr: " << result.err;
  EXPECT_TRUE(!result.err.empty() && result.err.back() == '\n') << result.err;
  EXPECT_NE(result.err.find(expected), std::string::npos)
      << "stderr '" << result.err << "' should mention '" << expected << "'";
}

void
expectSuccess(const ToolRun& result)
{
  EXPECT_EQ(result.exit_code, 0)
      << "stdout: " << result.out << "\nstderr: " << result.err;
  EXPECT_EQ(result.err, "");
}

} // namespace test
} // namespace cocone
} // namespace pcl
