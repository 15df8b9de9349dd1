// SPDX-License-Identifier: GPL-3.0-or-later
//
// PCD: checked here, read by PCL.
//
// PCL's reader is the one that knows PCL's format (its three encodings, LZF and the
// structure-of-arrays layout of binary_compressed), and it reads the four PCD files of
// the shared data as they are. But alone it is not safe on a file it did not write
// (measured by io/survey's reader_survey, PCL 1.13): it crashes (SIGSEGV) on an empty
// or non-PCD file and on a COUNT whose product with SIZE overflows; it allocates what
// the header declares before looking at the data (POINTS 2000000000 in a 120-byte
// file: std::bad_alloc); it reads "4 x 6" and a line with too few values as points (a
// warning at most); and it prints to stderr on every problem. So every file is checked
// here first, and PCL reads only what passed.
#include "readers.h"

#include "cloud_layout.h"

#include <pcl/common/io.h>
#include <pcl/io/lzf.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <istream>
#include <iterator>
#include <limits>
#include <streambuf>

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

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
constexpr std::string_view pcd_keywords[] = {"VERSION", "FIELDS", "SIZE",   "TYPE",
                                             "COUNT",   "WIDTH",  "HEIGHT", "VIEWPOINT",
                                             "POINTS",  "DATA"};

/** Checks what PCL's reader would complain about (on stderr, or by crashing, as it does
 * on an empty file), plus what it silently gets wrong in ascii data. Stricter than PCL
 * where PCL reads on with a warning: the keywords must come in the prescribed order,
 * once each, and WIDTH, HEIGHT and POINTS must be there. */
void
checkPcd(const Source& source, std::string_view text)
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
      if (tokens.next(token))
        source.failAt(number, keyword + " has more than one value");
      (keyword == "WIDTH" ? width : keyword == "HEIGHT" ? height : points) = count;
    }
    else { // DATA
      if (!tokens.next(token) ||
          (token != "ascii" && token != "binary" && token != "binary_compressed"))
        source.failAt(number, "unknown PCD data kind");
      data = std::string(token);
      if (tokens.next(token))
        source.failAt(number, "DATA has more than one value");
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
  // PCL reads these numbers again as int and computes its offsets, point step and data
  // size from them in 32 bits: each is bounded here so that none of that overflows,
  // and the sums are checked as they grow, before anything is allocated.
  constexpr long long max_int = std::numeric_limits<std::int32_t>::max();
  long long point_step = 0;
  long long values_per_point = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const long long size = sizes[i];
    if ((size != 1 && size != 2 && size != 4 && size != 8) ||
        pcl::getFieldType(static_cast<int>(size), types[i]) < 0 || counts[i] < 1 ||
        counts[i] > max_int)
      source.fail("PCD field " + excerpt(names[i]) +
                  " has an invalid SIZE, TYPE or COUNT");
    // size <= 8 and count < 2^31: neither the product nor the sums (bounded below
    // max_int before each step) can overflow.
    point_step += size * counts[i];
    values_per_point += counts[i];
    if (point_step > max_int)
      source.fail("PCD points too large (more than " + std::to_string(max_int) +
                  " bytes each)");
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
  // Both factors are below 2^31.
  const auto data_size =
      static_cast<std::uint64_t>(points) * static_cast<std::uint64_t>(point_step);
  if (data_size > std::numeric_limits<std::uint32_t>::max())
    source.fail("PCD data of " + std::to_string(data_size) +
                " bytes: more than the 4 GiB PCL's reader can address");

  const std::size_t body = static_cast<std::size_t>(lines.position() - text.data());
  const std::size_t available = text.size() - body;
  if (data == "binary") {
    if (available < data_size)
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
    if (sizes_header[1] != data_size)
      source.fail("the compressed data does not decompress to " +
                  std::to_string(points) + " points");
    // LZF's longest back reference is 3 bytes for 264 (the format of liblzf's
    // lzf_d.c), so no compressed block expands more than 88 times: a header claiming
    // more is a lie told to make the reader allocate.
    if (sizes_header[1] / 88 > sizes_header[0])
      source.fail("the compressed data is too short for " + std::to_string(points) +
                  " points");
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
      if (static_cast<long long>(values) != values_per_point)
        source.failAt(lines.number(), "expected " + std::to_string(values_per_point) +
                                          " values, found " + std::to_string(values));
      ++read;
    }
    if (read != points)
      source.fail("the file has " + std::to_string(read) + " data lines for " +
                  std::to_string(points) + " points");
  }
}

/** A read-only stream over the bytes in memory, so that PCL parses the very bytes that
 * were checked instead of opening the file a second time (it may have changed). PCL's
 * header reader asks where the data start with tellg, hence the seeks. */
class MemoryBuffer : public std::streambuf
{
public:
  explicit MemoryBuffer(std::string_view text)
  {
    // The get area is only read from; streambuf wants non-const pointers all the same.
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }

protected:
  pos_type
  seekoff(off_type offset, std::ios_base::seekdir from,
          std::ios_base::openmode which) override
  {
    const off_type size = egptr() - eback();
    const off_type base = from == std::ios_base::beg   ? 0
                          : from == std::ios_base::cur ? gptr() - eback()
                                                       : size;
    if (!(which & std::ios_base::in) || offset < -base || offset > size - base)
      return pos_type(off_type(-1));
    setg(eback(), eback() + base + offset, egptr());
    return pos_type(base + offset);
  }

  pos_type
  seekpos(pos_type position, std::ios_base::openmode which) override
  {
    return seekoff(off_type(position), std::ios_base::beg, which);
  }
};

} // namespace

void
readPcd(const Source& source, std::string_view text, pcl::PCLPointCloud2& cloud)
{
  checkPcd(source, text);
  MemoryBuffer buffer(text);
  std::istream stream(&buffer);
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0;
  int data_type = 0;
  unsigned int data_index = 0;
  if (reader.readHeader(stream, cloud, origin, orientation, version, data_type,
                        data_index) < 0)
    source.fail("PCL's PCD reader rejected the header");
  int result = 0;
  if (data_type == 0) {
    stream.clear();
    stream.seekg(data_index);
    result = reader.readBodyASCII(stream, cloud, version);
  }
  else {
    result = reader.readBodyBinary(reinterpret_cast<const unsigned char*>(text.data()),
                                   cloud, version, data_type == 2, data_index);
  }
  if (result < 0)
    source.fail("PCL's PCD reader rejected the data");
  // The check and PCL read the header separately; were they ever to disagree, the
  // cloud would not be what was checked.
  if (cloud.data.size() !=
      static_cast<std::size_t>(cloud.width) * cloud.height * cloud.point_step)
    source.fail("PCL's PCD reader gave a cloud of inconsistent size");
  makeXyzFloat(cloud);
  cloud.is_dense = allFinite(cloud);
}

} // namespace io_internal
} // namespace cocone
} // namespace pcl
