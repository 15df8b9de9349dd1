// SPDX-License-Identifier: GPL-3.0-or-later
//
// Geomview OFF: a header, the counts, the vertex lines, the face lines.
//
// Our own parser: neither PCL 1.13 nor VTK 9.1 has an OFF reader. CGAL 5.5's
// CGAL::IO::read_OFF (CGAL is a dependency of the core already) reads the three OFF
// files of the shared data, but reserves for the counts of the header before reading:
// a 20-byte file declaring 2000000000 vertices or faces, or a face of 4000000000
// corners, ends in std::bad_alloc (measured by io/survey's reader_survey under an 8 GB
// address-space limit).
#include "readers.h"

#include "cloud_layout.h"

#include <algorithm>
#include <limits>

namespace pcl {
namespace cocone {
namespace io_internal {

void
readOff(const Source& source, std::string_view text, std::vector<float>& xyz,
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
  // The edge count is often left out, and never used; but if it is there it must be a
  // count, and nothing may follow it.
  if (tokens.next(token)) {
    parseCount(source, lines.number(), token);
    if (tokens.next(token))
      source.failAt(lines.number(), excerpt(token) + " after the vertex, face and "
                                                     "edge counts");
  }
  if (vertex_count > std::numeric_limits<pcl::index_t>::max())
    source.failAt(lines.number(), "too many vertices");

  xyz.reserve(static_cast<std::size_t>(std::min<long long>(
                  vertex_count, static_cast<long long>(text.size() / 6))) *
              3);
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

} // namespace io_internal
} // namespace cocone
} // namespace pcl
