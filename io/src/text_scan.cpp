// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_scan.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

namespace pcl {
namespace cocone {
namespace io_internal {

std::string
excerpt(std::string_view token)
{
  constexpr std::size_t max_length = 24;
  std::string out = "'";
  for (const char c : token.substr(0, max_length)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (token.size() > max_length)
    out += "...";
  return out + "'";
}

std::string
oneLine(std::string text)
{
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return text;
}

bool
parseDouble(std::string_view token, double& value)
{
  const char* first = token.data();
  const char* last = first + token.size();
  // from_chars takes no '+', which some writers put on exponents' mantissas anyway.
  if (first != last && *first == '+') {
    ++first;
    if (first != last && *first == '-')
      return false;
  }
  if (first == last)
    return false;
  auto result = std::from_chars(first, last, value);
  if (result.ec == std::errc::result_out_of_range && result.ptr == last) {
    // Subnormal or beyond double: long double's range takes it, and the cast gives the
    // value a text reader would expect (a denormal, 0 or infinity).
    long double wide = 0;
    result = std::from_chars(first, last, wide);
    if (result.ec == std::errc() && result.ptr == last) {
      value = static_cast<double>(wide);
      return true;
    }
    return false;
  }
  return result.ec == std::errc() && result.ptr == last;
}

bool
parseInteger(std::string_view token, long long& value)
{
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') {
    ++first;
    if (first != last && *first == '-')
      return false;
  }
  if (first == last)
    return false;
  const auto result = std::from_chars(first, last, value);
  return result.ec == std::errc() && result.ptr == last;
}

double
parseNumber(const Source& source, std::size_t line, std::string_view token)
{
  double value = 0;
  if (!parseDouble(token, value))
    source.failAt(line, excerpt(token) + " is not a number");
  return value;
}

long long
parseCount(const Source& source, std::size_t line, std::string_view token)
{
  long long value = 0;
  if (!parseInteger(token, value) || value < 0)
    source.failAt(line, excerpt(token) + " is not a count (a non-negative integer)");
  return value;
}

// Whole-file reading: the files are a few megabytes, and parsing from memory is both
// simpler and faster than stream extraction.
void
readFile(const Source& source, const std::string& path, std::string& contents)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found)
    source.fail("no such file");
  if (ec)
    source.fail("cannot access: " + ec.message());
  if (fs::is_directory(status))
    source.fail("is a directory, not a file");
  // A FIFO or a device would block or never end.
  if (!fs::is_regular_file(status))
    source.fail("not a regular file");

  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(
      std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file)
    source.fail("cannot open: " + std::generic_category().message(errno));
  const std::uintmax_t size = fs::file_size(path, ec);
  contents.clear();
  if (!ec)
    contents.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof(buffer), file.get())) > 0)
    contents.append(buffer, read);
  if (std::ferror(file.get()))
    source.fail("read error: " + std::generic_category().message(errno));
}

} // namespace io_internal
} // namespace cocone
} // namespace pcl
