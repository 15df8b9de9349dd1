// SPDX-License-Identifier: GPL-3.0-or-later
//
// Column formats (.xyz, .pts, .txt): one point per line, x y z first, or Hoppe's a3d
// streams (his .pts files), whose points are the `p x y z` records.
//
// Our own parser, because no library reader reads these files as they are written
// (measured by io/survey's reader_survey with PCL 1.13 and VTK 9.1, on the five column
// files of the shared data and on malformed ones):
// - vtkSimplePointsReader reads all numbers as one stream of x y z triples: a 6-column
//   file gives two points per line (3holes: 8000 points for 4000, kitten: 10420 for
//   5210), and what it read before a bad token is a success ("4 five 6": no error);
// - vtkPTSReader reads Leica's PTS, whose first line is a point count: it loses the
//   first point of every file here (3holes: 3999) and rejects Hoppe's `p x y z`;
// - pcl::ASCIIReader refuses every extension but .txt; renamed, it reads Hoppe's two
//   `#` lines as points (cactus: 3320 for 3318) and takes binary bytes, "1,5 2 3",
//   "4 five 6" and a two-value line as points without an error.
// And none of them knows the a3d records.
#include "readers.h"

#include "cloud_layout.h"

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

/** What a line of Hoppe's a3d stream is, by its record code (the first token). Each
 * record is the code and three numbers (Mesh-processing-library, libHh/A3dStream.h):
 * `p x y z` is a point; `n` (the next point's normal), `d`, `s`, `g` (its colour
 * state), `o`, `O` (select or clear an object) and `f` (end of frame) are state and
 * commands that place no point; `q` ends the stream; `P`, `L`, `v`, `E` make polygons
 * and polylines, which are not samples. */
enum class A3dRecord
{
  none,
  point,
  state,
  end,
  polygon
};

A3dRecord
a3dRecord(std::string_view code)
{
  if (code.size() != 1)
    return A3dRecord::none;
  switch (code[0]) {
  case 'p':
    return A3dRecord::point;
  case 'n':
  case 'd':
  case 's':
  case 'g':
  case 'o':
  case 'O':
  case 'f':
    return A3dRecord::state;
  case 'q':
    return A3dRecord::end;
  case 'P':
  case 'L':
  case 'v':
  case 'E':
    return A3dRecord::polygon;
  default:
    return A3dRecord::none;
  }
}

} // namespace

void
readColumns(const Source& source, std::string_view text, std::vector<float>& xyz)
{
  LineCursor lines(text.data(), text.data() + text.size());
  std::string_view line;
  std::string_view token;
  while (lines.nextContent(line, true)) {
    TokenCursor tokens(line);
    tokens.next(token);
    const A3dRecord record = a3dRecord(token);
    if (record == A3dRecord::end)
      break; // what follows is no longer a3d
    if (record == A3dRecord::polygon)
      source.failAt(lines.number(), "a3d record " + excerpt(token) +
                                        " belongs to a polygon or polyline; only "
                                        "point records ('p x y z') are samples");
    if (record == A3dRecord::state) {
      // Read to be sure the line is what it says, then set aside.
      for (int k = 0; k < 3; ++k) {
        if (!tokens.next(token))
          source.failAt(lines.number(),
                        "a3d record expects 3 numbers, found " + std::to_string(k));
        parseNumber(source, lines.number(), token);
      }
      continue;
    }
    // A point record, or plain columns whose first three are x y z.
    bool have = record != A3dRecord::point || tokens.next(token);
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
