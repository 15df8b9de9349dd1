// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/prune.h"

#include "common/parallel.h"

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

using Vector = Eigen::Vector3d;

} // namespace

// Pruning. An edge is sharp when, ordering its triangles by angle around it, two
// consecutive ones are more than 3 pi / 2 apart: a fold (the triangles bend back onto
// each other) or a bare edge (one triangle). Triangles at folds go. A triangle at a
// bare edge goes too unless a flat sheet holds it: one of its other edges has exactly
// two triangles meeting without a fold. That exception is what keeps a small gap (a
// Delaunay triangle that only two of its three vertices marked, far from any boundary
// sample) from letting pruning cascade through a whole surface (measured on the
// Stanford bunny with the plain rule), while fins hanging off an edge shared by three
// or more triangles still go; the gaps are closed by stitching. Triangles incident to a
// boundary sample are never pruned, as in the paper.
bool
Pruner::mustPrune(std::uint32_t t, std::vector<SampleIndex>& apexes,
                  std::vector<double>& angles) const
{
  const std::vector<Vector>& points = mesh_.points();
  const TriangleIndices& tri = mesh_.triangle(t);
  const std::uint32_t group = mesh_.group(t);
  bool bare = false, held = false;
  for (int k = 0; k < 3; ++k) {
    const SampleIndex a = tri[k], b = tri[(k + 1) % 3];
    // The apexes of the live triangles on the edge (t's own among them).
    apexes.clear();
    mesh_.forEachOnEdge(a, b, [&](std::uint32_t s, SampleIndex apex_of_s) {
      if (mesh_.inMesh(s) || (mesh_.state(s) == kCandidate && mesh_.group(s) == group))
        apexes.push_back(apex_of_s);
    });
    if (apexes.size() == 1) {
      bare = true;
      continue;
    }
    const Vector pa = points[a];
    const Vector axis = (points[b] - pa).normalized();
    const auto across = [&](SampleIndex apex_of_s) {
      Vector u = points[apex_of_s] - pa;
      return Vector(u - u.dot(axis) * axis);
    };
    if (apexes.size() == 2) {
      // Two half-planes fold (the wider gap exceeds 3 pi / 2) when they are less than
      // pi / 2 apart.
      if (across(apexes[0]).dot(across(apexes[1])) > 0)
        return true;
      held = true;
      continue;
    }
    // Angles around the edge, from the first triangle's half-plane.
    const Vector reference = across(apexes[0]).normalized();
    const Vector normal = axis.cross(reference);
    angles.clear();
    for (const SampleIndex apex_of_s : apexes) {
      const Vector u = across(apex_of_s);
      double angle = std::atan2(u.dot(normal), u.dot(reference));
      if (angle < 0)
        angle += 2 * M_PI;
      angles.push_back(angle);
    }
    std::sort(angles.begin(), angles.end());
    double widest = 2 * M_PI - angles.back() + angles.front();
    for (std::size_t i = 1; i < angles.size(); ++i)
      widest = std::max(widest, angles[i] - angles[i - 1]);
    if (widest > 1.5 * M_PI)
      return true; // a fold
  }
  return bare && !held;
}

std::size_t
Pruner::prune(std::uint32_t group)
{
  const std::vector<std::uint8_t>& boundary = boundary_;
  // A group's triangles are contiguous in the pool.
  const std::uint32_t first = mesh_.groupBegin(group), last = mesh_.groupEnd(group);
  const auto is_protected = [&](std::uint32_t t) {
    const TriangleIndices& tri = mesh_.triangle(t);
    return group == kCoconeGroup &&
           (boundary[tri[0]] || boundary[tri[1]] || boundary[tri[2]]);
  };
  std::vector<std::uint32_t> work;
  std::vector<std::uint8_t> queued(last - first, 0);
  for (std::uint32_t t = first; t < last; ++t)
    if (mesh_.state(t) == kCandidate) {
      work.push_back(t);
      queued[t - first] = 1;
    }

  // The first verdicts, read-only, in parallel (most triangles are judged only once).
  // A verdict goes stale when a triangle on one of its edges is removed; the cascade
  // below judges stale ones again, in the same order as a sequential run would.
  // A hole's group is small: judged in the cascade alone, it costs no parallel set-up.
  constexpr std::size_t kParallelVerdicts = 4096;
  const bool parallel = last - first >= kParallelVerdicts;
  std::vector<std::uint8_t> verdict(last - first, 0),
      stale(last - first, parallel ? 0 : 1);
  const auto judge = [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<SampleIndex> apexes;
    std::vector<double> angles;
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const std::uint32_t t = work[i];
      verdict[t - first] = !is_protected(t) && mustPrune(t, apexes, angles);
    }
  };
  if (parallel)
    runInArena(threads_, [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 1024), judge);
    });

  std::size_t pruned = 0;
  std::vector<std::uint32_t> neighbours;
  while (!work.empty()) {
    const std::uint32_t t = work.back();
    work.pop_back();
    queued[t - first] = 0;
    if (mesh_.state(t) != kCandidate)
      continue;
    if (stale[t - first] ? is_protected(t) || !mustPrune(t, apexes_, angles_)
                         : !verdict[t - first])
      continue;
    mesh_.reject(t);
    ++pruned;
    const TriangleIndices& tri = mesh_.triangle(t);
    for (int k = 0; k < 3; ++k) {
      mesh_.trianglesOnEdge(
          tri[k], tri[(k + 1) % 3],
          [&](std::uint32_t s) {
            return mesh_.state(s) == kCandidate && mesh_.group(s) == group;
          },
          neighbours);
      for (const std::uint32_t s : neighbours) {
        stale[s - first] = 1;
        if (!queued[s - first]) {
          queued[s - first] = 1;
          work.push_back(s);
        }
      }
    }
  }
  return pruned;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
