// SPDX-License-Identifier: GPL-3.0-or-later
// reconstructSurface: runs the mesher's stages in order, each in a room of its own
// under src/reconstruction/, over one MeshState. The pool holds every triangle that may
// become part of the surface: the cocone candidates (group 0) and, later, the Delaunay
// triangles offered to each hole (group k for the k-th hole) and the triangles of
// fills and insertions.
#include "common/progress.h"
#include "common/status_guard.h"
#include "denoise/restore.h"
#include "reconstruction/candidates.h"
#include "reconstruction/crossings.h"
#include "reconstruction/fill.h"
#include "reconstruction/local_spacing.h"
#include "reconstruction/mesh_state.h"
#include "reconstruction/orientation.h"
#include "reconstruction/prune.h"
#include "reconstruction/stitch.h"
#include "reconstruction/walk.h"

#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

namespace {

/** BOUNDARY's flags as the reconstruction uses them, into report.boundary_samples,
 * with the counts of distinct samples; all 0 when detection is off. */
void
flagBoundarySamples(const VoronoiCocone& voronoi,
                    const ReconstructionParameters& parameters,
                    ReconstructionReport& report)
{
  const std::size_t n = voronoi.size();
  report.distinct_samples = voronoi.numUniqueSamples();
  if (!parameters.detect_boundary) {
    report.boundary_samples.assign(n, 0);
    return;
  }
  // The paper's flags: the completed rim row and the band describe the rim for users,
  // but whether a sample votes is the paper's decision, which its analysis rests on.
  BoundaryParameters as_published = parameters.boundary;
  as_published.band_rings = 0;
  as_published.complete_rim_row = false;
  std::string message;
  const Status status =
      detectBoundarySamples(voronoi, as_published, report.boundary_samples, &message);
  if (status != Status::ok)
    throw detail::StageFailure{status, message};
  // Boundary samples cast no vote: when they are the majority, too few triangles would
  // be chosen to cover the surface (Power Crust's 1281-point knot: 98% flagged, 12% of
  // the samples used). runStages then falls back to no detection; say so.
  for (SampleIndex v = 0; v < n; ++v)
    report.distinct_boundary_samples +=
        report.boundary_samples[v] && voronoi.representative(v) == v;
  if (report.tooSparseForBoundaryDetection())
    PCL_WARN("[pcl::cocone::reconstructSurface] %zu of %zu distinct samples are "
             "boundary samples: the cloud is too sparse for boundary detection at rho "
             "%g, so it is reconstructed without it (every hole is closed where it "
             "can be); a larger rho fits it better if it has true boundaries.\n",
             report.distinct_boundary_samples, report.distinct_samples,
             parameters.boundary.ratio_bound);
}

/** The stages, in order, into \a output and \a report (reset first). */
void
runStages(const VoronoiCocone& voronoi, const ReconstructionParameters& parameters,
          std::vector<TriangleIndices>& output, ReconstructionReport& report,
          const ProgressCallback& callback)
{
  // Each stage reports its end as the share of a typical run done by then (measured on
  // the benchmark's scans: stitching takes the most on noisy ones).
  const detail::StageProgress progress(callback, 0, 1);
  using Clock = std::chrono::steady_clock;
  Clock::time_point start = Clock::now();
  const auto lap = [&](double& seconds, const char* stage) {
    const Clock::time_point now = Clock::now();
    seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    PCL_DEBUG("[pcl::cocone::reconstructSurface] %s: %.3f s\n", stage, seconds);
  };
  report = ReconstructionReport();
  ReconstructionReport::Timings& timings = report.timings;
  const unsigned threads = voronoi.getNumberOfThreads();
  const double ratio = parameters.true_boundary_ratio;
  detail::MeshState mesh(voronoi.centeredPoints());
  flagBoundarySamples(voronoi, parameters, report);
  lap(timings.boundary, "boundary samples");
  progress.report(0.05);

  // The sparse fallback (see tooSparseForBoundaryDetection): when most samples are
  // flagged, the flags say that the cloud is sparse, not where its rims are. Every
  // sample then votes, and no hole counts as a true boundary; candidates larger than a
  // sampled surface's triangles are dropped instead, so that the cocones of a thin,
  // sparse part do not bridge it.
  const bool sparse = report.tooSparseForBoundaryDetection();
  const std::vector<std::uint8_t> no_flags(sparse ? voronoi.size() : 0, 0);
  const std::vector<std::uint8_t>& boundary =
      sparse ? no_flags : report.boundary_samples;
  const std::vector<double> spacing = detail::measureLocalSpacing(voronoi);
  const std::vector<std::uint8_t> rim_evidence =
      sparse ? no_flags : detail::rimEvidence(voronoi, boundary, spacing);
  const detail::HoleRule rule(mesh.points(), rim_evidence, ratio);

  report.candidate_triangles = detail::collectCandidates(voronoi, boundary, mesh);
  if (sparse)
    report.candidate_triangles -=
        detail::rejectLargeCandidates(mesh, spacing, detail::kSparseCandidateRadius);
  report.lid_triangles = detail::removeLids(mesh, spacing, rule, threads);
  lap(timings.candidates, "candidates and lids");
  progress.report(0.2);

  detail::Pruner pruner(mesh, boundary, threads);
  report.pruned_triangles = pruner.prune(detail::kCoconeGroup);
  lap(timings.pruning, "pruning");
  progress.report(0.3);

  detail::PinchResolver pinches(mesh);
  detail::Walker walker(mesh, pinches, threads);
  report.walked_triangles = walker.walkAll();
  report.pinch_removed_triangles += pinches.resolve();
  lap(timings.walk, "manifold extraction");
  progress.report(0.55);

  // Every loop gets a turn at stitching, and another only when the mesh changed within
  // its bounding box since (a loop that stayed open would stay open again): removing
  // crossings and inserting samples change the mesh, and open holes, and so does
  // growing a hole over the triangles in the way of its fill (they need not touch it).
  detail::PolygonFiller filler(mesh, pinches, rule);
  detail::Stitcher stitcher(mesh, voronoi, spacing, pruner, walker, filler, rule);
  if (parameters.stitch_holes)
    stitcher.stitchLoops();
  mesh.logChanges(true);
  report.inserted_samples = detail::insertUnusedSamples(mesh, voronoi, spacing);
  const detail::CrossingRemoval crossings =
      detail::removeCrossings(mesh, pinches, boundary, threads);
  report.crossing_triangles = crossings.removed;
  report.pinch_removed_triangles += crossings.pinch_removed;
  // The holes opened by this round's growths get one more round; what the last round
  // opens stays open. A round after no change would offer nothing.
  if (parameters.stitch_holes && mesh.hasChanges() && stitcher.stitchLoops() > 0 &&
      mesh.hasChanges())
    stitcher.stitchLoops();
  mesh.logChanges(false);
  mesh.clearChanges();
  report.stitched_holes = stitcher.stitchedHoles();
  report.stitched_triangles = stitcher.stitchedTriangles();
  report.open_loops = mesh.traceLoops();
  lap(timings.stitching, "stitching");
  progress.report(0.9);

  detail::orientClosedComponentsOutward(mesh);
  output.clear();
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t)
    if (mesh.inMesh(t))
      output.push_back(mesh.oriented(t));
  for (SampleIndex v = 0; v < mesh.sampleCount(); ++v)
    if (mesh.meshDegree(v) == 0)
      report.unused_samples.push_back(v);
  lap(timings.finishing, "orientation and loops");
  progress.report(1);
}

/** The mesh was chosen on the smoothed copy of the samples: back at the input
 * positions, no triangle may cross another (see detail::restoreInputPositions); the
 * open loops and unused samples are those of the repaired mesh. */
void
restoreInputPositions(const VoronoiCocone& voronoi,
                      std::vector<TriangleIndices>& output,
                      ReconstructionReport& report)
{
  const auto start = std::chrono::steady_clock::now();
  const detail::RestoreRepair repair = detail::restoreInputPositions(
      voronoi.centeredInputPoints(), output, voronoi.getNumberOfThreads());
  report.restore_removed_triangles = repair.removed_triangles;
  report.restore_filled_triangles = repair.filled_triangles;
  // Timed to the end of the repair's bookkeeping (loops and unused samples too).
  const auto stop = [&] {
    report.timings.restore =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PCL_DEBUG("[pcl::cocone::reconstructSurface] back at the input positions: %.3f s\n",
              report.timings.restore);
  };
  if (repair.removed_triangles == 0)
    return stop();
  const MeshTopology topology = analyzeTriangleMesh(output);
  PCL_DEBUG(
      "[pcl::cocone::reconstructSurface] back at the input positions: %zu "
      "triangles removed (crossing, pinched or cut off), %zu filled in again; %zu "
      "non-manifold edges, %zu non-manifold vertices, %zu duplicates\n",
      repair.removed_triangles, repair.filled_triangles, topology.non_manifold_edges,
      topology.non_manifold_vertices, topology.duplicate_triangles);
  report.open_loops.clear();
  for (const std::vector<std::uint32_t>& loop : topology.boundary_loops)
    report.open_loops.emplace_back(loop.begin(), loop.end());
  std::vector<std::uint8_t> used(voronoi.size(), 0);
  for (const TriangleIndices& t : output)
    for (const SampleIndex v : t)
      used[v] = 1;
  report.unused_samples.clear();
  for (SampleIndex v = 0; v < voronoi.size(); ++v)
    if (!used[v])
      report.unused_samples.push_back(v);
  stop();
}

} // namespace

Status
reconstructSurface(const VoronoiCocone& voronoi,
                   const ReconstructionParameters& parameters,
                   std::vector<TriangleIndices>& triangles,
                   ReconstructionReport& report, const ProgressCallback& progress,
                   std::string* message)
{
  triangles.clear();
  report = ReconstructionReport();
  if (voronoi.status() != Status::ok) {
    detail::setMessage(message, "the reconstruction needs a diagram: compute() did not "
                                "succeed");
    return Status::not_computed;
  }
  if (!isValid(parameters)) {
    detail::setMessage(message,
                       "a parameter of the reconstruction is outside its range");
    return Status::invalid_parameter;
  }
  const Status status = detail::runGuarded("the reconstruction", message, [&] {
    runStages(voronoi, parameters, triangles, report, progress);
    if (voronoi.denoised())
      restoreInputPositions(voronoi, triangles, report);
    return Status::ok;
  });
  if (status != Status::ok) {
    std::vector<TriangleIndices>().swap(triangles);
    report = ReconstructionReport();
  }
  return status;
}

} // namespace cocone
} // namespace pcl
