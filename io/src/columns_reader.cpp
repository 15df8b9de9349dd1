// SPDX-License-Identifier: GPL-3.0-or-later
//
// Column formats (.xyz, .pts, .txt): one point per line, x y z first.
//
// Our own parser, because no library reader reads these files as they are written
// (measured with PCL 1.13 and VTK 9.1 on the five column files of the shared data and
// on malformed ones):
// - vtkSimplePointsReader reads all numbers as one stream of x y z triples: a 6-column
//   file gives two points per line (3holes: 8000 points for 4000, kitten: 10420 for
//   5210), and what it read before a bad token is a success ("4 five 6": no error);
// - vtkPTSReader reads Leica's PTS, whose first line is a point count: it loses the
//   first point of every file here (3holes: 3999) and rejects Hoppe's `p x y z`;
// - pcl::ASCIIReader refuses every extension but .txt; renamed, it reads Hoppe's two
//   `#` lines as points (cactus: 3320 for 3318) and takes binary bytes, "1,5 2 3",
//   "4 five 6" and a two-value line as points without an error.
#include "readers.h"

#include "cloud_layout.h"

namespace pcl {
namespace cocone {
namespace io_internal {

void
readColumns(const Source& source, std::string_view text, std::vector<float>& xyz)
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

} // namespace io_internal
} // namespace cocone
} // namespace pcl
