// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/disjoint_sets.h"
#include "common/parallel.h"
#include "reconstruction/box_grid.h"
#include "reconstruction/candidates.h"
#include "reconstruction/crossings.h"
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
  report_.inserted_samples = detail::insertUnusedSamples(mesh_, voronoi_, spacing_);
  const detail::CrossingRemoval crossings = detail::removeCrossings(
      mesh_, pinches_, report_.boundary_samples, voronoi_.getNumberOfThreads());
  report_.crossing_triangles = crossings.removed;
  report_.pinch_removed_triangles += crossings.pinch_removed;
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
