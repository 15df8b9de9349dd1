// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_scan.h"

#include <pcl/cocone/io/point_io.h>

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
  // Read straight into the string, in one call for a file that keeps its size (a
  // small buffer appended to the string copied every byte twice); a file that grows
  // meanwhile is read on to its end.
  const std::uintmax_t size = fs::file_size(path, ec);
  contents.assign(ec ? 0 : static_cast<std::size_t>(size), '\0');
  contents.resize(std::fread(&contents[0], 1, contents.size(), file.get()));
  if (ec || contents.size() == size) {
    char buffer[1 << 16];
    std::size_t read = 0;
    while ((read = std::fread(buffer, 1, sizeof(buffer), file.get())) > 0)
      contents.append(buffer, read);
  }
  if (std::ferror(file.get()))
    source.fail("read error: " + std::generic_category().message(errno));
}

} // namespace io_internal

std::string
utf8Escaped(std::string_view text)
{
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) {
      return static_cast<unsigned char>(text[k]);
    };
    const unsigned char lead = byte(i);
    // The length of the sequence \a lead starts and the range of its second byte
    // (RFC 3629, section 4), which excludes overlong forms, surrogates and code points
    // beyond U+10FFFF.
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xbf;
    if (lead < 0x80)
      length = 1;
    else if (lead >= 0xc2 && lead <= 0xdf)
      length = 2;
    else if (lead >= 0xe0 && lead <= 0xef) {
      length = 3;
      low = lead == 0xe0 ? 0xa0 : 0x80;
      high = lead == 0xed ? 0x9f : 0xbf;
    }
    else if (lead >= 0xf0 && lead <= 0xf4) {
      length = 4;
      low = lead == 0xf0 ? 0x90 : 0x80;
      high = lead == 0xf4 ? 0x8f : 0xbf;
    }
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const unsigned char b = byte(i + k);
      valid = k == 1 ? (b >= low && b <= high) : (b >= 0x80 && b <= 0xbf);
    }
    if (valid) {
      out.append(text.substr(i, length));
      i += length;
      continue;
    }
    constexpr char digits[] = "0123456789abcdef";
    out += "\\x";
    out += digits[lead >> 4];
    out += digits[lead & 0xf];
    ++i;
  }
  return out;
}

} // namespace cocone
} // namespace pcl
