// SPDX-License-Identifier: GPL-3.0-or-later
//
// PLY, ascii and binary in either byte order.
//
// Our own parser, because each library reader has a defect that rules it out
// (measured by io/survey's reader_survey with PCL 1.13 and VTK 9.1, on the five PLY
// files of the shared data and on malformed ones):
// - pcl::PLYReader turns bun000's range_grid into an organized 512 x 400 cloud (204800
//   points for its 40256 vertices), renames nx/ny/nz to normal_x/y/z, prints a warning
//   for every face element, reads "4 x 6" as a vertex without an error, returns face
//   indices beyond the vertices, and allocates what a header declares before reading:
//   `element vertex -1`, or 2000000000 vertices in a 120-byte file, is std::bad_alloc
//   (an abort where nobody catches it); on ascii files it takes four to six times as
//   long (bun_zipper's vertices and faces: 265 ms, this parser 48 ms);
// - vtkPLYReader keeps only the properties it knows (bun_zipper's confidence and
//   intensity are lost), crashes (SIGSEGV) on an ascii line with fewer values than
//   declared, on a vertex element without z and on a list length of 4294967280, and
//   returns a truncated file as a success, the missing vertices zero (1000 vertices
//   from a body of 120 bytes).
#include "readers.h"

#include "cloud_layout.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

constexpr std::size_t max_properties = 65535;

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

enum class PlyFormat
{
  ascii,
  binary_little_endian,
  binary_big_endian
};

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
parsePlyHeader(const Source& source, std::string_view text)
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
      if (tokens.next(token))
        source.failAt(number, "element " + excerpt(element.name) +
                                  ": more than a name and a count");
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
      // A documented limit, far above any real file's, so that no sum of property
      // sizes can overflow.
      if (properties.size() == max_properties)
        source.failAt(number, "more than " + std::to_string(max_properties) +
                                  " properties in one element");
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
  PlyAsciiBody(const Source& source, std::string_view text, const PlyHeader& header)
    : source_(source), lines_(text.data() + header.body_offset,
                              text.data() + text.size(), header.body_line)
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
  readVertices(const PlyElement& element, const std::vector<int>& targets,
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
  readFaces(const PlyElement& element, std::size_t list_property,
            std::size_t vertex_count, std::vector<pcl::Vertices>& faces)
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

  /** Fails if the body holds more lines than the \a declared ones still to come: an
   * extra line is a point (or face) that the header does not count, and would be
   * dropped without a word. \a last is the element read last, for the message. */
  void
  checkNoMoreLines(std::size_t declared, const PlyElement& last)
  {
    std::string_view line;
    for (std::size_t i = 0; i < declared; ++i)
      if (!lines_.nextContent(line, false))
        return; // fewer: what is missing belongs to an element not read here
    if (lines_.nextContent(line, false))
      source_.failAt(lines_.number(),
                     declared == 0
                         ? "more " + excerpt(last.name) + " lines than the " +
                               std::to_string(last.count) + " the header declares"
                         : "more lines than the header declares");
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
  PlyBinaryBody(const Source& source, std::string_view text, const PlyHeader& header)
    : source_(source),
      p_(reinterpret_cast<const std::uint8_t*>(text.data()) + header.body_offset),
      end_(reinterpret_cast<const std::uint8_t*>(text.data()) + text.size())
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
  readVertices(const PlyElement& element, const std::vector<int>& targets,
               pcl::PCLPointCloud2& cloud)
  {
    if (copyFixedVertices(element, targets, cloud))
      return;
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
  readFaces(const PlyElement& element, std::size_t list_property,
            std::size_t vertex_count, std::vector<pcl::Vertices>& faces)
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
  /** The common case of large files: vertices of one fixed size whose properties are
   * stored in the fields' own types and the host's byte order. They are copied by a
   * plan made once (adjacent properties merged into one copy: x, y, z are one 12-byte
   * copy), after one bounds check for the whole element; checking and dispatching
   * every property of every vertex took three to four times as long as reading the
   * file. Returns false, having read nothing, when the element is not such a case or
   * ends early (the general path then says where). */
  bool
  copyFixedVertices(const PlyElement& element, const std::vector<int>& targets,
                    pcl::PCLPointCloud2& cloud)
  {
    struct Copy
    {
      std::size_t from, to, size;
    };
    std::vector<Copy> plan;
    std::size_t record = 0;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& property = element.properties[k];
      if (swap_ || property.count_type != 0)
        return false;
      const Field& field = cloud.fields[targets[k]];
      if (field.datatype != property.type)
        return false;
      const std::size_t size = pcl::getFieldSize(property.type);
      if (!plan.empty() && plan.back().from + plan.back().size == record &&
          plan.back().to + plan.back().size == field.offset)
        plan.back().size += size;
      else
        plan.push_back({record, field.offset, size});
      record += size;
    }
    if (record == 0 || element.count > remaining() / record)
      return false;
    for (std::size_t i = 0; i < element.count; ++i) {
      const std::uint8_t* from = p_ + i * record;
      std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
      for (const Copy& copy : plan)
        std::memcpy(point + copy.to, from + copy.from, copy.size);
    }
    p_ += element.count * record;
    return true;
  }

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
walkPly(const Source& source, std::string_view text, const PlyHeader& header,
        const PlyElement* wanted, Read read)
{
  if (header.format == PlyFormat::ascii) {
    PlyAsciiBody body(source, text, header);
    readPlyElement(body, header, wanted, read);
    // Each count is below 2^31, so the sum of the counts after the element read cannot
    // overflow.
    std::size_t declared = 0;
    bool after = false;
    for (const PlyElement& element : header.elements) {
      if (after)
        declared += element.count;
      after = after || &element == wanted;
    }
    body.checkNoMoreLines(declared, *wanted);
  }
  else {
    PlyBinaryBody body(source, text, header);
    readPlyElement(body, header, wanted, read);
  }
}

} // namespace

void
readPlyVertices(const Source& source, std::string_view text, pcl::PCLPointCloud2& cloud)
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
  finishLayout(cloud, 0); // pads the point, so that the size below is the final one
  checkDataSize(cloud.point_step, vertex->count);
  finishLayout(cloud, room);
  walkPly(source, text, header, vertex,
          [&](auto& body) { body.readVertices(*vertex, targets, cloud); });
  cloud.width = static_cast<std::uint32_t>(vertex->count);
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = allFinite(cloud);
}

void
readPlyFaces(const Source& source, std::string_view text,
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

} // namespace io_internal
} // namespace cocone
} // namespace pcl
