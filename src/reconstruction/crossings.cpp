// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/crossings.h"

#include "common/parallel.h"

#include <pcl/cocone/core/mesh_geometry.h>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

using Vector = Eigen::Vector3d;

// How far (in local spacings) an unused sample may lie from the mesh to be put back.
constexpr double kInsertionReach = 1.0;

// The crossing pairs of removeCrossings when no fill has built the mesh's grid. The
// suspects are then few (mostly the triangles at a rim's boundary samples), so a grid
// of the suspects alone is asked by every mesh triangle, rather than a grid of the
// whole mesh being built for them: on a 1M-point hemisphere, whose one loop (its rim)
// stays open, stitching took 1.6 to 2.1 s with that grid, and 0.7 s without. Each pair
// is tested once, in the cell that holds the low corner of the common part of the two
// boxes, and the lists come out sorted, as the other way gives them.
template <typename Crosses>
void
findCrossingsBySuspectGrid(const MeshState& mesh, unsigned threads,
                           const std::vector<std::uint32_t>& suspects,
                           const Crosses& crosses,
                           std::vector<std::vector<std::uint32_t>>& crossing)
{
  const std::vector<Vector>& points = mesh.points();
  double edges = 0;
  for (const std::uint32_t t : suspects)
    edges += (points[mesh.oriented(t)[0]] - points[mesh.oriented(t)[1]]).norm();
  BoxGrid grid(BoxGrid::cellSideFor(edges, suspects.size())); // of suspect positions
  std::vector<Box> boxes(suspects.size());
  for (std::uint32_t i = 0; i < suspects.size(); ++i) {
    boxes[i] = mesh.boundingBox(mesh.oriented(suspects[i]));
    grid.insert(i, boxes[i]);
  }

  using Pair = std::pair<std::uint32_t, std::uint32_t>; // suspect position, triangle
  tbb::enumerable_thread_specific<std::vector<Pair>> found;
  const auto ask = [&](const tbb::blocked_range<std::uint32_t>& range) {
    std::vector<Pair>& pairs = found.local();
    for (std::uint32_t u = range.begin(); u != range.end(); ++u) {
      if (!mesh.inMesh(u))
        continue;
      const Box box = mesh.boundingBox(mesh.oriented(u));
      grid.forEachOverlapping(
          box, [&](std::uint32_t i) -> const Box& { return boxes[i]; },
          [&](std::uint32_t i) {
            if (crosses(suspects[i], boxes[i], u, box))
              pairs.emplace_back(i, u);
          });
    }
  };
  runInArena(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, mesh.poolSize(), 4096), ask);
  });
  std::vector<Pair> pairs;
  for (const std::vector<Pair>& part : found)
    pairs.insert(pairs.end(), part.begin(), part.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [i, u] : pairs)
    crossing[i].push_back(u);
}

} // namespace

// Samples left in no triangle although they lie on the surface (a hole grown over
// them, a walk that went around them, often at sharp corners) are put back by splitting
// the mesh triangle they lie over in three, or the edge they lie next to (and its two
// triangles in two), when they are within kInsertionReach local spacings of it and the
// new triangles cut nothing. Duplicates and outliers stay out.
std::size_t
insertUnusedSamples(MeshState& mesh, const VoronoiCocone& voronoi,
                    const std::vector<double>& spacing)
{
  const std::vector<Vector>& points = mesh.points();
  std::vector<SampleIndex> neighbours;
  std::vector<std::uint32_t> nearby;
  std::vector<TriangleIndices> splits;
  std::vector<std::uint32_t> nearby_edge;
  std::size_t inserted = 0;
  for (SampleIndex v = 0; v < mesh.sampleCount(); ++v) {
    if (mesh.meshDegree(v) != 0 || voronoi.representative(v) != v || !(spacing[v] > 0))
      continue;
    // The mesh triangles at its Delaunay neighbours.
    voronoi.delaunayNeighbours(v, neighbours);
    nearby.clear();
    for (const SampleIndex w : neighbours)
      mesh.forEachAround(w, [&](std::uint32_t t) {
        if (mesh.inMesh(t))
          nearby.push_back(t);
      });
    std::sort(nearby.begin(), nearby.end());
    nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
    // The closest point of those triangles: inside one (split it in three) or on an
    // edge shared by two (split both in two).
    // Measured in the spacing of the surface there, not of v: an outlier's own nearest
    // neighbours are far.
    const Vector p = points[v];
    const auto reach = [&](const TriangleIndices& o) {
      return kInsertionReach * std::min({spacing[o[0]], spacing[o[1]], spacing[o[2]]});
    };
    double best_distance = std::numeric_limits<double>::infinity();
    std::uint32_t best = 0;
    int best_edge = -1; // -1: inside the triangle; k: on its edge k -> k + 1
    for (const std::uint32_t t : nearby) {
      const TriangleIndices& o = mesh.oriented(t);
      const Vector a = points[o[0]], b = points[o[1]], c = points[o[2]];
      const Vector normal = (b - a).cross(c - a);
      const double twice_area = normal.norm();
      if (!(twice_area > 0))
        continue;
      const Vector unit = normal / twice_area;
      const Vector q = p - (p - a).dot(unit) * unit; // projection on the plane
      if ((b - a).cross(q - a).dot(unit) >= 0 && (c - b).cross(q - b).dot(unit) >= 0 &&
          (a - c).cross(q - c).dot(unit) >= 0) {
        const double distance = std::abs((p - a).dot(unit));
        if (distance < best_distance && distance < reach(o)) {
          best_distance = distance;
          best = t;
          best_edge = -1;
        }
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        const Vector e0 = points[o[k]], e1 = points[o[(k + 1) % 3]];
        const double t_along = (p - e0).dot(e1 - e0) / (e1 - e0).squaredNorm();
        if (!(t_along > 0 && t_along < 1))
          continue; // nearest to a corner: no edge to split
        const double distance = (e0 + t_along * (e1 - e0) - p).norm();
        if (distance < best_distance && distance < reach(o)) {
          best_distance = distance;
          best = t;
          best_edge = k;
        }
      }
    }
    if (!std::isfinite(best_distance))
      continue;
    const TriangleIndices o = mesh.oriented(best);
    std::vector<std::uint32_t> replaced = {best};
    if (best_edge < 0) {
      splits = {{o[0], o[1], v}, {o[1], o[2], v}, {o[2], o[0], v}};
    }
    else {
      const SampleIndex e0 = o[best_edge], e1 = o[(best_edge + 1) % 3];
      const SampleIndex apex_here = o[(best_edge + 2) % 3];
      mesh.meshOnEdge(e0, e1, nearby_edge);
      if (nearby_edge.size() != 2)
        continue;
      const std::uint32_t other =
          nearby_edge[0] == best ? nearby_edge[1] : nearby_edge[0];
      const SampleIndex apex_there = mesh.apex(other, e0, e1);
      replaced.push_back(other);
      // best traverses e0 -> e1, other e1 -> e0; keep both orientations.
      splits = {{e0, v, apex_here},
                {v, e1, apex_here},
                {e1, v, apex_there},
                {v, e0, apex_there}};
    }
    // Most nearby triangles are apart from every split, which the boxes tell first.
    Box splits_box = mesh.boundingBox(splits[0]);
    for (const TriangleIndices& split : splits) {
      const Box box = mesh.boundingBox(split);
      splits_box = {splits_box.low.cwiseMin(box.low),
                    splits_box.high.cwiseMax(box.high)};
    }
    bool crossing = false;
    for (const std::uint32_t t : nearby) {
      if (crossing)
        break;
      if (std::find(replaced.begin(), replaced.end(), t) != replaced.end() ||
          boxesApart(mesh.boundingBox(mesh.oriented(t)), splits_box))
        continue;
      for (const TriangleIndices& split : splits)
        if (trianglesIntersect(points, split, mesh.oriented(t))) {
          crossing = true;
          break;
        }
    }
    if (crossing)
      continue;
    for (const std::uint32_t t : replaced)
      mesh.leaveMesh(t);
    for (const TriangleIndices& split : splits)
      mesh.enterMesh(mesh.addToPool(split, kPolygonGroup));
    ++inserted;
  }
  return inserted;
}

// The walk takes restricted Delaunay triangles, which cannot cross on a well-sampled
// surface; where samples are undersampled or noisy (boundary samples), and where
// triangles were added by stitching or insertion, nothing rules it out. Those
// triangles are checked against every mesh triangle near them (the grid of the
// fills' checks), and of each crossing pair the one added last is removed; the holes
// this leaves are stitched like the others (fills are checked already).
CrossingRemoval
removeCrossings(MeshState& mesh, PinchResolver& pinches,
                const std::vector<std::uint8_t>& boundary, unsigned threads)
{
  const std::vector<Vector>& points = mesh.points();
  std::vector<std::uint32_t> suspects;
  std::vector<std::uint8_t> is_suspect(mesh.poolSize(), 0);
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t) {
    const TriangleIndices& o = mesh.oriented(t);
    if (mesh.inMesh(t) && (mesh.group(t) != kCoconeGroup || boundary[o[0]] ||
                           boundary[o[1]] || boundary[o[2]])) {
      suspects.push_back(t);
      is_suspect[t] = 1;
    }
  }
  if (suspects.empty())
    return {};

  // Every crossing pair (suspect, mesh triangle), found in parallel without changing
  // anything, listed in increasing order; a pair of two suspects only from the
  // earlier one (the removals below never need it from the later one: by then one of
  // the two is out of the mesh, see there). Triangles are found near a suspect by
  // their boxes, through a grid: looking through the triangles at its corners'
  // Delaunay neighbours instead read some 30 incidence lists per suspect and cost twice
  // as much (PCL's table scene: 1.1 s against 0.55 s), and could miss a crossing
  // triangle with no corner there.
  std::vector<std::vector<std::uint32_t>> crossing(suspects.size());
  const auto crosses = [&](std::uint32_t t, const Box& t_box, std::uint32_t u,
                           const Box& u_box) {
    // Most are apart, which their boxes tell without the call (the exact test starts
    // with the same strict comparison).
    return (u > t || !is_suspect[u]) && !boxesApart(u_box, t_box) &&
           trianglesIntersect(points, mesh.oriented(t), mesh.oriented(u));
  };
  if (mesh.hasGrid()) {
    // The fills built the mesh's grid: each suspect asks it.
    tbb::enumerable_thread_specific<std::vector<std::uint32_t>> scratch;
    const auto findCrossings = [&](const tbb::blocked_range<std::size_t>& range) {
      std::vector<std::uint32_t>& nearby = scratch.local();
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const std::uint32_t t = suspects[i];
        const Box box = mesh.boundingBox(mesh.oriented(t));
        mesh.meshNear(box, nearby);
        for (const std::uint32_t u : nearby)
          if (crosses(t, box, u, mesh.boundingBox(mesh.oriented(u))))
            crossing[i].push_back(u);
      }
    };
    runInArena(threads, [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, suspects.size(), 64),
                        findCrossings);
    });
  }
  else {
    findCrossingsBySuspectGrid(mesh, threads, suspects, crosses, crossing);
  }
  // Of each crossing pair the triangle added last goes, suspects in order: removals
  // only shrink the mesh, so the pairs still both in it here are exactly those a
  // sequential pass testing as it goes would meet. (A suspect u crossing a later
  // suspect t has met t here unless u left the mesh first: either way, by t's turn
  // one of them is gone, which is why t's list need not hold u.)
  std::vector<std::uint32_t> gone;
  for (std::size_t i = 0; i < suspects.size(); ++i) {
    const std::uint32_t t = suspects[i];
    if (!mesh.inMesh(t))
      continue;
    for (const std::uint32_t u : crossing[i]) {
      if (!mesh.inMesh(u))
        continue;
      const std::uint32_t drop = std::max(t, u);
      mesh.leaveMesh(drop);
      gone.push_back(drop);
      if (drop == t)
        break;
    }
  }
  // A removal can leave a vertex with two fans.
  for (const std::uint32_t t : gone)
    pinches.note(mesh.oriented(t));
  CrossingRemoval removal;
  removal.pinch_removed = pinches.resolve();
  removal.removed = gone.size();
  return removal;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
