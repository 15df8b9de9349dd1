// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/disjoint_sets.h"
#include "common/parallel.h"
#include "reconstruction/box_grid.h"
#include "reconstruction/candidates.h"
#include "reconstruction/fill.h"
#include "reconstruction/local_spacing.h"
#include "reconstruction/mesh_state.h"
#include "reconstruction/prune.h"
#include "reconstruction/stitch.h"
#include "reconstruction/walk.h"

#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/mesh_geometry.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>

namespace pcl {
namespace cocone {

bool
isValid(const ReconstructionParameters& parameters)
{
  return isValid(parameters.boundary) &&
         kTrueBoundaryRatioRange.contains(parameters.true_boundary_ratio);
}

namespace {

using Vector = Eigen::Vector3d;
using detail::Box;
using detail::BoxGrid;
using detail::boxesApart;
using detail::kCandidate;
using detail::kCoconeGroup;
using detail::kInMesh;
using detail::kLargestPolygonFill;
using detail::kPolygonGroup;
using detail::kRejected;

constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();
// How far (in local spacings) an unused sample may lie from the mesh to be put back.
constexpr double kInsertionReach = 1.0;

/** Extracts the surface. The pool holds every triangle that may become part of it: the
 * cocone candidates (group 0) and, later, the Delaunay triangles offered to each hole
 * (group k for the k-th hole). */
class Mesher
{
public:
  Mesher(const VoronoiCocone& voronoi, const ReconstructionParameters& parameters,
         ReconstructionReport& report)
      : voronoi_(voronoi), points_(voronoi.centeredPoints()), parameters_(parameters),
        report_(report), n_(voronoi.size()), mesh_(points_),
        pruner_(mesh_, report_.boundary_samples, voronoi.getNumberOfThreads()),
        pinches_(mesh_), walker_(mesh_, pinches_, voronoi.getNumberOfThreads()),
        filler_(mesh_, pinches_, parameters.true_boundary_ratio),
        stitcher_(mesh_, voronoi, spacing_, pruner_, walker_, filler_,
                  parameters.true_boundary_ratio)
  {}

  void run(std::vector<TriangleIndices>& output);

private:
  // --- stages ---------------------------------------------------------------------
  void insertUnusedSamples();
  std::size_t removeCrossings();
  template <typename Crosses>
  void findCrossingsBySuspectGrid(const std::vector<std::uint32_t>& suspects,
                                  const Crosses& crosses,
                                  std::vector<std::vector<std::uint32_t> >& crossing) const;
  void orientClosedComponentsOutward();

  const VoronoiCocone& voronoi_;
  const std::vector<Vector>& points_;
  const ReconstructionParameters& parameters_;
  ReconstructionReport& report_;
  const std::size_t n_;

  detail::MeshState mesh_;
  detail::Pruner pruner_;
  detail::PinchResolver pinches_;
  detail::Walker walker_;
  detail::PolygonFiller filler_;
  std::vector<double> spacing_; // local sample spacing
  detail::Stitcher stitcher_;
};

// ---------------------------------------------------------------------------------
// Samples left in no triangle although they lie on the surface (a hole grown over
// them, a walk that went around them, often at sharp corners) are put back by splitting
// the mesh triangle they lie over in three, or the edge they lie next to (and its two
// triangles in two), when they are within kInsertionReach local spacings of it and the
// new triangles cut nothing. Duplicates and outliers stay out.
void
Mesher::insertUnusedSamples()
{
  std::vector<SampleIndex> neighbours;
  std::vector<std::uint32_t> nearby;
  std::vector<TriangleIndices> splits;
  std::vector<std::uint32_t> nearby_edge;
  std::size_t inserted = 0;
  for (SampleIndex v = 0; v < n_; ++v) {
    if (mesh_.meshDegree(v) != 0 || voronoi_.representative(v) != v || !(spacing_[v] > 0))
      continue;
    // The mesh triangles at its Delaunay neighbours.
    voronoi_.delaunayNeighbours(v, neighbours);
    nearby.clear();
    for (const SampleIndex w : neighbours)
      mesh_.forEachAround(w, [&](std::uint32_t t) {
        if (mesh_.inMesh(t))
          nearby.push_back(t);
      });
    std::sort(nearby.begin(), nearby.end());
    nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
    // The closest point of those triangles: inside one (split it in three) or on an
    // edge shared by two (split both in two).
    // Measured in the spacing of the surface there, not of v: an outlier's own nearest
    // neighbours are far.
    const Vector p = points_[v];
    const auto reach = [&](const TriangleIndices& o) {
      return kInsertionReach *
             std::min({spacing_[o[0]], spacing_[o[1]], spacing_[o[2]]});
    };
    double best_distance = std::numeric_limits<double>::infinity();
    std::uint32_t best = 0;
    int best_edge = -1; // -1: inside the triangle; k: on its edge k -> k + 1
    for (const std::uint32_t t : nearby) {
      const TriangleIndices& o = mesh_.oriented(t);
      const Vector a = points_[o[0]], b = points_[o[1]], c = points_[o[2]];
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
        const Vector e0 = points_[o[k]], e1 = points_[o[(k + 1) % 3]];
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
    const TriangleIndices o = mesh_.oriented(best);
    std::vector<std::uint32_t> replaced = {best};
    if (best_edge < 0) {
      splits = {{o[0], o[1], v}, {o[1], o[2], v}, {o[2], o[0], v}};
    }
    else {
      const SampleIndex e0 = o[best_edge], e1 = o[(best_edge + 1) % 3];
      const SampleIndex apex_here = o[(best_edge + 2) % 3];
      mesh_.meshOnEdge(e0, e1, nearby_edge);
      if (nearby_edge.size() != 2)
        continue;
      const std::uint32_t other =
          nearby_edge[0] == best ? nearby_edge[1] : nearby_edge[0];
      const SampleIndex apex_there = mesh_.apex(other, e0, e1);
      replaced.push_back(other);
      // best traverses e0 -> e1, other e1 -> e0; keep both orientations.
      splits = {{e0, v, apex_here},
                {v, e1, apex_here},
                {e1, v, apex_there},
                {v, e0, apex_there}};
    }
    // Most nearby triangles are apart from every split, which the boxes tell first.
    Box splits_box = mesh_.boundingBox(splits[0]);
    for (const TriangleIndices& split : splits) {
      const Box box = mesh_.boundingBox(split);
      splits_box = {splits_box.low.cwiseMin(box.low), splits_box.high.cwiseMax(box.high)};
    }
    bool crossing = false;
    for (const std::uint32_t t : nearby) {
      if (crossing)
        break;
      if (std::find(replaced.begin(), replaced.end(), t) != replaced.end() ||
          boxesApart(mesh_.boundingBox(mesh_.oriented(t)), splits_box))
        continue;
      for (const TriangleIndices& split : splits)
        if (trianglesIntersect(points_, split, mesh_.oriented(t))) {
          crossing = true;
          break;
        }
    }
    if (crossing)
      continue;
    for (const std::uint32_t t : replaced)
      mesh_.leaveMesh(t);
    for (const TriangleIndices& split : splits) {
      mesh_.addToPool(split, kPolygonGroup);
      mesh_.enterMesh(static_cast<std::uint32_t>(mesh_.poolSize() - 1));
    }
    ++inserted;
  }
  report_.inserted_samples = inserted;
}

// The crossing pairs of removeCrossings when no fill has built the mesh's grid. The
// suspects are then few (mostly the triangles at a rim's boundary samples), so a grid
// of the suspects alone is asked by every mesh triangle, rather than a grid of the
// whole mesh being built for them: on a 1M-point hemisphere, whose one loop (its rim)
// stays open, stitching took 1.6 to 2.1 s with that grid, and 0.7 s without. Each pair
// is tested once, in the cell that holds the low corner of the common part of the two
// boxes, and the lists come out sorted, as the other way gives them.
template <typename Crosses>
void
Mesher::findCrossingsBySuspectGrid(
    const std::vector<std::uint32_t>& suspects, const Crosses& crosses,
    std::vector<std::vector<std::uint32_t> >& crossing) const
{
  double edges = 0;
  for (const std::uint32_t t : suspects)
    edges += (points_[mesh_.oriented(t)[0]] - points_[mesh_.oriented(t)[1]]).norm();
  BoxGrid grid(BoxGrid::cellSideFor(edges, suspects.size())); // of suspect positions
  std::vector<Box> boxes(suspects.size());
  for (std::uint32_t i = 0; i < suspects.size(); ++i) {
    boxes[i] = mesh_.boundingBox(mesh_.oriented(suspects[i]));
    grid.insert(i, boxes[i]);
  }

  using Pair = std::pair<std::uint32_t, std::uint32_t>; // suspect position, triangle
  tbb::enumerable_thread_specific<std::vector<Pair> > found;
  const auto ask = [&](const tbb::blocked_range<std::uint32_t>& range) {
    std::vector<Pair>& pairs = found.local();
    for (std::uint32_t u = range.begin(); u != range.end(); ++u) {
      if (!mesh_.inMesh(u))
        continue;
      const Box box = mesh_.boundingBox(mesh_.oriented(u));
      grid.forEachOverlapping(
          box, [&](std::uint32_t i) -> const Box& { return boxes[i]; },
          [&](std::uint32_t i) {
            if (crosses(suspects[i], boxes[i], u, box))
              pairs.emplace_back(i, u);
          });
    }
  };
  detail::runInArena(voronoi_.getNumberOfThreads(), [&] {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(
                          0, static_cast<std::uint32_t>(mesh_.poolSize()), 4096),
                      ask);
  });
  std::vector<Pair> pairs;
  for (const std::vector<Pair>& part : found)
    pairs.insert(pairs.end(), part.begin(), part.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [i, u] : pairs)
    crossing[i].push_back(u);
}

// The walk takes restricted Delaunay triangles, which cannot cross on a well-sampled
// surface; where samples are undersampled or noisy (boundary samples), and where
// triangles were added by stitching or insertion, nothing rules it out. Those
// triangles are checked against every mesh triangle near them (the grid of the
// fills' checks), and of each crossing pair the one added last is removed; the holes
// this leaves are stitched like the others (fills are checked already). Returns the
// number of triangles removed.
std::size_t
Mesher::removeCrossings()
{
  const std::vector<std::uint8_t>& boundary = report_.boundary_samples;
  std::vector<std::uint32_t> suspects;
  std::vector<std::uint8_t> is_suspect(mesh_.poolSize(), 0);
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t) {
    const TriangleIndices& o = mesh_.oriented(t);
    if (mesh_.inMesh(t) && (mesh_.group(t) != kCoconeGroup || boundary[o[0]] ||
                                 boundary[o[1]] || boundary[o[2]])) {
      suspects.push_back(t);
      is_suspect[t] = 1;
    }
  }
  if (suspects.empty())
    return 0;

  // Every crossing pair (suspect, mesh triangle), found in parallel without changing
  // anything, listed in increasing order; a pair of two suspects only from the
  // earlier one (the removals below never need it from the later one: by then one of
  // the two is out of the mesh, see there). Triangles are found near a suspect by
  // their boxes, through a grid: looking through the triangles at its corners'
  // Delaunay neighbours instead read some 30 incidence lists per suspect and cost twice
  // as much (PCL's table scene: 1.1 s against 0.55 s), and could miss a crossing
  // triangle with no corner there.
  std::vector<std::vector<std::uint32_t> > crossing(suspects.size());
  const auto crosses = [&](std::uint32_t t, const Box& t_box, std::uint32_t u,
                           const Box& u_box) {
    // Most are apart, which their boxes tell without the call (the exact test starts
    // with the same strict comparison).
    return (u > t || !is_suspect[u]) && !boxesApart(u_box, t_box) &&
           trianglesIntersect(points_, mesh_.oriented(t), mesh_.oriented(u));
  };
  if (mesh_.hasGrid()) {
    // The fills built the mesh's grid: each suspect asks it.
    tbb::enumerable_thread_specific<std::vector<std::uint32_t> > scratch;
    const auto findCrossings = [&](const tbb::blocked_range<std::size_t>& range) {
      std::vector<std::uint32_t>& nearby = scratch.local();
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const std::uint32_t t = suspects[i];
        const Box box = mesh_.boundingBox(mesh_.oriented(t));
        mesh_.meshNear(box, nearby);
        for (const std::uint32_t u : nearby)
          if (crosses(t, box, u, mesh_.boundingBox(mesh_.oriented(u))))
            crossing[i].push_back(u);
      }
    };
    detail::runInArena(voronoi_.getNumberOfThreads(), [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, suspects.size(), 64),
                        findCrossings);
    });
  }
  else {
    findCrossingsBySuspectGrid(suspects, crosses, crossing);
  }
  // Of each crossing pair the triangle added last goes, suspects in order: removals
  // only shrink the mesh, so the pairs still both in it here are exactly those a
  // sequential pass testing as it goes would meet. (A suspect u crossing a later
  // suspect t has met t here unless u left the mesh first: either way, by t's turn
  // one of them is gone, which is why t's list need not hold u.)
  std::vector<std::uint32_t> gone;
  for (std::size_t i = 0; i < suspects.size(); ++i) {
    const std::uint32_t t = suspects[i];
    if (!mesh_.inMesh(t))
      continue;
    for (const std::uint32_t u : crossing[i]) {
      if (!mesh_.inMesh(u))
        continue;
      const std::uint32_t drop = std::max(t, u);
      mesh_.leaveMesh(drop);
      gone.push_back(drop);
      if (drop == t)
        break;
    }
  }
  // A removal can leave a vertex with two fans.
  for (const std::uint32_t t : gone)
    pinches_.note(mesh_.oriented(t));
  report_.pinch_removed_triangles += pinches_.resolve();
  report_.crossing_triangles = gone.size();
  return gone.size();
}

// Closed components face outward: flip any whose signed volume is negative.
void
Mesher::orientClosedComponentsOutward()
{
  // Components of the mesh through shared vertices, by union-find over the samples.
  // Every vertex has a single fan (PinchResolver), so these are the components
  // through shared edges, found without looking up a single edge.
  detail::DisjointSets components(n_);
  const auto find = [&](SampleIndex v) { return components.find(v); };
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t)
    if (mesh_.inMesh(t)) {
      components.unite(mesh_.oriented(t)[0], mesh_.oriented(t)[1]);
      components.unite(mesh_.oriented(t)[0], mesh_.oriented(t)[2]);
    }
  // Signed volume per component (divergence theorem, up to a factor 6), summed in
  // triangle order.
  std::vector<double> volume(n_, 0);
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t)
    if (mesh_.inMesh(t)) {
      const TriangleIndices& o = mesh_.oriented(t);
      volume[find(o[0])] += points_[o[0]].dot(points_[o[1]].cross(points_[o[2]]));
    }
  // A component with a boundary edge is open: its inside is undefined.
  std::vector<std::uint8_t> open(n_, 0);
  std::vector<std::uint32_t> on_edge;
  for (const auto& [a, b] : mesh_.maybeOpen()) {
    mesh_.meshOnEdge(a, b, on_edge);
    if (on_edge.size() == 1)
      open[find(a)] = 1;
  }
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t)
    if (mesh_.inMesh(t)) {
      const SampleIndex root = find(mesh_.oriented(t)[0]);
      if (!open[root] && volume[root] < 0)
        mesh_.flip(t);
    }
}

void
Mesher::run(std::vector<TriangleIndices>& output)
{
  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now();
  const auto lap = [&](double& seconds, const char* stage) {
    const Clock::time_point now = Clock::now();
    seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    PCL_DEBUG("[pcl::cocone::reconstructSurface] %s: %.3f s\n", stage, seconds);
  };
  report_ = ReconstructionReport();
  ReconstructionReport::Timings& timings = report_.timings;
  if (parameters_.detect_boundary) {
    // The paper's flags: the completed rim row and the band describe the rim for users,
    // but whether a sample votes is the paper's decision, which its analysis rests on.
    BoundaryParameters as_published = parameters_.boundary;
    as_published.band_rings = 0;
    as_published.complete_rim_row = false;
    detectBoundarySamples(voronoi_, as_published, report_.boundary_samples);
    // Boundary samples cast no vote: when they are the majority, too few triangles are
    // chosen to cover the surface (Power Crust's 1281-point knot: 98% flagged, 11% of
    // the samples used). Say so, with the way out, rather than return a scrap silently.
    for (SampleIndex v = 0; v < n_; ++v)
      report_.distinct_boundary_samples +=
          report_.boundary_samples[v] && voronoi_.representative(v) == v;
    report_.distinct_samples = voronoi_.numUniqueSamples();
    if (report_.tooSparseForBoundaryDetection())
      PCL_WARN("[pcl::cocone::reconstructSurface] %zu of %zu distinct samples are "
               "boundary samples: the cloud is too sparse for boundary detection at rho "
               "%g, and most of the surface will stay uncovered; a larger rho or no "
               "boundary detection fits it better.\n",
               report_.distinct_boundary_samples, report_.distinct_samples,
               parameters_.boundary.ratio_bound);
  }
  else {
    report_.boundary_samples.assign(n_, 0);
  }
  lap(timings.boundary, "boundary samples");

  spacing_ = detail::measureLocalSpacing(voronoi_);
  report_.candidate_triangles =
      detail::collectCandidates(voronoi_, report_.boundary_samples, mesh_);
  report_.lid_triangles =
      detail::removeLids(mesh_, spacing_, report_.boundary_samples,
                         parameters_.true_boundary_ratio, voronoi_.getNumberOfThreads());
  lap(timings.candidates, "candidates and lids");
  report_.pruned_triangles = pruner_.prune(kCoconeGroup);
  lap(timings.pruning, "pruning");
  report_.walked_triangles = walker_.walkAll();
  report_.pinch_removed_triangles += pinches_.resolve();
  lap(timings.walk, "manifold extraction");
  // Every loop gets a turn at stitching, and another only when the mesh changed within
  // its bounding box since (a loop that stayed open would stay open again): removing
  // crossings and inserting samples change the mesh, and open holes, and so does
  // growing a hole over the triangles in the way of its fill (they need not touch it).
  if (parameters_.stitch_holes)
    stitcher_.stitchLoops();
  mesh_.logChanges(true);
  insertUnusedSamples();
  removeCrossings();
  // The holes opened by this round's growths get one more round; what the last round
  // opens stays open. A round after no change would offer nothing.
  if (parameters_.stitch_holes && mesh_.hasChanges() && stitcher_.stitchLoops() > 0 &&
      mesh_.hasChanges())
    stitcher_.stitchLoops();
  mesh_.logChanges(false);
  mesh_.clearChanges();
  report_.stitched_holes = stitcher_.stitchedHoles();
  report_.stitched_triangles = stitcher_.stitchedTriangles();
  report_.open_loops = mesh_.traceLoops();
  lap(timings.stitching, "stitching");
  orientClosedComponentsOutward();

  output.clear();
  for (std::uint32_t t = 0; t < mesh_.poolSize(); ++t)
    if (mesh_.inMesh(t))
      output.push_back(mesh_.oriented(t));
  for (SampleIndex v = 0; v < n_; ++v)
    if (mesh_.meshDegree(v) == 0)
      report_.unused_samples.push_back(v);
  lap(timings.finishing, "orientation and loops");
}

} // namespace

Status
reconstructSurface(const VoronoiCocone& voronoi,
                   const ReconstructionParameters& parameters,
                   std::vector<TriangleIndices>& triangles,
                   ReconstructionReport& report)
{
  triangles.clear();
  report = ReconstructionReport();
  if (voronoi.status() != Status::ok)
    return Status::not_computed;
  Mesher mesher(voronoi, parameters, report);
  mesher.run(triangles);
  return Status::ok;
}

} // namespace cocone
} // namespace pcl
