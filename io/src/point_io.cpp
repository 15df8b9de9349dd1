// SPDX-License-Identifier: GPL-3.0-or-later
//
// PLY, OBJ, OFF and the column formats are parsed here rather than with PCL's readers:
// pcl::PLYReader prints a warning for every face element, renames nx/ny/nz to
// normal_x/y/z, turns a scan's range_grid into an organized cloud of a different size
// (bun000: 512 x 400 instead of 40256 vertices) and takes ~0.3 s on a 3 MB ascii file.
// PCD goes to PCL, but only after the file has been checked here: PCL prints to stderr
// on every problem, accepts ascii lines with missing or non-numeric values, and crashes
// on an empty or non-PCD file.
#include <pcl/cocone/io/point_io.h>

#include <pcl/common/io.h>
#include <pcl/io/lzf.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <memory>
#include <new>
#include <string_view>
#include <system_error>

namespace pcl {
namespace cocone {

namespace {

using Field = pcl::PCLPointField;

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

// ---------------------------------------------------------------------------------
// Values and cloud layout

/** double to float without the undefined behaviour of an out-of-range conversion. */
float
toFloat(double value)
{
  constexpr double max = std::numeric_limits<float>::max();
  if (value > max)
    return std::numeric_limits<float>::infinity();
  if (value < -max)
    return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

template <typename T>
T
loadScalar(const std::uint8_t* source, bool swap)
{
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, source, sizeof(T));
  if (swap)
    std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

double
loadValue(const std::uint8_t* source, std::uint8_t datatype, bool swap)
{
  switch (datatype) {
  case Field::INT8:
    return loadScalar<std::int8_t>(source, swap);
  case Field::UINT8:
    return loadScalar<std::uint8_t>(source, swap);
  case Field::INT16:
    return loadScalar<std::int16_t>(source, swap);
  case Field::UINT16:
    return loadScalar<std::uint16_t>(source, swap);
  case Field::INT32:
    return loadScalar<std::int32_t>(source, swap);
  case Field::UINT32:
    return loadScalar<std::uint32_t>(source, swap);
  case Field::INT64:
    return static_cast<double>(loadScalar<std::int64_t>(source, swap));
  case Field::UINT64:
    return static_cast<double>(loadScalar<std::uint64_t>(source, swap));
  case Field::FLOAT32:
    return loadScalar<float>(source, swap);
  case Field::FLOAT64:
    return loadScalar<double>(source, swap);
  case Field::BOOL:
    return loadScalar<std::uint8_t>(source, swap) != 0 ? 1.0 : 0.0;
  }
  return 0;
}

template <typename T>
void
storeScalar(std::uint8_t* target, T value)
{
  std::memcpy(target, &value, sizeof(T));
}

/** Only called with values that fit the type (see fitsDatatype). */
void
storeValue(std::uint8_t* target, std::uint8_t datatype, double value)
{
  switch (datatype) {
  case Field::INT8:
    return storeScalar(target, static_cast<std::int8_t>(value));
  case Field::UINT8:
    return storeScalar(target, static_cast<std::uint8_t>(value));
  case Field::INT16:
    return storeScalar(target, static_cast<std::int16_t>(value));
  case Field::UINT16:
    return storeScalar(target, static_cast<std::uint16_t>(value));
  case Field::INT32:
    return storeScalar(target, static_cast<std::int32_t>(value));
  case Field::UINT32:
    return storeScalar(target, static_cast<std::uint32_t>(value));
  case Field::FLOAT32:
    return storeScalar(target, toFloat(value));
  case Field::FLOAT64:
    return storeScalar(target, value);
  }
}

template <typename T>
bool
fitsRange(double value)
{
  return value >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
         value <= static_cast<double>(std::numeric_limits<T>::max());
}

bool
fitsDatatype(double value, std::uint8_t datatype)
{
  switch (datatype) {
  case Field::INT8:
    return fitsRange<std::int8_t>(value);
  case Field::UINT8:
    return fitsRange<std::uint8_t>(value);
  case Field::INT16:
    return fitsRange<std::int16_t>(value);
  case Field::UINT16:
    return fitsRange<std::uint16_t>(value);
  case Field::INT32:
    return fitsRange<std::int32_t>(value);
  case Field::UINT32:
    return fitsRange<std::uint32_t>(value);
  default:
    return true; // floats take anything, NaN included
  }
}

/** Appends a single-valued field at the next offset aligned to its size, so that code
 * reading it through a pointer of its type sees aligned data. */
void
appendField(pcl::PCLPointCloud2& cloud,
            const std::string& name,
            std::uint8_t datatype,
            std::uint32_t count = 1)
{
  const auto size = static_cast<std::uint32_t>(pcl::getFieldSize(datatype));
  Field field;
  field.name = name;
  field.datatype = datatype;
  field.count = count;
  field.offset = (cloud.point_step + size - 1) / size * size;
  cloud.fields.push_back(field);
  cloud.point_step = field.offset + size * count;
}

/** Pads the point to the alignment of its widest field and sizes the cloud. */
void
finishLayout(pcl::PCLPointCloud2& cloud, std::size_t points)
{
  std::uint32_t alignment = 1;
  for (const Field& field : cloud.fields)
    alignment = std::max<std::uint32_t>(alignment, pcl::getFieldSize(field.datatype));
  cloud.point_step = (cloud.point_step + alignment - 1) / alignment * alignment;
  cloud.width = static_cast<std::uint32_t>(points);
  cloud.height = 1;
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_bigendian = false;
  cloud.data.assign(static_cast<std::size_t>(cloud.point_step) * points, 0);
}

int
fieldIndex(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  for (std::size_t i = 0; i < cloud.fields.size(); ++i)
    if (cloud.fields[i].name == name)
      return static_cast<int>(i);
  return -1;
}

/** is_dense as PCL means it: every point has finite x, y and z (float fields). */
bool
allFinite(const pcl::PCLPointCloud2& cloud)
{
  const std::uint32_t offsets[3] = {cloud.fields[fieldIndex(cloud, "x")].offset,
                                    cloud.fields[fieldIndex(cloud, "y")].offset,
                                    cloud.fields[fieldIndex(cloud, "z")].offset};
  const std::size_t points = static_cast<std::size_t>(cloud.width) * cloud.height;
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    for (const std::uint32_t offset : offsets) {
      float value;
      std::memcpy(&value, point + offset, sizeof(float));
      if (!std::isfinite(value))
        return false;
    }
  }
  return true;
}

void
makeXyzCloud(const std::vector<float>& xyz, pcl::PCLPointCloud2& cloud)
{
  cloud = pcl::PCLPointCloud2();
  appendField(cloud, "x", Field::FLOAT32);
  appendField(cloud, "y", Field::FLOAT32);
  appendField(cloud, "z", Field::FLOAT32);
  finishLayout(cloud, xyz.size() / 3);
  if (!xyz.empty())
    std::memcpy(cloud.data.data(), xyz.data(), xyz.size() * sizeof(float));
  cloud.is_dense = allFinite(cloud);
}

// ---------------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------------
// Column formats (.xyz, .pts, .txt)

void
parseColumns(const Source& source, const std::string& text, std::vector<float>& xyz)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  while (lines.nextContent(line, true)) {
    TokenCursor tokens(line);
    tokens.next(token);
    // Hoppe's .pts: "p x y z" for points, "n nx ny nz" for the normal of the last one.
    if (token == "n")
      continue;
    bool have = token != "p" || tokens.next(token);
    for (int k = 0; k < 3; ++k) {
      if (!have)
        source.failAt(lines.number(),
                      "expected 3 coordinates, found " + std::to_string(k));
      xyz.push_back(toFloat(parseNumber(source, lines.number(), token)));
      have = tokens.next(token);
    }
  }
}

// ---------------------------------------------------------------------------------
// Wavefront OBJ

/** The position index of an OBJ face corner ("v", "v/vt", "v//vn", "v/vt/vn"),
 * resolved to 0-based; negative indices count back from the last vertex read. */
long long
objCorner(const Source& source,
          std::size_t line,
          std::string_view token,
          std::size_t vertices_so_far)
{
  const std::string_view position = token.substr(0, token.find('/'));
  long long index = 0;
  if (!parseInteger(position, index) || index == 0)
    source.failAt(line, excerpt(token) + " is not a vertex reference");
  if (index > 0)
    return index - 1;
  index += static_cast<long long>(vertices_so_far);
  if (index < 0)
    source.failAt(line, "relative vertex reference " + excerpt(token) +
                            " points before the first vertex");
  return index;
}

void
parseObj(const Source& source,
         const std::string& text,
         std::vector<float>& xyz,
         std::vector<pcl::Vertices>* faces)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  // Positive references may name vertices defined later, so the range is checked once
  // all are known; this remembers the worst one and where it was.
  long long max_index = -1;
  std::size_t max_line = 0;
  while (lines.nextContent(line, true)) {
    TokenCursor tokens(line);
    tokens.next(token);
    if (token == "v") {
      for (int k = 0; k < 3; ++k) {
        if (!tokens.next(token))
          source.failAt(lines.number(),
                        "expected 3 coordinates, found " + std::to_string(k));
        xyz.push_back(toFloat(parseNumber(source, lines.number(), token)));
      }
    }
    else if (token == "f" && faces) {
      pcl::Vertices face;
      while (tokens.next(token)) {
        const long long index =
            objCorner(source, lines.number(), token, xyz.size() / 3);
        if (index > max_index) {
          max_index = index;
          max_line = lines.number();
        }
        if (index > std::numeric_limits<pcl::index_t>::max())
          source.failAt(lines.number(),
                        "vertex reference " + excerpt(token) + " too large");
        face.vertices.push_back(static_cast<pcl::index_t>(index));
      }
      if (face.vertices.size() < 3)
        source.failAt(lines.number(), "a face needs at least 3 vertices");
      faces->push_back(std::move(face));
    }
    // vt, vn, g, o, s, usemtl, mtllib, l, ...: not samples, not faces.
  }
  if (max_index >= static_cast<long long>(xyz.size() / 3))
    source.failAt(max_line, "vertex " + std::to_string(max_index + 1) +
                                " referenced, but the file has " +
                                std::to_string(xyz.size() / 3));
}

// ---------------------------------------------------------------------------------
// Geomview OFF

void
parseOff(const Source& source,
         const std::string& text,
         std::vector<float>& xyz,
         std::vector<pcl::Vertices>* faces)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  if (!lines.nextContent(line, true))
    source.fail("empty file, no OFF header");
  TokenCursor tokens(line);
  tokens.next(token);
  long long first_count = 0;
  if (token.size() >= 3 && token.substr(token.size() - 3) == "OFF") {
    // [ST][C][N][4][n]OFF: texture coordinates, colours and normals follow x y z on the
    // vertex lines and are ignored; 4D and n-dimensional vertices are not points.
    std::string_view prefix = token.substr(0, token.size() - 3);
    for (const std::string_view part : {"ST", "C", "N"})
      if (prefix.substr(0, part.size()) == part)
        prefix.remove_prefix(part.size());
    if (!prefix.empty())
      source.failAt(lines.number(),
                    excerpt(token) +
                        " header: only 3D OFF (with ST, C, N) is supported");
    if (tokens.next(token)) {
      if (token == "BINARY")
        source.failAt(lines.number(), "binary OFF is not supported");
    }
    else {
      if (!lines.nextContent(line, true))
        source.fail("file ends after the OFF header, no counts line");
      tokens = TokenCursor(line);
      tokens.next(token);
    }
  }
  else if (!parseInteger(token, first_count)) {
    source.failAt(lines.number(), "not an OFF file (no OFF header)");
  }

  // token is the first of "vertices faces [edges]".
  const long long vertex_count = parseCount(source, lines.number(), token);
  if (!tokens.next(token))
    source.failAt(lines.number(), "expected the vertex and face counts");
  const long long face_count = parseCount(source, lines.number(), token);
  if (vertex_count > std::numeric_limits<pcl::index_t>::max())
    source.failAt(lines.number(), "too many vertices");

  xyz.reserve(static_cast<std::size_t>(
      std::min<long long>(vertex_count, static_cast<long long>(text.size() / 6))) * 3);
  for (long long i = 0; i < vertex_count; ++i) {
    if (!lines.nextContent(line, true))
      source.fail("file ends after " + std::to_string(i) + " of " +
                  std::to_string(vertex_count) + " vertices");
    tokens = TokenCursor(line);
    for (int k = 0; k < 3; ++k) {
      if (!tokens.next(token))
        source.failAt(lines.number(),
                      "expected 3 coordinates, found " + std::to_string(k));
      xyz.push_back(toFloat(parseNumber(source, lines.number(), token)));
    }
  }
  if (!faces)
    return;

  for (long long i = 0; i < face_count; ++i) {
    if (!lines.nextContent(line, true))
      source.fail("file ends after " + std::to_string(i) + " of " +
                  std::to_string(face_count) + " faces");
    tokens = TokenCursor(line);
    tokens.next(token);
    const long long size = parseCount(source, lines.number(), token);
    if (size < 3)
      source.failAt(lines.number(), "a face needs at least 3 vertices");
    pcl::Vertices face;
    face.vertices.reserve(static_cast<std::size_t>(std::min<long long>(size, 64)));
    for (long long k = 0; k < size; ++k) {
      if (!tokens.next(token))
        source.failAt(lines.number(), "face has fewer vertex indices than its count " +
                                          std::to_string(size));
      long long index = 0;
      if (!parseInteger(token, index))
        source.failAt(lines.number(), excerpt(token) + " is not a vertex index");
      if (index < 0 || index >= vertex_count)
        source.failAt(lines.number(), "vertex index " + std::to_string(index) +
                                          " out of range (the file has " +
                                          std::to_string(vertex_count) + " vertices)");
      face.vertices.push_back(static_cast<pcl::index_t>(index));
    }
    // Anything after the indices is the face's colour.
    faces->push_back(std::move(face));
  }
}

// ---------------------------------------------------------------------------------
// PLY

struct PlyProperty
{
  std::string name;
  std::uint8_t type = 0;       // as a PCLPointField datatype
  std::uint8_t count_type = 0; // the list length's type; 0 for a scalar property
};

struct PlyElement
{
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader
{
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0; // first byte after the end_header line
  std::size_t body_line = 0;   // its line number, for ascii messages
};

std::uint8_t
plyType(std::string_view name)
{
  if (name == "char" || name == "int8")
    return Field::INT8;
  if (name == "uchar" || name == "uint8")
    return Field::UINT8;
  if (name == "short" || name == "int16")
    return Field::INT16;
  if (name == "ushort" || name == "uint16")
    return Field::UINT16;
  if (name == "int" || name == "int32")
    return Field::INT32;
  if (name == "uint" || name == "uint32")
    return Field::UINT32;
  if (name == "float" || name == "float32")
    return Field::FLOAT32;
  if (name == "double" || name == "float64")
    return Field::FLOAT64;
  return 0;
}

bool
isIntegerType(std::uint8_t type)
{
  return type != Field::FLOAT32 && type != Field::FLOAT64;
}

PlyHeader
parsePlyHeader(const Source& source, const std::string& text)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  if (!lines.next(line) || !TokenCursor(line).next(token) || token != "ply")
    source.fail("not a PLY file (the first line is not 'ply')");

  PlyHeader header;
  bool have_format = false;
  for (;;) {
    if (!lines.next(line))
      source.fail("the PLY header has no end_header line");
    TokenCursor tokens(line);
    if (!tokens.next(token) || token == "comment" || token == "obj_info")
      continue;
    if (token == "end_header")
      break;
    const std::size_t number = lines.number();
    if (token == "format") {
      tokens.next(token);
      if (token == "ascii")
        header.format = PlyFormat::ascii;
      else if (token == "binary_little_endian")
        header.format = PlyFormat::binary_little_endian;
      else if (token == "binary_big_endian")
        header.format = PlyFormat::binary_big_endian;
      else
        source.failAt(number, "unknown PLY format " + excerpt(token));
      have_format = true;
    }
    else if (token == "element") {
      PlyElement element;
      if (!tokens.next(token))
        source.failAt(number, "element without a name");
      element.name = std::string(token);
      if (!tokens.next(token))
        source.failAt(number, "element " + excerpt(element.name) + " without a count");
      const long long count = parseCount(source, number, token);
      if (count > std::numeric_limits<pcl::index_t>::max())
        source.failAt(number, "element " + excerpt(element.name) + " too large");
      element.count = static_cast<std::size_t>(count);
      header.elements.push_back(std::move(element));
    }
    else if (token == "property") {
      if (header.elements.empty())
        source.failAt(number, "property before any element");
      PlyProperty property;
      tokens.next(token);
      if (token == "list") {
        tokens.next(token);
        property.count_type = plyType(token);
        if (property.count_type == 0 || !isIntegerType(property.count_type))
          source.failAt(number, "list length type " + excerpt(token) +
                                    " is not an integer type");
        tokens.next(token);
      }
      property.type = plyType(token);
      if (property.type == 0)
        source.failAt(number, "unknown property type " + excerpt(token));
      if (!tokens.next(token))
        source.failAt(number, "property without a name");
      property.name = std::string(token);
      auto& properties = header.elements.back().properties;
      for (const PlyProperty& other : properties)
        if (other.name == property.name)
          source.failAt(number, "duplicate property " + excerpt(property.name));
      properties.push_back(std::move(property));
    }
    else {
      source.failAt(number, "unknown PLY header line starting with " + excerpt(token));
    }
  }
  if (!have_format)
    source.fail("the PLY header has no format line");
  header.body_offset = static_cast<std::size_t>(lines.position() - text.data());
  header.body_line = lines.number() + 1;
  return header;
}

/** Walks the body of an ascii PLY file: one element instance per line. */
class PlyAsciiBody
{
public:
  PlyAsciiBody(const Source& source, const std::string& text, const PlyHeader& header)
  : source_(source)
  , lines_(text.data() + header.body_offset, text.data() + text.size(),
           header.body_line)
  {}

  void
  skip(const PlyElement& element)
  {
    std::string_view line;
    for (std::size_t i = 0; i < element.count; ++i)
      if (!lines_.nextContent(line, false))
        endedEarly(element, i);
  }

  /** Each scalar property k goes to field targets[k] of the cloud. */
  void
  readVertices(const PlyElement& element,
               const std::vector<int>& targets,
               pcl::PCLPointCloud2& cloud)
  {
    std::string_view line;
    std::string_view token;
    for (std::size_t i = 0; i < element.count; ++i) {
      if (!lines_.nextContent(line, false))
        endedEarly(element, i);
      TokenCursor tokens(line);
      if (cloud.data.size() < (i + 1) * cloud.point_step)
        cloud.data.resize((i + 1) * cloud.point_step);
      std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& property = element.properties[k];
        if (property.count_type != 0) {
          skipList(tokens, element);
          continue;
        }
        const Field& field = cloud.fields[targets[k]];
        const double value =
            parseNumber(source_, lines_.number(), nextToken(tokens, element));
        if (!fitsDatatype(value, property.type))
          source_.failAt(lines_.number(), "value of " + excerpt(property.name) +
                                              " out of range for its type");
        storeValue(point + field.offset, field.datatype, value);
      }
      checkEnd(tokens, element);
    }
  }

  void
  readFaces(const PlyElement& element,
            std::size_t list_property,
            std::size_t vertex_count,
            std::vector<pcl::Vertices>& faces)
  {
    std::string_view line;
    // A face line takes at least 8 bytes ("3 0 1 2\n"); the header may claim more.
    faces.reserve(faces.size() + std::min(element.count, lines_.remaining() / 8));
    for (std::size_t i = 0; i < element.count; ++i) {
      if (!lines_.nextContent(line, false))
        endedEarly(element, i);
      TokenCursor tokens(line);
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        if (k != list_property) {
          if (element.properties[k].count_type != 0)
            skipList(tokens, element);
          else
            parseNumber(source_, lines_.number(), nextToken(tokens, element));
          continue;
        }
        const long long size =
            parseCount(source_, lines_.number(), nextToken(tokens, element));
        if (size < 3)
          source_.failAt(lines_.number(), "a face needs at least 3 vertices");
        pcl::Vertices face;
        face.vertices.reserve(static_cast<std::size_t>(std::min<long long>(size, 64)));
        for (long long j = 0; j < size; ++j) {
          const std::string_view token = nextToken(tokens, element);
          long long index = 0;
          if (!parseInteger(token, index))
            source_.failAt(lines_.number(), excerpt(token) + " is not a vertex index");
          if (index < 0 || static_cast<unsigned long long>(index) >= vertex_count)
            source_.failAt(lines_.number(), "vertex index " + std::to_string(index) +
                                                " out of range (the file has " +
                                                std::to_string(vertex_count) +
                                                " vertices)");
          face.vertices.push_back(static_cast<pcl::index_t>(index));
        }
        faces.push_back(std::move(face));
      }
      checkEnd(tokens, element);
    }
  }

private:
  [[noreturn]] void
  endedEarly(const PlyElement& element, std::size_t read)
  {
    source_.fail("file ends after " + std::to_string(read) + " of " +
                 std::to_string(element.count) + " " + excerpt(element.name) +
                 " lines");
  }

  std::string_view
  nextToken(TokenCursor& tokens, const PlyElement& element)
  {
    std::string_view token;
    if (!tokens.next(token))
      source_.failAt(lines_.number(), "fewer values than the header declares for " +
                                          excerpt(element.name));
    return token;
  }

  void
  skipList(TokenCursor& tokens, const PlyElement& element)
  {
    const long long size =
        parseCount(source_, lines_.number(), nextToken(tokens, element));
    for (long long j = 0; j < size; ++j)
      nextToken(tokens, element);
  }

  void
  checkEnd(TokenCursor& tokens, const PlyElement& element)
  {
    std::string_view token;
    if (tokens.next(token))
      source_.failAt(lines_.number(), "more values than the header declares for " +
                                          excerpt(element.name));
  }

  const Source& source_;
  LineCursor lines_;
};

/** Walks the body of a binary PLY file, checking every read against its end. */
class PlyBinaryBody
{
public:
  PlyBinaryBody(const Source& source, const std::string& text, const PlyHeader& header)
  : source_(source)
  , p_(reinterpret_cast<const std::uint8_t*>(text.data()) + header.body_offset)
  , end_(reinterpret_cast<const std::uint8_t*>(text.data()) + text.size())
  {
    const std::uint16_t probe = 1;
    std::uint8_t first_byte;
    std::memcpy(&first_byte, &probe, 1);
    const bool host_little = first_byte == 1;
    swap_ = host_little != (header.format == PlyFormat::binary_little_endian);
  }

  void
  skip(const PlyElement& element)
  {
    std::size_t size = 0;
    bool fixed = true;
    for (const PlyProperty& property : element.properties) {
      fixed = fixed && property.count_type == 0;
      size += pcl::getFieldSize(property.type);
    }
    if (fixed) {
      if (size > 0 && element.count > remaining() / size)
        truncated(element, remaining() / size);
      p_ += element.count * size;
      return;
    }
    for (std::size_t i = 0; i < element.count; ++i)
      for (const PlyProperty& property : element.properties)
        skipProperty(property, element, i);
  }

  void
  readVertices(const PlyElement& element,
               const std::vector<int>& targets,
               pcl::PCLPointCloud2& cloud)
  {
    for (std::size_t i = 0; i < element.count; ++i) {
      std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& property = element.properties[k];
        if (property.count_type != 0) {
          skipProperty(property, element, i);
          continue;
        }
        const Field& field = cloud.fields[targets[k]];
        const std::size_t size = pcl::getFieldSize(property.type);
        need(size, element, i);
        if (field.datatype == property.type) {
          std::memcpy(point + field.offset, p_, size);
          if (swap_)
            std::reverse(point + field.offset, point + field.offset + size);
        }
        else {
          storeValue(point + field.offset, field.datatype,
                     loadValue(p_, property.type, swap_));
        }
        p_ += size;
      }
    }
  }

  void
  readFaces(const PlyElement& element,
            std::size_t list_property,
            std::size_t vertex_count,
            std::vector<pcl::Vertices>& faces)
  {
    faces.reserve(faces.size() + std::min(element.count, remaining() / 4));
    for (std::size_t i = 0; i < element.count; ++i) {
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& property = element.properties[k];
        if (k != list_property) {
          skipProperty(property, element, i);
          continue;
        }
        const std::size_t size = listSize(property, element, i);
        if (size < 3)
          source_.fail(excerpt(element.name) + " " + std::to_string(i) +
                       ": a face needs at least 3 vertices");
        const std::size_t index_size = pcl::getFieldSize(property.type);
        need(size * index_size, element, i);
        pcl::Vertices face;
        face.vertices.resize(size);
        for (std::size_t j = 0; j < size; ++j, p_ += index_size) {
          const double index = loadValue(p_, property.type, swap_);
          if (!(index >= 0 && index < static_cast<double>(vertex_count)))
            source_.fail(excerpt(element.name) + " " + std::to_string(i) +
                         ": vertex index " +
                         std::to_string(static_cast<long long>(index)) +
                         " out of range (the file has " + std::to_string(vertex_count) +
                         " vertices)");
          face.vertices[j] = static_cast<pcl::index_t>(index);
        }
        faces.push_back(std::move(face));
      }
    }
  }

private:
  std::size_t
  remaining() const
  {
    return static_cast<std::size_t>(end_ - p_);
  }

  [[noreturn]] void
  truncated(const PlyElement& element, std::size_t item)
  {
    source_.fail("truncated: the binary data ends in " + excerpt(element.name) + " " +
                 std::to_string(item + 1) + " of " + std::to_string(element.count));
  }

  void
  need(std::size_t bytes, const PlyElement& element, std::size_t item)
  {
    if (bytes > remaining())
      truncated(element, item);
  }

  std::size_t
  listSize(const PlyProperty& property, const PlyElement& element, std::size_t item)
  {
    const std::size_t size = pcl::getFieldSize(property.count_type);
    need(size, element, item);
    const double count = loadValue(p_, property.count_type, swap_);
    p_ += size;
    if (count < 0)
      source_.fail(excerpt(element.name) + " " + std::to_string(item) +
                   ": negative list length");
    return static_cast<std::size_t>(count);
  }

  void
  skipProperty(const PlyProperty& property, const PlyElement& element, std::size_t item)
  {
    const std::size_t size = pcl::getFieldSize(property.type);
    const std::size_t count =
        property.count_type != 0 ? listSize(property, element, item) : 1;
    if (count > remaining() / size)
      truncated(element, item);
    p_ += count * size;
  }

  const Source& source_;
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  bool swap_ = false;
};

const PlyElement*
findElement(const PlyHeader& header, const std::string& name)
{
  for (const PlyElement& element : header.elements)
    if (element.name == name)
      return &element;
  return nullptr;
}

/** Reads the elements up to \a wanted, skipping the others, then calls
 * \a read(body). The elements after \a wanted are never looked at. */
template <typename Body, typename Read>
void
readPlyElement(Body& body, const PlyHeader& header, const PlyElement* wanted, Read read)
{
  for (const PlyElement& element : header.elements) {
    if (&element == wanted) {
      read(body);
      return;
    }
    body.skip(element);
  }
}

template <typename Read>
void
walkPly(const Source& source,
        const std::string& text,
        const PlyHeader& header,
        const PlyElement* wanted,
        Read read)
{
  if (header.format == PlyFormat::ascii) {
    PlyAsciiBody body(source, text, header);
    readPlyElement(body, header, wanted, read);
  }
  else {
    PlyBinaryBody body(source, text, header);
    readPlyElement(body, header, wanted, read);
  }
}

void
readPlyVertices(const Source& source, const std::string& text,
                pcl::PCLPointCloud2& cloud)
{
  const PlyHeader header = parsePlyHeader(source, text);
  const PlyElement* vertex = findElement(header, "vertex");
  if (!vertex)
    source.fail("no vertex element in the PLY header");
  if (vertex->count == 0)
    source.fail("no points (the vertex element is empty)");

  cloud = pcl::PCLPointCloud2();
  std::vector<int> targets(vertex->properties.size(), -1);
  for (std::size_t k = 0; k < vertex->properties.size(); ++k) {
    const PlyProperty& property = vertex->properties[k];
    const bool coordinate =
        property.name == "x" || property.name == "y" || property.name == "z";
    if (property.count_type != 0) {
      if (coordinate)
        source.fail("vertex property " + excerpt(property.name) + " is a list");
      continue; // a list has no place in a fixed-size point
    }
    targets[k] = static_cast<int>(cloud.fields.size());
    // The library works on float coordinates whatever precision the file has.
    appendField(cloud, property.name,
                coordinate ? static_cast<std::uint8_t>(Field::FLOAT32) : property.type);
  }
  for (const char* name : {"x", "y", "z"})
    if (fieldIndex(cloud, name) < 0)
      source.fail(std::string("the vertex element has no property '") + name + "'");

  // A header can claim more vertices than the file holds: allocate no more than the
  // file has room for.
  const std::size_t body_size = text.size() - header.body_offset;
  std::size_t room = vertex->count;
  if (header.format != PlyFormat::ascii) {
    std::size_t bytes = 0;
    for (const PlyProperty& property : vertex->properties)
      bytes += pcl::getFieldSize(property.count_type != 0 ? property.count_type
                                                          : property.type);
    if (bytes > 0 && vertex->count > body_size / bytes)
      source.fail("truncated: the file is too short for " +
                  std::to_string(vertex->count) + " vertices");
  }
  else {
    // Each value takes a character and a separator; a short file then fails in the
    // reader, which can say on which line.
    room = std::min(room, (body_size + 1) / (2 * vertex->properties.size()));
  }
  finishLayout(cloud, room);
  walkPly(source, text, header, vertex, [&](auto& body) {
    body.readVertices(*vertex, targets, cloud);
  });
  cloud.width = static_cast<std::uint32_t>(vertex->count);
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = allFinite(cloud);
}

void
readPlyFaces(const Source& source,
             const std::string& text,
             std::vector<pcl::Vertices>& faces)
{
  const PlyHeader header = parsePlyHeader(source, text);
  const PlyElement* face = findElement(header, "face");
  const PlyElement* vertex = findElement(header, "vertex");
  if (!face || face->count == 0) {
    // No faces to read, but a file cut short in its vertices is still a broken file.
    if (vertex)
      walkPly(source, text, header, vertex, [&](auto& body) { body.skip(*vertex); });
    return;
  }
  const std::size_t vertex_count = vertex ? vertex->count : 0;
  std::size_t list_property = face->properties.size();
  for (std::size_t k = 0; k < face->properties.size(); ++k) {
    const PlyProperty& property = face->properties[k];
    if (property.count_type != 0 &&
        (property.name == "vertex_indices" || property.name == "vertex_index"))
      list_property = k;
  }
  if (list_property == face->properties.size())
    source.fail("the face element has no vertex_indices list");
  if (!isIntegerType(face->properties[list_property].type))
    source.fail("the face vertex indices are not integers");
  walkPly(source, text, header, face, [&](auto& body) {
    body.readFaces(*face, list_property, vertex_count, faces);
  });
}

// ---------------------------------------------------------------------------------
// PCD

/** Whether PCL's tokenizer (blanks, tabs and carriage returns) and this file's, which
 * also splits at \\v and \\f, could see different tokens; no PCD holds such bytes. */
bool
hasControlCharacter(std::string_view line)
{
  return std::any_of(line.begin(), line.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r';
  });
}

// The header keywords in the order the format prescribes.
constexpr std::string_view pcd_keywords[] = {"VERSION", "FIELDS", "SIZE",
                                             "TYPE",    "COUNT",  "WIDTH",
                                             "HEIGHT",  "VIEWPOINT", "POINTS",
                                             "DATA"};

/** Checks what PCL's reader would complain about (on stderr, or by crashing, as it does
 * on an empty file), plus what it silently gets wrong in ascii data. Stricter than PCL
 * where PCL reads on with a warning: the keywords must come in the prescribed order,
 * once each, and WIDTH, HEIGHT and POINTS must be there. */
void
checkPcd(const Source& source, const std::string& text)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  std::vector<std::string> names;
  std::vector<long long> sizes;
  std::vector<char> types;
  std::vector<long long> counts;
  long long width = -1;
  long long height = -1;
  long long points = -1;
  std::string data;
  double value = 0;
  int last_rank = -1;
  while (data.empty()) {
    if (!lines.next(line))
      source.fail("not a PCD file (no DATA line)");
    const std::size_t number = lines.number();
    if (line.empty())
      continue; // the only kind of blank line PCL passes over in a header
    if (hasControlCharacter(line))
      source.failAt(number, "control character in the PCD header");
    // PCL would take a blank-only line for the end of the header and read its fields
    // one off after a leading blank.
    if (isBlank(line.front()))
      source.failAt(number, "PCD header line starts with a blank");
    TokenCursor tokens(line);
    tokens.next(token);
    if (token.front() == '#')
      continue;
    const std::string keyword(token == "COLUMNS" ? "FIELDS" : token);
    const auto rank = static_cast<int>(
        std::find(std::begin(pcd_keywords), std::end(pcd_keywords), keyword) -
        std::begin(pcd_keywords));
    if (rank == static_cast<int>(std::size(pcd_keywords)))
      source.failAt(number, "not a PCD header line: " + excerpt(keyword));
    if (rank <= last_rank)
      source.failAt(number, keyword + " repeated or out of order");
    last_rank = rank;

    if (keyword == "VERSION")
      continue;
    if (keyword == "VIEWPOINT") {
      for (int k = 0; k < 7; ++k)
        if (!tokens.next(token) || !parseDouble(token, value))
          source.failAt(number, "VIEWPOINT needs 7 numbers");
    }
    else if (keyword == "FIELDS") {
      while (tokens.next(token))
        names.emplace_back(token);
    }
    else if (keyword == "SIZE" || keyword == "COUNT") {
      auto& values = keyword == "SIZE" ? sizes : counts;
      while (tokens.next(token))
        values.push_back(parseCount(source, number, token));
      if (values.size() != names.size())
        source.failAt(number, keyword + " has " + std::to_string(values.size()) +
                                  " values for " + std::to_string(names.size()) +
                                  " FIELDS");
    }
    else if (keyword == "TYPE") {
      while (tokens.next(token))
        types.push_back(token.size() == 1 ? token[0] : '?');
      if (types.size() != names.size())
        source.failAt(number, "TYPE has " + std::to_string(types.size()) +
                                  " values for " + std::to_string(names.size()) +
                                  " FIELDS");
    }
    else if (keyword == "WIDTH" || keyword == "HEIGHT" || keyword == "POINTS") {
      if (!tokens.next(token))
        source.failAt(number, keyword + " without a value");
      const long long count = parseCount(source, number, token);
      if (count > std::numeric_limits<std::int32_t>::max())
        source.failAt(number, keyword + " too large");
      (keyword == "WIDTH" ? width : keyword == "HEIGHT" ? height : points) = count;
    }
    else { // DATA
      if (!tokens.next(token) ||
          (token != "ascii" && token != "binary" && token != "binary_compressed"))
        source.failAt(number, "unknown PCD data kind");
      data = std::string(token);
    }
  }

  // PCL goes on reading header lines after DATA until one is not a keyword: a data
  // line that looks like one (a second DATA line, say) would be taken for header.
  for (LineCursor after = lines; after.next(line);) {
    if (line.empty())
      continue;
    if (!TokenCursor(line).next(token))
      break;
    if (token.front() == '#')
      continue;
    const bool header_like =
        token.substr(0, 7) == "COLUMNS" ||
        std::any_of(std::begin(pcd_keywords), std::end(pcd_keywords),
                    [&](std::string_view keyword) {
                      return token.substr(0, keyword.size()) == keyword;
                    });
    if (header_like)
      source.failAt(after.number(), "data after DATA that reads as a header line");
    break;
  }

  if (names.empty())
    source.fail("the PCD header has no FIELDS");
  if (sizes.empty() || types.empty())
    source.fail("the PCD header lacks SIZE or TYPE");
  if (counts.empty())
    counts.assign(names.size(), 1);
  std::size_t point_step = 0;
  std::size_t values_per_point = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (pcl::getFieldType(static_cast<int>(sizes[i]), types[i]) < 0 || counts[i] < 1)
      source.fail("PCD field " + excerpt(names[i]) +
                  " has an invalid SIZE, TYPE or COUNT");
    point_step += static_cast<std::size_t>(sizes[i] * counts[i]);
    values_per_point += static_cast<std::size_t>(counts[i]);
  }
  for (const char* name : {"x", "y", "z"}) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      source.fail(std::string("the PCD file has no field '") + name + "'");
    if (counts[static_cast<std::size_t>(it - names.begin())] != 1)
      source.fail(std::string("PCD field '") + name + "' has more than one value");
  }
  if (width < 0 || height < 0 || points < 0)
    source.fail("the PCD header lacks WIDTH, HEIGHT or POINTS");
  if (width * height != points)
    source.fail("PCD WIDTH x HEIGHT differs from POINTS");
  if (points == 0)
    source.fail("no points (POINTS is 0)");

  const std::size_t body = static_cast<std::size_t>(lines.position() - text.data());
  const std::size_t available = text.size() - body;
  const auto expected = static_cast<std::size_t>(points);
  if (data == "binary") {
    if (available / point_step < expected)
      source.fail("truncated: the binary data holds fewer than " +
                  std::to_string(points) + " points");
  }
  else if (data == "binary_compressed") {
    std::uint32_t sizes_header[2] = {0, 0}; // compressed, uncompressed
    if (available < sizeof(sizes_header))
      source.fail("truncated: no compressed data");
    std::memcpy(sizes_header, text.data() + body, sizeof(sizes_header));
    if (sizes_header[0] > available - sizeof(sizes_header))
      source.fail("truncated: the compressed data is shorter than its header says");
    if (expected > std::numeric_limits<std::uint32_t>::max() / point_step ||
        sizes_header[1] != expected * point_step)
      source.fail("the compressed data does not decompress to " +
                  std::to_string(points) + " points");
    std::vector<char> scratch(sizes_header[1]);
    if (pcl::lzfDecompress(text.data() + body + sizeof(sizes_header), sizes_header[0],
                           scratch.data(), sizes_header[1]) != sizes_header[1])
      source.fail("the compressed data is corrupt");
  }
  else {
    long long read = 0;
    while (lines.next(line)) {
      // As in the header, PCL skips empty lines only; a blank one would be a point.
      if (line.empty())
        continue;
      if (hasControlCharacter(line))
        source.failAt(lines.number(), "control character in the PCD data");
      TokenCursor tokens(line);
      std::size_t values = 0;
      while (tokens.next(token)) {
        if (!parseDouble(token, value))
          source.failAt(lines.number(), excerpt(token) + " is not a number");
        ++values;
      }
      if (values != values_per_point)
        source.failAt(lines.number(), "expected " + std::to_string(values_per_point) +
                                          " values, found " + std::to_string(values));
      ++read;
    }
    if (read != points)
      source.fail("the file has " + std::to_string(read) + " data lines for " +
                  std::to_string(points) + " points");
  }
}

/** Rewrites x, y and z stored as other types (double, integers) as float. */
void
makeXyzFloat(pcl::PCLPointCloud2& cloud)
{
  bool convert = false;
  for (const Field& field : cloud.fields)
    if ((field.name == "x" || field.name == "y" || field.name == "z") &&
        field.datatype != Field::FLOAT32)
      convert = true;
  if (!convert)
    return;
  pcl::PCLPointCloud2 out;
  out.header = cloud.header;
  for (const Field& field : cloud.fields) {
    const bool coordinate = field.name == "x" || field.name == "y" || field.name == "z";
    appendField(out, field.name,
                coordinate ? static_cast<std::uint8_t>(Field::FLOAT32) : field.datatype,
                field.count);
  }
  const std::uint32_t width = cloud.width;
  const std::uint32_t height = cloud.height;
  finishLayout(out, static_cast<std::size_t>(width) * height);
  out.width = width;
  out.height = height;
  out.row_step = out.point_step * width;
  const std::size_t points = static_cast<std::size_t>(width) * height;
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* from = cloud.data.data() + i * cloud.point_step;
    std::uint8_t* to = out.data.data() + i * out.point_step;
    for (std::size_t f = 0; f < cloud.fields.size(); ++f) {
      const Field& source = cloud.fields[f];
      const Field& target = out.fields[f];
      if (source.datatype == target.datatype)
        std::memcpy(to + target.offset, from + source.offset,
                    pcl::getFieldSize(source.datatype) * source.count);
      else
        storeValue(to + target.offset, target.datatype,
                   loadValue(from + source.offset, source.datatype, false));
    }
  }
  cloud = std::move(out);
}

void
readPcd(const Source& source,
        const std::string& path,
        const std::string& text,
        pcl::PCLPointCloud2& cloud)
{
  checkPcd(source, text);
  if (pcl::io::loadPCDFile(path, cloud) < 0)
    source.fail("PCL's PCD reader rejected the file");
  makeXyzFloat(cloud);
  cloud.is_dense = allFinite(cloud);
}

// ---------------------------------------------------------------------------------

enum class Format { pcd, ply, obj, off, columns, unknown };

Format
formatOf(const std::string& path, std::string& extension)
{
  extension = std::filesystem::path(path).extension().string();
  std::string lower = extension;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](char c) {
    return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  });
  if (lower == ".pcd")
    return Format::pcd;
  if (lower == ".ply")
    return Format::ply;
  if (lower == ".obj")
    return Format::obj;
  if (lower == ".off")
    return Format::off;
  if (lower == ".xyz" || lower == ".pts" || lower == ".txt")
    return Format::columns;
  return Format::unknown;
}

/** Runs \a body and turns whatever it throws into the one-line reason. */
template <typename Body>
bool
guarded(const std::string& path, std::string* error, Body body)
{
  std::string reason;
  try {
    body();
    if (error)
      error->clear();
    return true;
  }
  catch (const FormatError& e) {
    reason = e.message;
  }
  catch (const std::bad_alloc&) {
    reason = path + ": out of memory";
  }
  catch (const std::exception& e) {
    reason = path + ": " + e.what();
  }
  catch (...) {
    reason = path + ": unexpected error";
  }
  if (error)
    *error = oneLine(std::move(reason));
  return false;
}

} // namespace

bool
loadPointSamples(const std::string& path, pcl::PCLPointCloud2& cloud,
                 std::string* error)
{
  const bool ok = guarded(path, error, [&] {
    cloud = pcl::PCLPointCloud2();
    const Source source(path);
    std::string extension;
    const Format format = formatOf(path, extension);
    if (format == Format::unknown)
      source.fail("unknown extension " + excerpt(extension) +
                  " (readable: .pcd .ply .obj .off .xyz .pts .txt)");
    std::string text;
    readFile(source, path, text);
    std::vector<float> xyz;
    switch (format) {
    case Format::pcd:
      readPcd(source, path, text, cloud);
      break;
    case Format::ply:
      readPlyVertices(source, text, cloud);
      break;
    case Format::obj:
      parseObj(source, text, xyz, nullptr);
      break;
    case Format::off:
      parseOff(source, text, xyz, nullptr);
      break;
    case Format::columns:
      parseColumns(source, text, xyz);
      break;
    case Format::unknown:
      break;
    }
    if (format == Format::obj || format == Format::off || format == Format::columns) {
      if (xyz.empty())
        source.fail(format == Format::obj ? "no points (no 'v x y z' line)" :
                    format == Format::off ? "no points (the vertex count is 0)" :
                                            "no points (only blank or comment lines)");
      makeXyzCloud(xyz, cloud);
    }
  });
  if (!ok)
    cloud = pcl::PCLPointCloud2();
  return ok;
}

bool
loadMeshFaces(const std::string& path,
              std::vector<pcl::Vertices>& faces,
              std::string* error)
{
  const bool ok = guarded(path, error, [&] {
    faces.clear();
    const Source source(path);
    std::string extension;
    const Format format = formatOf(path, extension);
    if (format != Format::ply && format != Format::obj && format != Format::off)
      source.fail("not a mesh format (faces are read from .ply, .obj and .off)");
    std::string text;
    readFile(source, path, text);
    std::vector<float> xyz;
    if (format == Format::ply)
      readPlyFaces(source, text, faces);
    else if (format == Format::obj)
      parseObj(source, text, xyz, &faces);
    else
      parseOff(source, text, xyz, &faces);
  });
  if (!ok)
    faces.clear();
  return ok;
}

} // namespace cocone
} // namespace pcl
