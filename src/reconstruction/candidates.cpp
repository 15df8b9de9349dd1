// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/candidates.h"

#include "common/parallel.h"
#include "reconstruction/local_spacing.h"

#include <pcl/console/print.h>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

using Vector = Eigen::Vector3d;

double
circumradius(const Vector& a, const Vector& b, const Vector& c)
{
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double area2 = (b - a).cross(c - a).norm(); // twice the area
  if (!(area2 > 0))
    return std::numeric_limits<double>::infinity();
  return ab * bc * ca / (2 * area2);
}

} // namespace

// Candidates: boundary samples cast no vote. The original COCONE keeps a triangle
// marked by all three vertices, which caps open surfaces with a lid or, after pruning,
// lets them be eaten away; a union over the samples' marks (a literal reading of the
// paper's pseudo-code) adds many non-manifold edges. So a triangle is a candidate when
// every non-boundary vertex marks it, and it has one.
std::size_t
collectCandidates(const VoronoiCocone& voronoi,
                  const std::vector<std::uint8_t>& boundary, MeshState& mesh)
{
  // Nearly every marked triangle of a well sampled surface is a candidate.
  const std::size_t expected = voronoi.markedTriangles().size();
  mesh.reservePool(expected);
  for (const MarkedTriangle& t : voronoi.markedTriangles()) {
    int voters = 0;
    bool every_voter_marks = true;
    for (int k = 0; k < 3; ++k) {
      if (boundary[t.vertex[k]])
        continue;
      ++voters;
      every_voter_marks = every_voter_marks && t.isMarkedBy(k);
    }
    if (voters > 0 && every_voter_marks)
      mesh.addToPool(t.vertex, kCoconeGroup);
  }
  mesh.closeGroup();
  mesh.rebuildIncidence();
  return mesh.poolSize();
}

// Lids. A hole that is small against the local feature size leaves most samples on its
// rim flat (BOUNDARY flags only a few of them), and their cocones choose Delaunay
// triangles across it: the candidates cover the hole with a lid of triangles larger
// than those of a sampled surface (whose circumradius stays below about 0.9 local
// spacings). Oversized candidates are grouped into patches (connected through edges);
// a patch that the hole rule calls a true boundary (HoleRule: large, and flagged along
// its rim) is a lid and is removed, so the hole stays open. Large patches without
// flags along their rim are sparsely sampled flat regions (as in meshes decimated
// adaptively) or the wide gaps of a random sample, and stay. Measured on the Stanford
// bunny: without this step two of the five holes of its base stay open, with it all
// five, and no other loop.
std::size_t
removeLids(MeshState& mesh, const std::vector<double>& spacing, const HoleRule& rule,
           unsigned threads)
{
  const std::vector<Vector>& points = mesh.points();
  constexpr double kOversized = 1.25; // circumradius in local spacings
  std::vector<std::uint8_t> oversized(mesh.poolSize(), 0);
  runInArena(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, mesh.poolSize(), 4096),
                      [&](const tbb::blocked_range<std::uint32_t>& range) {
                        for (std::uint32_t t = range.begin(); t != range.end(); ++t) {
                          const TriangleIndices& tri = mesh.triangle(t);
                          const double local = std::max(
                              {spacing[tri[0]], spacing[tri[1]], spacing[tri[2]]});
                          oversized[t] =
                              circumradius(points[tri[0]], points[tri[1]],
                                           points[tri[2]]) > kOversized * local;
                        }
                      });
  });
  std::vector<std::uint8_t> seen(mesh.poolSize(), 0);
  std::vector<std::uint32_t> patch, on_edge;
  std::vector<SampleIndex> vertices, rim;
  std::size_t lids = 0;
  for (std::uint32_t start = 0; start < mesh.poolSize(); ++start) {
    if (!oversized[start] || seen[start])
      continue;
    patch.assign(1, start);
    seen[start] = 1;
    double area = 0, perimeter = 0;
    rim.clear();
    for (std::size_t head = 0; head < patch.size(); ++head) {
      const TriangleIndices& tri = mesh.triangle(patch[head]);
      area += 0.5 * (points[tri[1]] - points[tri[0]])
                        .cross(points[tri[2]] - points[tri[0]])
                        .norm();
      for (int k = 0; k < 3; ++k) {
        const SampleIndex a = tri[k], b = tri[(k + 1) % 3];
        mesh.trianglesOnEdge(
            a, b, [&](std::uint32_t s) { return oversized[s] != 0; }, on_edge);
        if (on_edge.size() == 1) {
          perimeter += (points[a] - points[b]).norm();
          rim.push_back(a);
          rim.push_back(b);
        }
        for (const std::uint32_t s : on_edge)
          if (!seen[s]) {
            seen[s] = 1;
            patch.push_back(s);
          }
      }
    }
    vertices.clear();
    for (const std::uint32_t t : patch)
      vertices.insert(vertices.end(), mesh.triangle(t).begin(), mesh.triangle(t).end());
    const double local = typicalSpacing(spacing, vertices);
    if (!isTrueBoundary(area, perimeter, local, rule.sizeRatio()))
      continue; // small: a sampling gap
    const bool lid = rule.isTrueBoundary(area, perimeter, local, rim);
    const RimFlags flags = rule.rimFlags(rim, local);
    PCL_VERBOSE(
        "[pcl::cocone::reconstructSurface] patch of %zu oversized candidates, "
        "size %.2f local spacings: %zu of %zu rim samples flagged, %zu distinct: "
        "%s\n",
        patch.size(), 2 * area / perimeter / local, flags.flagged, flags.rim,
        flags.distinct, lid ? "a lid over a true boundary" : "kept");
    if (!lid)
      continue; // a sparsely sampled region or a sampling gap, not a hole
    for (const std::uint32_t t : patch)
      mesh.reject(t);
    lids += patch.size();
  }
  return lids;
}

std::size_t
rejectLargeCandidates(MeshState& mesh, const std::vector<double>& spacing, double ratio)
{
  const std::vector<Vector>& points = mesh.points();
  std::size_t rejected = 0;
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t) {
    const TriangleIndices& tri = mesh.triangle(t);
    const double local = std::max({spacing[tri[0]], spacing[tri[1]], spacing[tri[2]]});
    if (mesh.state(t) == kCandidate &&
        circumradius(points[tri[0]], points[tri[1]], points[tri[2]]) > ratio * local) {
      mesh.reject(t);
      ++rejected;
    }
  }
  return rejected;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
