// SPDX-License-Identifier: GPL-3.0-or-later
//
// What every text reader of pcl_cocone_io shares: the one-line reason of a failure,
// token and line scanning over the whole file in memory, strict number parsing and the
// reading of the file itself. Internal to the library (not installed).
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

namespace pcl {
namespace cocone {
namespace io_internal {

// The parsers throw this and the public functions turn it into the one-line reason;
// threading error codes through every token would bury the formats in bookkeeping.
struct FormatError
{
  std::string message;
};

/** Names the file in every message, so that a reason can be shown as it is. */
class Source
{
public:
  explicit Source(const std::string& name) : name_(name) {}

  [[noreturn]] void
  fail(const std::string& what) const
  {
    throw FormatError{name_ + ": " + what};
  }

  [[noreturn]] void
  failAt(std::size_t line, const std::string& what) const
  {
    fail("line " + std::to_string(line) + ": " + what);
  }

private:
  const std::string& name_;
};

/** A token quoted for a message: bounded and without control characters, so that a
 * binary file read as text cannot break the one-line promise. */
std::string excerpt(std::string_view token);

/** \a text on one line: line breaks become blanks. */
std::string oneLine(std::string text);

// ---------------------------------------------------------------------------------
// Text scanning without allocations: the files hold hundreds of thousands of tokens.

inline bool
isBlank(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

class TokenCursor
{
public:
  explicit TokenCursor(std::string_view line)
    : p_(line.data()), end_(line.data() + line.size())
  {}

  bool
  next(std::string_view& token)
  {
    while (p_ != end_ && isBlank(*p_))
      ++p_;
    if (p_ == end_)
      return false;
    const char* start = p_;
    while (p_ != end_ && !isBlank(*p_))
      ++p_;
    token = std::string_view(start, static_cast<std::size_t>(p_ - start));
    return true;
  }

private:
  const char* p_;
  const char* end_;
};

class LineCursor
{
public:
  LineCursor(const char* begin, const char* end, std::size_t first_line = 1)
    : p_(begin), end_(end), number_(first_line - 1)
  {}

  /** The next line without its '\n' ('\r' is left to the tokenizer, which treats it as
   * a blank); false at the end of the buffer. A last line without '\n' counts. */
  bool
  next(std::string_view& line)
  {
    if (p_ == end_)
      return false;
    const auto* newline = static_cast<const char*>(
        std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_)));
    const char* line_end = newline ? newline : end_;
    line = std::string_view(p_, static_cast<std::size_t>(line_end - p_));
    p_ = newline ? newline + 1 : end_;
    ++number_;
    return true;
  }

  /** The next line that holds a token, with a trailing `#` comment cut off when
   * \a comments is set. */
  bool
  nextContent(std::string_view& line, bool comments)
  {
    while (next(line)) {
      if (comments) {
        const std::size_t hash = line.find('#');
        if (hash != std::string_view::npos)
          line = line.substr(0, hash);
      }
      for (const char c : line)
        if (!isBlank(c))
          return true;
    }
    return false;
  }

  std::size_t
  number() const
  {
    return number_;
  }

  const char*
  position() const
  {
    return p_;
  }

  std::size_t
  remaining() const
  {
    return static_cast<std::size_t>(end_ - p_);
  }

private:
  const char* p_;
  const char* end_;
  std::size_t number_;
};

bool parseDouble(std::string_view token, double& value);

bool parseInteger(std::string_view token, long long& value);

/** The number \a token, or a failure naming it and \a line. */
double parseNumber(const Source& source, std::size_t line, std::string_view token);

/** The non-negative integer \a token, or a failure naming it and \a line. */
long long parseCount(const Source& source, std::size_t line, std::string_view token);

/** Reads the regular file \a path whole into \a contents; fails with the system's
 * reason (and refuses directories, FIFOs and devices, which would block or never
 * end). */
void readFile(const Source& source, const std::string& path, std::string& contents);

} // namespace io_internal
} // namespace cocone
} // namespace pcl
