// SPDX-License-Identifier: GPL-3.0-or-later
//
// Wavefront OBJ: the `v` lines are the points, the `f` lines the faces.
//
// Our own parser, because both library readers hand out faces that name vertices the
// file does not have, an out-of-bounds read for whoever uses the mesh (measured by
// io/survey's reader_survey with PCL 1.13 and VTK 9.1, on fandisk and on malformed
// files):
// - pcl::OBJReader returns `f 1 2 9` on 3 vertices (index 8), `f 0 1 2`, `f -5 1 2`
//   (index -2) and `f 1 2 99999999999` (wrapped to 1215752190) as a success, and
//   crashes (SIGSEGV) on the line `v 1 2`; it also adds normal_x/y/z fields whenever
//   the file has `vn` lines, and prints to stderr when an `mtllib` file is missing;
// - vtkOBJReader accepts the same faces, and reads `v 1 2` and `v 1 x 3` as points.
#include "readers.h"

#include "cloud_layout.h"

#include <limits>

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

/** The position index of an OBJ face corner ("v", "v/vt", "v//vn", "v/vt/vn"),
 * resolved to 0-based; negative indices count back from the last vertex read. */
long long
objCorner(const Source& source, std::size_t line, std::string_view token,
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

} // namespace

void
readObj(const Source& source, std::string_view text, std::vector<float>& xyz,
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

} // namespace io_internal
} // namespace cocone
} // namespace pcl
