// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's polygon fill: closes a hole that its Delaunay triangles do not
// close with the least-area triangulation of its loop, growing the hole over the
// triangles in the way. Never installed.
#pragma once

#include "reconstruction/least_area_fill.h"
#include "reconstruction/local_spacing.h"
#include "reconstruction/mesh_state.h"
#include "reconstruction/walk.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Loops longer than this are not filled as polygons (O(m^3) time, O(m^2) memory). */
constexpr std::size_t kLargestPolygonFill = 60;

/** What a polygon fill did. */
struct PolygonFill
{
  bool closed = false;     ///< the hole is closed; otherwise the mesh is as it was
  std::size_t added = 0;   ///< triangles of the fill (when closed)
  std::size_t removed = 0; ///< mesh triangles removed to grow the hole (when closed)
};

/** Closes holes of a MeshState by least-area fills (see the source). */
class PolygonFiller
{
public:
  /** Fills holes of \a mesh, resolving through \a pinches the pinches that growing a
   * hole makes; a hole that \a rule calls a true boundary is not filled. */
  PolygonFiller(MeshState& mesh, PinchResolver& pinches, const HoleRule& rule)
    : mesh_(mesh), pinches_(pinches), rule_(rule)
  {}

  /** Closes the hole of \a loop (as the mesh triangles run it), whose samples are
   * \a spacing apart; \a loop becomes the grown hole's loop when the hole grew. The
   * fill's triangles join the pool in group kPolygonGroup. */
  PolygonFill fill(std::vector<SampleIndex>& loop, double spacing);

private:
  bool fillByLeastArea(const std::vector<SampleIndex>& loop,
                       std::vector<TriangleIndices>& fill,
                       std::vector<std::uint32_t>& blockers);

  MeshState& mesh_;
  PinchResolver& pinches_;
  const HoleRule& rule_;
  // Reused from one fill to the next.
  LeastAreaFillScratch scratch_;
  std::vector<std::uint32_t> near_;        // mesh triangles near the loop
  std::vector<TriangleIndices> obstacles_; // the same, as oriented in the mesh
};

} // namespace detail
} // namespace cocone
} // namespace pcl
