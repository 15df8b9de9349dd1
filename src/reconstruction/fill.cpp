// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/fill.h"

#include "reconstruction/local_spacing.h"

#include <pcl/console/print.h>

#include <Eigen/Geometry>

namespace pcl {
namespace cocone {
namespace detail {

// Closes a hole with the least-area triangulation of its loop. Where every such
// triangulation would cut through surface triangles around the hole (typically a
// triangle the walk laid across a sharp edge), those triangles are removed, the hole
// grows to include them and the fill is tried again, a few times at most; if the hole
// still cannot be closed, or turns out to be a true boundary, everything is restored.
PolygonFill
PolygonFiller::fill(std::vector<SampleIndex>& loop, double spacing)
{
  constexpr int kGrowths = 3;
  std::vector<std::uint32_t> removed, blockers, added;
  std::vector<TriangleIndices> fill;
  std::vector<SampleIndex> grown;
  bool closed = false;
  for (int attempt = 0; attempt <= kGrowths && !closed; ++attempt) {
    if (loop.size() > kLargestPolygonFill)
      break;
    if (!fillByLeastArea(loop, fill, blockers)) {
      if (blockers.empty() || attempt == kGrowths)
        break;
      // Grow the hole over the triangles in the way; where that pinches a vertex (a
      // blocker touching the hole at a vertex only), drop its smaller fan so that the
      // holes join through an edge.
      mesh_.undo(blockers);
      removed.insert(removed.end(), blockers.begin(), blockers.end());
      for (const std::uint32_t t : blockers)
        pinches_.note(mesh_.oriented(t));
      pinches_.resolve(&removed);
      if (!mesh_.traceLoopFrom(loop.front(), grown) &&
          !(mesh_.meshDegree(loop.back()) && mesh_.traceLoopFrom(loop.back(), grown)))
        break;
      loop = grown;
      continue;
    }
    const double perimeter = mesh_.loopLength(loop);
    double fill_area = 0;
    for (const TriangleIndices& t : fill)
      fill_area += 0.5 * mesh_.orientedNormal(t).norm();
    const bool true_boundary =
        rule_.isTrueBoundaryAtPolygonFill(fill_area, perimeter, spacing, loop);
    if (pcl::console::isVerbosityLevelEnabled(pcl::console::L_VERBOSE)) {
      const RimFlags flags = rule_.rimFlags(loop, spacing);
      PCL_VERBOSE(
          "[pcl::cocone::reconstructSurface] hole of %zu edges: polygon fill of size "
          "%.2f local spacings, %zu of %zu rim samples flagged, %zu distinct: %s\n",
          loop.size(), 2 * fill_area / perimeter / spacing, flags.flagged, flags.rim,
          flags.distinct, true_boundary ? "true boundary" : "undersampling hole");
    }
    if (true_boundary)
      break;
    added.clear();
    for (const TriangleIndices& t : fill) {
      added.push_back(mesh_.addToPool(t, kPolygonGroup));
      mesh_.enterMesh(added.back());
    }
    closed = mesh_.closes(loop, added);
    if (!closed) {
      mesh_.undo(added);
      break;
    }
  }
  if (closed)
    return {true, added.size(), removed.size()};
  for (const std::uint32_t t : removed) // restore what was removed to grow the hole
    mesh_.enterMesh(t);
  return {};
}

// The least-area fill of the loop (fillLoopByLeastArea), using no diagonal that is an
// edge of the mesh already and no triangle that intersects the mesh around the hole;
// the blockers are mesh triangles.
bool
PolygonFiller::fillByLeastArea(const std::vector<SampleIndex>& loop,
                               std::vector<TriangleIndices>& fill,
                               std::vector<std::uint32_t>& blockers)
{
  fill.clear();
  blockers.clear();
  const std::size_t m = loop.size();
  if (m < 3)
    return false;
  std::vector<std::uint32_t> on_edge;
  if (m == 3) {
    // The loop of a lone triangle: its only fill is the same triangle again, which
    // would make a two-sided, zero-volume component. (A longer loop's fill triangles
    // each have a new diagonal, so none of them can be a mesh triangle.)
    mesh_.meshOnEdge(loop[0], loop[1], on_edge);
    for (const std::uint32_t u : on_edge)
      if (mesh_.contains(u, loop[2]))
        return false;
  }
  // Every fill triangle lies in the loop's bounding box: gather the mesh there once,
  // rather than for each of the O(m^3) candidates.
  mesh_.buildGrid();
  mesh_.meshNear(mesh_.boundingBox(loop), near_);
  obstacles_.clear();
  for (const std::uint32_t u : near_)
    obstacles_.push_back(mesh_.oriented(u));
  const auto is_edge = [&](SampleIndex a, SampleIndex b) {
    mesh_.meshOnEdge(a, b, on_edge);
    return !on_edge.empty();
  };
  const bool found = fillLoopByLeastArea(mesh_.points(), loop, is_edge, obstacles_,
                                         fill, blockers, scratch_);
  for (std::uint32_t& blocker : blockers) // positions in near_, sorted as near_ is
    blocker = near_[blocker];
  return found;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
