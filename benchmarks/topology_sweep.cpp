// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_topology_sweep: the reconstruction's topology on area-uniform random
// samples (test/support sampleRandom) of the analytic shapes, size by size: boundary
// loops against the true ones, closed and genus, samples used, and the time of the
// whole reconstruction as a ratio to the bare CGAL Delaunay triangulation of the same
// points (docs/topology.md). Not run by the tests; single-threaded by default.
//
//   pcl_cocone_topology_sweep [-sizes 10000,100000] [-seeds 1,2] [-shapes torus,cube]
//                             [-ramp] [-noise S] [-threads N] [-intersections]
//                             [-verbose] [-repeat N]
//   pcl_cocone_topology_sweep -file cloud.ply [-verbose]   (one data file)
#include "support/noise.h"
#include "support/shapes.h"

#include <pcl/cocone/core/mesh_geometry.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <pcl/cocone/io/point_io.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/point_types.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace pcl::cocone;
namespace shapes = pcl::cocone::test;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using Clock = std::chrono::steady_clock;

double
secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/** The bare Delaunay triangulation of the points, as the benchmark's floor (translated
 * to the centroid, bulk insertion with spatial sorting, sequential). */
double
timeDelaunay(const std::vector<Eigen::Vector3d>& input)
{
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : input)
    centroid += p;
  centroid /= static_cast<double>(input.size());
  std::vector<std::pair<Point3, std::uint32_t>> points;
  points.reserve(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Eigen::Vector3d p = input[i] - centroid;
    points.emplace_back(Point3(p.x(), p.y(), p.z()), static_cast<std::uint32_t>(i));
  }
  const Clock::time_point start = Clock::now();
  Delaunay dt;
  dt.insert(points.begin(), points.end());
  return secondsSince(start);
}

std::vector<std::string>
split(const std::string& list)
{
  std::vector<std::string> items;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty())
      items.push_back(item);
  return items;
}

/** A loop runs along the true rim when at least half of its vertices lie within 3
 * spacings of it; the others are spurious. */
std::size_t
loopsOnRim(const shapes::SampledShape& shape,
           const std::vector<Eigen::Vector3d>& points,
           const std::vector<std::vector<std::uint32_t>>& loops)
{
  if (shape.closed)
    return 0;
  std::size_t on_rim = 0;
  for (const std::vector<std::uint32_t>& loop : loops) {
    std::size_t near = 0;
    for (const std::uint32_t v : loop)
      near += shape.distance_to_rim(points[v]) < 3 * shape.spacing();
    on_rim += 2 * near >= loop.size();
  }
  return on_rim;
}

/** Reconstructs the points of a file (any format the tools read) and prints its
 * topology: with -verbose, the evidence of every hole decision on a real scan. */
int
reconstructFile(const std::string& path, unsigned threads)
{
  pcl::PCLPointCloud2 blob;
  std::string why;
  if (!loadPointSamples(path, blob, &why)) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), why.c_str());
    return 1;
  }
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::fromPCLPointCloud2(blob, xyz);
  std::vector<Eigen::Vector3d> points;
  for (const pcl::PointXYZ& p : xyz)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
      points.emplace_back(p.x, p.y, p.z);
  VoronoiCocone voronoi;
  voronoi.setNumberOfThreads(threads);
  std::vector<TriangleIndices> triangles;
  ReconstructionReport report;
  if (voronoi.compute(points) != Status::ok ||
      reconstructSurface(voronoi, ReconstructionParameters(), triangles, report) !=
          Status::ok) {
    std::fprintf(stderr, "%s: the reconstruction failed\n", path.c_str());
    return 1;
  }
  const MeshTopology topology = analyzeTriangleMesh(triangles);
  std::printf("%s: %zu of %zu samples flagged, %zu loops, closed %s, genus %ld, %zu of "
              "%zu samples used\n",
              path.c_str(), report.distinct_boundary_samples, report.distinct_samples,
              topology.boundary_loops.size(), topology.isClosed() ? "yes" : "no",
              topology.genus(), points.size() - report.unused_samples.size(),
              points.size());
  return 0;
}

} // namespace

int
main(int argc, char** argv)
{
  std::vector<std::size_t> sizes = {10000, 100000};
  std::vector<std::uint32_t> seeds = {1};
  std::vector<shapes::Shape> chosen = shapes::allShapes();
  bool ramp = false, intersections = false;
  double noise = 0; // sigma of isotropic Gaussian noise, in mean spacings
  std::string file;
  unsigned threads = 1;
  unsigned tiles = 0;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "-sizes" && has_value) {
      sizes.clear();
      for (const std::string& s : split(argv[++i]))
        sizes.push_back(std::stoul(s));
    }
    else if (arg == "-seeds" && has_value) {
      seeds.clear();
      for (const std::string& s : split(argv[++i]))
        seeds.push_back(static_cast<std::uint32_t>(std::stoul(s)));
    }
    else if (arg == "-shapes" && has_value) {
      chosen.clear();
      for (const std::string& name : split(argv[++i]))
        for (const shapes::Shape shape : shapes::allShapes())
          if (name == shapeName(shape))
            chosen.push_back(shape);
    }
    else if (arg == "-threads" && has_value)
      threads = static_cast<unsigned>(std::stoul(argv[++i]));
    else if (arg == "-tiles" && has_value)
      tiles = static_cast<unsigned>(std::stoul(argv[++i]));
    else if (arg == "-repeat" && has_value)
      repeat = std::max(1, std::stoi(argv[++i]));
    else if (arg == "-ramp")
      ramp = true;
    else if (arg == "-noise" && has_value) {
      noise = std::stod(argv[++i]);
      if (!(noise >= 0) || !std::isfinite(noise)) {
        std::fprintf(stderr, "%s: -noise wants a finite sigma >= 0, in spacings\n",
                     argv[0]);
        return 2;
      }
    }
    else if (arg == "-intersections")
      intersections = true;
    else if (arg == "-verbose") // the mesher's hole decisions, on stderr
      pcl::console::setVerbosityLevel(pcl::console::L_VERBOSE);
    else if (arg == "-file" && has_value)
      file = argv[++i];
    else {
      std::fprintf(
          stderr,
          "usage: %s [-sizes n,n] [-seeds s,s] [-shapes a,b] [-ramp] [-noise S] "
          "[-threads N] [-tiles N] [-intersections] [-verbose] [-repeat N] [-file "
          "path]\n",
          argv[0]);
      return 2;
    }
  }

  if (!file.empty()) {
    if (noise > 0) {
      std::fprintf(stderr, "%s: -noise applies to the generated shapes, not to -file\n",
                   argv[0]);
      return 2;
    }
    return reconstructFile(file, threads);
  }

  if (noise > 0)
    std::printf(
        "Isotropic Gaussian noise of %g mean spacings (noise seed: seed + 1000)\n\n",
        noise);
  std::printf(
      "| shape | n | seed | loops | true | spurious | true lost | closed | genus "
      "(true) | used | non-manifold | intersections | Delaunay s | tiles | "
      "triangulated | diagram s | total s | xDT | exact |\n");
  std::printf(
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  std::size_t cases = 0, exact_cases = 0;
  for (const std::size_t n : sizes)
    for (const shapes::Shape which : chosen)
      for (const std::uint32_t seed : seeds) {
        // With -noise, the noise of seed + 1000 (not the samples' own stream).
        const shapes::SampledShape shape =
            noise > 0
                ? shapes::withGaussianNoise(shapes::sampleRandom(which, n, seed, ramp),
                                            noise, seed + 1000)
                : shapes::sampleRandom(which, n, seed, ramp);
        // The bare Delaunay and the whole reconstruction (as the classes run it:
        // spatial order, diagram, mesher) take turns, -repeat times, and the best time
        // of each counts: a burst of load on the shared machine hits both alike.
        double t_delaunay = 0, t_total = 0, t_diagram = 0, share = 0;
        unsigned tiles_used = 0;
        std::vector<Eigen::Vector3d> ordered;
        std::vector<TriangleIndices> triangles;
        ReconstructionReport report;
        std::string message;
        Status status = Status::ok;
        for (int round = 0; round < repeat && status == Status::ok; ++round) {
          const double dt = timeDelaunay(shape.points);
          t_delaunay = round == 0 ? dt : std::min(t_delaunay, dt);
          const Clock::time_point start = Clock::now();
          const std::vector<SampleIndex> order = spatialOrder(shape.points, threads);
          ordered.assign(order.size(), Eigen::Vector3d::Zero());
          for (std::size_t k = 0; k < order.size(); ++k)
            ordered[k] = shape.points[order[k]];
          pcl::cocone::VoronoiParameters parameters;
          parameters.threads = threads;
          parameters.tiles = tiles;
          VoronoiCocone voronoi(parameters);
          status = voronoi.compute(ordered);
          t_diagram = secondsSince(start);
          tiles_used = voronoi.timings().tiles;
          share = voronoi.timings().triangulated_share;
          if (status == Status::ok)
            status = reconstructSurface(voronoi, ReconstructionParameters(), triangles,
                                        report, nullptr, &message);
          const double total = secondsSince(start);
          t_total = round == 0 ? total : std::min(t_total, total);
        }
        if (status != Status::ok) {
          std::printf("| %s | %zu | %u | failed: %s |\n", shapeName(which), n, seed,
                      message.c_str());
          continue;
        }

        const MeshTopology topology = analyzeTriangleMesh(triangles);
        const std::size_t loops = topology.boundary_loops.size();
        const std::size_t on_rim = loopsOnRim(shape, ordered, topology.boundary_loops);
        const std::size_t expected = static_cast<std::size_t>(shape.boundary_loops);
        const std::size_t spurious = loops - std::min(on_rim, expected);
        const std::size_t lost = expected - std::min(on_rim, expected);
        const bool closed = topology.isClosed();
        const long genus = topology.genus();
        const bool exact = topology.isManifold() && spurious == 0 && lost == 0 &&
                           closed == shape.closed && genus == shape.genus &&
                           topology.components == 1;
        const double used = 1.0 - static_cast<double>(report.unused_samples.size()) /
                                      static_cast<double>(n);
        std::string crossing = "-";
        if (intersections)
          crossing = std::to_string(countSelfIntersections(ordered, triangles));
        ++cases;
        exact_cases += exact;
        std::printf(
            "| %s | %zu | %u | %zu | %zu | %zu | %zu | %s | %ld (%d) | %.4f | %zu | "
            "%s | %.2f | %u | %.2f | %.2f | %.2f | %.2f | %s |\n",
            shapeName(which), n, seed, loops, expected, spurious, lost,
            closed ? "yes" : "no", genus, shape.genus, used,
            topology.non_manifold_edges, crossing.c_str(), t_delaunay, tiles_used,
            share, t_diagram, t_total, t_total / t_delaunay, exact ? "yes" : "NO");
        std::fflush(stdout);
      }
  std::printf("\nexact topology: %zu of %zu\n", exact_cases, cases);
  return 0;
}
