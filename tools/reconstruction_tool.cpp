// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_reconstruction and pcl_cocone_reconstruction_mpi: reconstructs an oriented
// 2-manifold (with boundary) through the samples with COCONE and boundary detection
// (Dey et al. 2001, section 3.4) and writes it as PLY, VTK or OBJ, then reports the
// mesh's topology so that a user can tell at once whether the surface came out closed
// and manifold. The MPI driver runs the same tool in every process, with a TileExchange
// (core/tile_exchange.h).
#include "reconstruction_tool.h"

#include "job_files.h"
#include "tool_common.h"

#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

using namespace pcl::cocone::tools;
using pcl::cocone::TriangleIndices;

namespace {

CommandLine
commandLine(bool distributed)
{
  std::string what = "reconstructs a triangle mesh through the samples with COCONE and "
                     "boundary detection (Dey et al., IEEE Visualization 2001): closed "
                     "surfaces come out closed, boundaries and undersampled parts stay "
                     "open.";
  if (distributed)
    what += " Run it under mpirun: every process reads INPUT, the tiles of the Voronoi "
            "diagram are dealt out among the processes, and rank 0 joins them and "
            "writes the same mesh as pcl_cocone_reconstruction (docs/scaling.md).";
  std::vector<Option> options{
      coconeAngleOption(),
      ratioBoundOption(0.99, "BOUNDARY's ratio bound r_p/h_p <= R for flat samples"),
      normalAngleOption(),
      {"-boundary_ratio", ValueKind::real, "B",
       "a hole larger than B local sample spacings is a true boundary and stays open; "
       "smaller holes are stitched; raise it to close a scan's cut",
       2, "", pcl::cocone::kTrueBoundaryRatioRange},
      flagOption(
          "-no_boundary",
          "no boundary detection: the original COCONE, for densely sampled closed "
          "smooth surfaces only"),
      flagOption("-no_stitch", "leave every hole open"),
      denoiseOption(),
      tilesOption(),
      threadsOption()};
  if (!distributed) {
    // Tiles as independent jobs (job_files.h).
    options.push_back(
        {"-jobs", ValueKind::integer, "N",
         "run as N independent jobs, e.g. a Slurm job array: jobs 1 to N-1 write their "
         "tiles next to OUTPUT, then job 0 joins them and writes the mesh (README)",
         0, "0 = one job", pcl::cocone::ParameterRange{0, 1024, false, false}});
    options.push_back({"-job", ValueKind::integer, "R",
                       "which of the -jobs N jobs this is, 0 to N-1; run 0 last, or "
                       "beside the others with -wait",
                       0, "", pcl::cocone::ParameterRange{0, 1023, false, false}});
    options.push_back(
        {"-wait", ValueKind::integer, "S",
         "job 0 may start with the others: it builds its own tiles, then waits up to S "
         "seconds for the other jobs' files (ignored by the other jobs)",
         0, "0 = the others must have finished",
         pcl::cocone::ParameterRange{0, 30 * 24 * 3600, false, false}});
  }
  options.push_back(verboseOption());
  return CommandLine(
      {distributed ? "pcl_cocone_reconstruction_mpi" : "pcl_cocone_reconstruction",
       what,
       "OUTPUT.{ply,vtk,obj}",
       {".ply", ".vtk", ".obj"},
       "the mesh: binary PLY, legacy ASCII VTK or OBJ; vertex i is input point i "
       "(points with a NaN coordinate, and points far beyond the cloud's scale, are left "
       "out and the ids after them renumbered)"},
      std::move(options));
}

/** -job R must name one of the -jobs N; checked before anything is loaded. */
void
checkJobOptions(const CommandLine& cmd)
{
  const unsigned jobs = cmd.count("-jobs"), job = cmd.count("-job");
  if (jobs == 0 && job != 0)
    fail("-job needs -jobs");
  if (jobs == 0 && cmd.count("-wait") != 0)
    fail("-wait needs -jobs");
  if (jobs > 0 && job >= jobs)
    fail("-job " + std::to_string(job) + " must be below -jobs " +
         std::to_string(jobs));
}

/** The exchange of -jobs N -job R (none for fewer than 2 jobs): its files carry the
 * input's hash and the options that shape the diagram, so that job 0 refuses tiles
 * made from anything else. */
std::shared_ptr<JobFiles>
jobFiles(const CommandLine& cmd, const pcl::PointCloud<pcl::PointXYZ>& xyz)
{
  const unsigned jobs = cmd.count("-jobs"), job = cmd.count("-job");
  if (jobs < 2)
    return nullptr;
  std::uint64_t hash = fingerprintBytes(nullptr, 0);
  for (const pcl::PointXYZ& p : xyz) {
    const float coordinates[3] = {p.x, p.y, p.z};
    hash = fingerprintBytes(coordinates, sizeof coordinates, hash);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  const std::string fingerprint =
      std::string(hex) + " n " + std::to_string(xyz.size()) + " theta " +
      formatNumber(cmd.value("-theta"), 17) + " denoise " + cmd.choice("-denoise") +
      " tiles " + std::to_string(cmd.count("-tiles"));
  return std::make_shared<JobFiles>(job, jobs, cmd.output(), fingerprint,
                                    cmd.count("-wait"));
}

/** When the reconstruction found the cloud too sparse for boundary detection, sets
 * \a note to say so, with the way out, and returns true. */
bool
sparseNote(const pcl::CoconeReconstruction<pcl::PointXYZ>& cocone, std::string& note)
{
  const pcl::cocone::ReconstructionStatistics& report = cocone.getReport();
  if (!report.tooSparseForBoundaryDetection())
    return false;
  note = std::to_string(report.distinct_boundary_samples) + " of " +
         std::to_string(report.distinct_samples) + " points are boundary samples";
  // With values far from the defaults, the parameters rather than the cloud may be the
  // reason (-alpha 0.001 flags every sample of any cloud): name them.
  const pcl::CoconeReconstruction<pcl::PointXYZ> defaults;
  std::string changed;
  const auto compare = [&](const char* option, double value, double default_value) {
    if (value != default_value)
      changed += std::string(changed.empty() ? "" : ", ") + option + " " +
                 formatNumber(value) + " (default " + formatNumber(default_value) + ")";
  };
  compare("-theta", cocone.getCoconeAngle(), defaults.getCoconeAngle());
  compare("-rho", cocone.getRatioBound(), defaults.getRatioBound());
  compare("-alpha", cocone.getNormalAngle(), defaults.getNormalAngle());
  if (changed.empty())
    note += ": the cloud is too sparse for boundary detection at rho " +
            formatNumber(cocone.getRatioBound()) +
            ", so it was reconstructed without it (every hole closed where it can be); "
            "a larger -rho keeps true boundaries open";
  else
    note += " with " + changed +
            ": these values flag most samples, so the cloud was reconstructed without "
            "boundary detection; try the defaults or a larger -rho";
  return true;
}

std::vector<pcl::Vertices>
reconstruct(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& xyz, const CommandLine& cmd,
            const std::shared_ptr<pcl::cocone::TileExchange>& exchange,
            pcl::Indices& far_points, std::size_t& unused_points,
            std::size_t& distinct_points)
{
  pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
  cocone.setInputCloud(xyz);
  cocone.setCoconeAngle(cmd.value("-theta"));
  cocone.setRatioBound(cmd.value("-rho"));
  cocone.setNormalAngle(cmd.value("-alpha"));
  cocone.setTrueBoundaryRatio(cmd.value("-boundary_ratio"));
  cocone.setBoundaryDetection(!cmd.flag("-no_boundary"));
  cocone.setHoleStitching(!cmd.flag("-no_stitch"));
  cocone.setNumberOfThreads(cmd.count("-threads"));
  unsigned tiles = static_cast<unsigned>(cmd.count("-tiles"));
  // Automatic, with several processes: one tile each.
  if (exchange && tiles == 0)
    tiles = exchange->size();
  cocone.setNumberOfTiles(tiles);
  cocone.setTileExchange(exchange);
  cocone.setDenoise(denoiseMode(cmd));
  cocone.setProgressCallback(terminalProgress());
  if (cmd.verbose())
    printDetail("Parameters",
                "theta " + formatNumber(cocone.getCoconeAngle()) + " rad, rho " +
                    formatNumber(cocone.getRatioBound()) + ", alpha " +
                    formatNumber(cocone.getNormalAngle()) + " rad, boundary ratio " +
                    formatNumber(cocone.getTrueBoundaryRatio()) +
                    ", boundary detection " +
                    (cocone.getBoundaryDetection() ? "on" : "off") + ", stitching " +
                    (cocone.getHoleStitching() ? "on" : "off"));

  std::vector<pcl::Vertices> polygons;
  if (exchange && exchange->rank() != 0) {
    // Another process's share of the tiles: it sends them to rank 0 and is done.
    cocone.reconstruct(polygons);
    if (!cocone.getErrorMessage().empty())
      fail(cocone.getErrorMessage());
    return polygons;
  }
  computeStage("the COCONE surface", "triangles",
               [&](std::string& reason) -> std::optional<std::size_t> {
                 cocone.reconstruct(polygons);
                 // Coplanar input and the like give no polygon; so does a cloud too
                 // sparse for the cocones to choose any triangle.
                 if (polygons.empty()) {
                   reason = cocone.getErrorMessage();
                   if (reason.empty() && sparseNote(cocone, reason))
                     reason = "no triangle: " + reason;
                   return std::nullopt;
                 }
                 return polygons.size();
               });

  printWarning(cocone.getWarningMessage());
  far_points = cocone.getFarIndices();
  unused_points = cocone.getUnusedIndices().size();
  distinct_points = cocone.getReport().distinct_samples;
  // The library's warning is silenced without -v (QuietPcl): repeat it as a note.
  std::string note;
  if (sparseNote(cocone, note))
    pcl::console::print_info("note: %s\n", note.c_str());
  if (cmd.verbose()) {
    const pcl::cocone::ReconstructionStatistics& report = cocone.getReport();
    std::size_t boundary_samples = 0;
    for (const std::uint8_t flag : cocone.getBoundarySamples())
      boundary_samples += flag;
    printDetail("Boundary samples", std::to_string(boundary_samples));
    printDetail("Candidate triangles",
                std::to_string(cocone.getNumberOfCandidateTriangles()));
    printDetail("Lid triangles removed",
                std::to_string(cocone.getNumberOfLidTriangles()));
    printDetail("Pruned triangles",
                std::to_string(cocone.getNumberOfPrunedTriangles()));
    printDetail("Walked triangles", std::to_string(report.walked_triangles));
    printDetail("Removed at pinched vertices",
                std::to_string(report.pinch_removed_triangles));
    printDetail("Stitched holes",
                std::to_string(cocone.getNumberOfStitchedHoles()) + " (" +
                    std::to_string(cocone.getNumberOfStitchedTriangles()) +
                    " triangles)");
    printDetail("Samples put back", std::to_string(report.inserted_samples));
    printDetail("Crossing triangles removed",
                std::to_string(report.crossing_triangles));
    printDetail("Open boundary loops",
                std::to_string(cocone.getBoundaryLoops().size()));
    printDetail("Unused points", std::to_string(cocone.getUnusedIndices().size()));
  }
  return polygons;
}

/** The polygons as triangles of input indices; a polygon that is no triangle would be
 * a bug of the class. */
std::vector<TriangleIndices>
asTriangles(const std::vector<pcl::Vertices>& polygons)
{
  std::vector<TriangleIndices> triangles;
  triangles.reserve(polygons.size());
  for (const pcl::Vertices& polygon : polygons) {
    if (polygon.vertices.size() != 3)
      fail("internal error: the reconstruction returned a polygon that is no triangle");
    TriangleIndices t;
    for (int k = 0; k < 3; ++k) {
      if (polygon.vertices[k] < 0)
        fail("internal error: a triangle uses a negative index");
      t[k] = static_cast<std::uint32_t>(polygon.vertices[k]);
    }
    triangles.push_back(t);
  }
  return triangles;
}

} // namespace

namespace pcl {
namespace cocone {
namespace tools {

int
runReconstructionTool(int argc, char** argv,
                      const std::shared_ptr<pcl::cocone::TileExchange>& exchange)
{
  CommandLine cmd = commandLine(exchange != nullptr);
  cmd.parse(argc, argv);
  if (!exchange)
    checkJobOptions(cmd);

  const pcl::PointCloud<pcl::PointXYZ>::Ptr xyz =
      toXyz(loadCloud(cmd.input(), cmd.verbose()));
  const std::shared_ptr<JobFiles> job_files = exchange ? nullptr : jobFiles(cmd, *xyz);
  const std::shared_ptr<pcl::cocone::TileExchange> shared =
      job_files ? job_files : exchange;
  if (job_files && job_files->rank() == 0) {
    try {
      job_files->checkOthersReady();
    }
    catch (const std::exception& e) {
      fail(e.what());
    }
  }
  pcl::Indices far_points;
  std::size_t unused = 0, distinct = 0;
  const std::vector<pcl::Vertices> polygons =
      reconstruct(xyz, cmd, shared, far_points, unused, distinct);
  if (shared && shared->rank() != 0) {
    if (job_files)
      pcl::console::print_info("job %u of %u: tiles written to %s\n", job_files->rank(),
                               job_files->size(),
                               job_files->fileOf(job_files->rank()).c_str());
    return 0;
  }
  // The finite points that are not far, in input order, the triangles renumbered: the
  // io library's mesh as written, shared with the Python module's Mesh.save.
  pcl::cocone::MeshForWriting mesh;
  std::string error;
  if (!pcl::cocone::meshForWriting(*xyz, asTriangles(polygons), far_points, mesh,
                                   &error))
    fail("internal error: " + error);
  if (mesh.non_finite_dropped > 0)
    pcl::console::print_info("note: %zu non-finite input points dropped; vertex ids "
                             "renumbered\n",
                             mesh.non_finite_dropped);
  if (mesh.far_dropped > 0)
    pcl::console::print_info("note: %zu far input points dropped; vertex ids "
                             "renumbered\n",
                             mesh.far_dropped);
  saveMesh(cmd.output(), mesh.vertices, mesh.triangles);
  if (job_files)
    job_files->removeFiles();

  const pcl::cocone::MeshTopology topology =
      pcl::cocone::analyzeTriangleMesh(mesh.triangles);
  pcl::console::print_info(
      "vertices used %zu, triangles %zu, boundary loops %zu, Euler characteristic %ld, "
      "closed %s, manifold %s\n",
      topology.vertices, topology.triangles, topology.boundary_loops.size(),
      topology.eulerCharacteristic(), topology.isClosed() ? "yes" : "no",
      topology.isManifold() ? "yes" : "no");
  // Every input point is in the mesh or accounted for here (getUnusedIndices()): the
  // points with a NaN coordinate or far beyond the cloud, the repeats of a position
  // (their first occurrence is the vertex), and those the mesh leaves out: outliers,
  // and samples of parts too thin or too sparse for a manifold through them.
  const std::size_t measured = xyz->size() - mesh.non_finite_dropped - mesh.far_dropped;
  if (distinct > measured ||
      unused < mesh.non_finite_dropped + mesh.far_dropped + (measured - distinct))
    fail("internal error: the unused points do not add up");
  const std::size_t duplicates = measured - distinct;
  pcl::console::print_info(
      "unused points %zu of %zu: %zu non-finite, %zu far, %zu duplicates, %zu left out "
      "of the mesh (outliers, undersampled parts)\n",
      unused, xyz->size(), mesh.non_finite_dropped, mesh.far_dropped, duplicates,
      unused - mesh.non_finite_dropped - mesh.far_dropped - duplicates);
  return 0;
}

} // namespace tools
} // namespace cocone
} // namespace pcl
