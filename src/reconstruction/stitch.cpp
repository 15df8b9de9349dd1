// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/stitch.h"

#include "common/parallel.h"
#include "reconstruction/local_spacing.h"

#include <pcl/console/print.h>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

using Vector = Eigen::Vector3d;

} // namespace

double
Stitcher::typicalSpacing(const std::vector<SampleIndex>& samples) const
{
  return detail::typicalSpacing(spacing_, samples);
}

bool
Stitcher::isTrueBoundary(double area, double perimeter, double spacing,
                         const std::vector<SampleIndex>& loop) const
{
  const bool kept_open = rule_.isTrueBoundary(area, perimeter, spacing, loop);
  if (detail::isTrueBoundary(area, perimeter, spacing, rule_.sizeRatio())) {
    const RimFlags flags = rule_.rimFlags(loop, spacing);
    PCL_VERBOSE("[pcl::cocone::reconstructSurface] hole of %zu edges, size %.2f local "
                "spacings: %zu of %zu rim samples flagged, %zu distinct: %s\n",
                loop.size(), 2 * area / perimeter / spacing, flags.flagged, flags.rim,
                flags.distinct, kept_open ? "true boundary" : "undersampling hole");
  }
  return kept_open;
}

// Stitching (paper 3.4.2): for each hole, the Delaunay triangles with all vertices on
// the hole (and on unused samples inside it) are offered to the same prune and walk,
// starting from the hole's edges. When they do not close it, a small hole (a handful of
// vertices whose triangle is not Delaunay: a sample on the other side of a thin part
// lies in its circumsphere) is closed by the triangulation of its loop of least area.
// The hole stays open, and everything is undone, when it is a true boundary
// (isTrueBoundary) or when closing it would break the manifold.
void
Stitcher::stitch(std::vector<std::vector<SampleIndex>>& loops)
{
  const std::vector<Vector>& points = mesh_.points();
  if (loops.empty())
    return;
  std::vector<std::uint8_t> stitched(loops.size(), 0);

  // Offer every hole its Delaunay triangles, in a group of its own (numbered after
  // those of any earlier call).
  const std::uint32_t first_group = mesh_.groupCount();
  std::vector<std::vector<SampleIndex>> members(loops.size());
  std::vector<std::uint8_t> kept_open(loops.size(), 0);
  std::vector<std::vector<std::array<SampleIndex, 3>>> offered(loops.size());
  // Each hole's samples and Delaunay triangles, in parallel (read-only), then added to
  // the pool in hole order.
  const auto prepare = [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<SampleIndex> neighbours, inner;
    for (std::size_t h = range.begin(); h != range.end(); ++h) {
      std::vector<SampleIndex>& vertices = members[h];
      vertices = loops[h];
      // Unused samples next to two or more hole vertices lie in the hole.
      inner.clear();
      for (const SampleIndex v : loops[h]) {
        voronoi_.delaunayNeighbours(v, neighbours);
        for (const SampleIndex w : neighbours)
          if (mesh_.meshDegree(w) == 0)
            inner.push_back(w);
      }
      std::sort(inner.begin(), inner.end());
      for (std::size_t i = 0; i < inner.size();) {
        std::size_t j = i;
        while (j < inner.size() && inner[j] == inner[i])
          ++j;
        if (j - i >= 2)
          vertices.push_back(inner[i]);
        i = j;
      }
      // Any surface spanning a loop has at least the loop's vector area (Stokes), so a
      // loop whose vector area already makes it a true boundary cannot be stitched.
      // Spare the long ones (a terrain's outer rim) the Delaunay fill; shorter ones
      // still go through it, as the polygon fill may grow them into another loop.
      if (loops[h].size() > kLargestPolygonFill) {
        Vector vector_area = Vector::Zero();
        for (std::size_t k = 0; k < loops[h].size(); ++k)
          vector_area += 0.5 * points[loops[h][k]].cross(
                                   points[loops[h][(k + 1) % loops[h].size()]]);
        kept_open[h] = isTrueBoundary(vector_area.norm(), mesh_.loopLength(loops[h]),
                                      typicalSpacing(vertices), loops[h]);
      }
      if (!kept_open[h])
        voronoi_.delaunayTrianglesAmong(vertices, offered[h]);
    }
  };
  runInArena(voronoi_.getNumberOfThreads(), [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, loops.size(), 4), prepare);
  });
  for (std::size_t h = 0; h < loops.size(); ++h) {
    for (const auto& t : offered[h])
      mesh_.addToPool({t[0], t[1], t[2]}, first_group + static_cast<std::uint32_t>(h));
    std::vector<std::array<SampleIndex, 3>>().swap(offered[h]);
    mesh_.closeGroup();
  }
  // Nothing added to the pool since the lists were built (every loop kept open, as a
  // hemisphere's rim is): they are current, and rebuilding them would read the whole
  // pool (0.3 s at a million samples).
  if (mesh_.hasLateTriangles())
    mesh_.rebuildIncidence();
  // A hole triangle that is a mesh triangle already is of no use.
  std::vector<std::uint32_t> same;
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t) {
    if (mesh_.group(t) == kCoconeGroup || mesh_.state(t) != kCandidate)
      continue;
    const TriangleIndices& tri = mesh_.triangle(t);
    mesh_.trianglesOnEdge(
        tri[0], tri[1],
        [&](std::uint32_t u) { return mesh_.inMesh(u) && mesh_.contains(u, tri[2]); },
        same);
    if (!same.empty())
      mesh_.reject(t);
  }

  std::vector<Walker::Front> frontier;
  std::vector<std::uint32_t> added, on_edge;
  for (std::size_t h = 0; h < loops.size(); ++h) {
    if (kept_open[h])
      continue;
    const std::uint32_t group = first_group + static_cast<std::uint32_t>(h);
    const std::vector<SampleIndex>& loop = loops[h];
    frontier.clear();
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const SampleIndex a = loop[k], b = loop[(k + 1) % loop.size()];
      mesh_.meshOnEdge(a, b, on_edge);
      if (on_edge.size() != 1)
        continue;
      const TriangleIndices& o = mesh_.oriented(on_edge[0]);
      for (int slot = 0; slot < 3; ++slot)
        if (o[slot] == a && o[(slot + 1) % 3] == b)
          frontier.emplace_back(on_edge[0], slot);
    }
    if (frontier.size() != loop.size())
      continue;
    const double spacing = typicalSpacing(members[h]);
    const double perimeter = mesh_.loopLength(loop);

    pruner_.prune(group);
    added.clear();
    walker_.walk(frontier, group, added);
    const bool walk_closes = !added.empty() && mesh_.closes(loop, added);
    const double fill_area = mesh_.area(added);
    PCL_VERBOSE(
        "[pcl::cocone::reconstructSurface] hole of %zu edges: Delaunay fill %s, "
        "size %.2f local spacings\n",
        loop.size(), walk_closes ? "closes it" : "does not close it",
        2 * fill_area / perimeter / spacing);
    if (walk_closes && !isTrueBoundary(fill_area, perimeter, spacing, loop)) {
      ++stitched_holes_;
      stitched_triangles_ += added.size();
      stitched[h] = 1;
      continue;
    }
    mesh_.undo(added);

    // A hole judged a true boundary here may still be closed by the polygon fill,
    // whose rule is stricter on small holes (HoleRule::isTrueBoundaryAtPolygonFill).
    const PolygonFill fill = filler_.fill(loops[h], spacing);
    if (fill.closed) {
      ++stitched_holes_;
      stitched_triangles_ += fill.added;
      stitched_triangles_ -= std::min(stitched_triangles_, fill.removed);
      stitched[h] = 1;
    }
  }
  // Every hole was closed completely or not at all: the others are what stays open.
  std::size_t kept = 0;
  for (std::size_t h = 0; h < loops.size(); ++h)
    if (!stitched[h]) {
      if (kept != h)
        loops[kept] = std::move(loops[h]);
      ++kept;
    }
  loops.resize(kept);
}

// One round of stitching over the loops of the mesh: those not offered before, and
// those offered before around which the mesh changed since (see reconstructSurface).
// Returns the number of loops offered.
std::size_t
Stitcher::stitchLoops()
{
  std::vector<std::vector<SampleIndex>>& tried = tried_;
  // What changed since the last round, net: a fill tried and undone changes nothing.
  const std::vector<Box> changed_boxes = mesh_.takeNetChangedBoxes();
  std::vector<std::vector<SampleIndex>> loops, keys;
  for (std::vector<SampleIndex>& loop : mesh_.traceLoops()) {
    std::vector<SampleIndex> key = loop;
    std::sort(key.begin(), key.end());
    if (std::binary_search(tried.begin(), tried.end(), key)) {
      const Box loop_box = mesh_.boundingBox(loop);
      if (std::all_of(changed_boxes.begin(), changed_boxes.end(),
                      [&](const Box& box) { return boxesApart(box, loop_box); }))
        continue;
    }
    else {
      keys.push_back(std::move(key));
    }
    loops.push_back(std::move(loop));
  }
  tried.insert(tried.end(), keys.begin(), keys.end());
  std::sort(tried.begin(), tried.end());
  const std::size_t offered = loops.size();
  stitch(loops);
  return offered;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
