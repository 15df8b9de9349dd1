// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reconstruction section: the Delaunay floor, our core alone, pcl::CoconeReconstruction
// and the peers pcl::GreedyProjectionTriangulation, pcl::Poisson and CGAL's advancing
// front surface reconstruction, on every input; with the paper's Table 1 beside ours.
#include "bench_quality.h"
#include "sections.h"

#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/common/io.h>
#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/gp3.h>
#include <pcl/surface/poisson.h>

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Scale_space_reconstruction_3/Advancing_front_mesher.h>
#include <CGAL/Scale_space_reconstruction_3/Jet_smoother.h>
#include <CGAL/Scale_space_surface_reconstruction_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>

namespace pcl {
namespace cocone {
namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

/** Peers are left out on inputs of this many points and more with --quick. */
constexpr std::size_t kQuickPeerLimit = 100000;
/** Generated shapes this large are not sampled as a torus: largeTorus() is that one. */
constexpr std::size_t kLargeSize = 1000000;
/** The largest random-sampled input the peers run on. */
constexpr std::size_t kRandomPeerLimit = 100000;

std::vector<TriangleIndices>
toTriangles(const std::vector<pcl::Vertices>& polygons)
{
  std::vector<TriangleIndices> triangles;
  triangles.reserve(polygons.size());
  for (const pcl::Vertices& p : polygons)
    for (std::size_t k = 1; k + 1 < p.vertices.size(); ++k)
      triangles.push_back({static_cast<std::uint32_t>(p.vertices[0]),
                           static_cast<std::uint32_t>(p.vertices[k]),
                           static_cast<std::uint32_t>(p.vertices[k + 1])});
  return triangles;
}

// ---------------------------------------------------------------------------------
// The methods. Each fills a Measurement inside a forked child.

/** The floor: CGAL's 3D Delaunay triangulation (EPICK, vertices with an index, bulk
 * insertion with spatial sorting), on the points translated to their centroid, as our
 * core builds it. Sequential, as in our core. */
void
runDelaunay(const Input& input, Measurement& m)
{
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : input.points)
    centroid += p;
  centroid /= static_cast<double>(input.points.size());
  std::vector<std::pair<Point3, std::uint32_t>> points;
  points.reserve(input.points.size());
  for (std::size_t i = 0; i < input.points.size(); ++i) {
    const Eigen::Vector3d p = input.points[i] - centroid;
    points.emplace_back(Point3(p.x(), p.y(), p.z()), static_cast<std::uint32_t>(i));
  }
  Delaunay dt;
  AlgorithmMeter meter;
  dt.insert(points.begin(), points.end());
  meter.stop(m);
  m.values["cells"] = static_cast<double>(dt.number_of_finite_cells());
}

/** Our core alone: VoronoiCocone::compute (triangulation and per-sample geometry), on
 * the points in spatial order as the PCL classes give them (the ordering is timed). */
void
runCore(const Input& input, Measurement& m)
{
  VoronoiCocone voronoi;
  AlgorithmMeter meter;
  const std::vector<SampleIndex> order = spatialOrder(input.points);
  std::vector<Eigen::Vector3d> ordered(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    ordered[k] = input.points[order[k]];
  const Status status = voronoi.compute(ordered);
  meter.stop(m);
  if (status != Status::ok) {
    m.error = voronoi.errorMessage();
    return;
  }
  m.values["t_delaunay"] = voronoi.timings().delaunay;
  m.values["t_geometry"] = voronoi.timings().geometry;
}

void
runCocone(const Input& input, bool quality, Measurement& m)
{
  pcl::CoconeReconstruction<pcl::PointXYZ> reconstruction;
  reconstruction.setInputCloud(input.cloud);
  std::vector<pcl::Vertices> polygons;
  AlgorithmMeter meter;
  reconstruction.reconstruct(polygons);
  meter.stop(m);
  if (!reconstruction.getErrorMessage().empty()) {
    m.error = reconstruction.getErrorMessage();
    return;
  }
  const ReconstructionStatistics& report = reconstruction.getReport();
  m.values["t_boundary"] = report.timings.boundary;
  m.values["t_candidates"] = report.timings.candidates;
  m.values["t_pruning"] = report.timings.pruning;
  m.values["t_walk"] = report.timings.walk;
  m.values["t_stitching"] = report.timings.stitching;
  m.values["t_finishing"] = report.timings.finishing;
  m.values["t_restore"] = report.timings.restore;
  m.values["stitched_holes"] = static_cast<double>(report.stitched_holes);
  m.values["unused"] = static_cast<double>(reconstruction.getUnusedIndices().size());
  if (quality)
    recordMeshQuality(input, input.points, toTriangles(polygons), true, m);
}

/** Normals as PCL's tutorials compute them: NormalEstimation, k = 20 neighbours.
 * With \a outward, each normal is flipped to point away from the centroid (the
 * consistent orientation Poisson needs; right for star-shaped objects only). */
pcl::PointCloud<pcl::PointNormal>::Ptr
estimateNormals(const Input& input, bool outward)
{
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  estimation.setInputCloud(input.cloud);
  estimation.setSearchMethod(tree);
  estimation.setKSearch(20);
  pcl::PointCloud<pcl::Normal> normals;
  estimation.compute(normals);
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  pcl::concatenateFields(*input.cloud, normals, *cloud);
  if (outward) {
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    for (const pcl::PointXYZ& p : *input.cloud)
      centroid += p.getVector3fMap();
    centroid /= static_cast<float>(input.cloud->size());
    for (pcl::PointNormal& p : *cloud)
      if ((p.getVector3fMap() - centroid).dot(p.getNormalVector3fMap()) < 0)
        p.getNormalVector3fMap() *= -1.0f;
  }
  return cloud;
}

void
runGreedyProjection(const Input& input, bool quality, Measurement& m)
{
  AlgorithmMeter meter;
  const auto cloud = estimateNormals(input, false);
  m.values["t_normals"] = meter.elapsed();
  auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointNormal>>();
  tree->setInputCloud(cloud);
  pcl::GreedyProjectionTriangulation<pcl::PointNormal> gp3;
  // PCL's greedy projection tutorial, with the radius scaled to the sampling: 3 mean
  // nearest-neighbour spacings.
  gp3.setSearchRadius(3.0 * input.spacing);
  gp3.setMu(2.5);
  gp3.setMaximumNearestNeighbors(100);
  gp3.setMaximumSurfaceAngle(M_PI / 4);
  gp3.setMinimumAngle(M_PI / 18);
  gp3.setMaximumAngle(2 * M_PI / 3);
  gp3.setNormalConsistency(false);
  gp3.setInputCloud(cloud);
  gp3.setSearchMethod(tree);
  std::vector<pcl::Vertices> polygons;
  gp3.reconstruct(polygons);
  meter.stop(m);
  if (quality)
    recordMeshQuality(input, input.points, toTriangles(polygons), true, m);
}

void
runPoisson(const Input& input, bool quality, Measurement& m)
{
  AlgorithmMeter meter;
  const auto with_normals = estimateNormals(input, true);
  // Points whose neighbourhood gave no normal (duplicates, degenerate spots) cannot
  // take part.
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  cloud->reserve(with_normals->size());
  for (const pcl::PointNormal& p : *with_normals)
    if (std::isfinite(p.normal_x) && std::isfinite(p.normal_y) &&
        std::isfinite(p.normal_z))
      cloud->push_back(p);
  m.values["t_normals"] = meter.elapsed();
  pcl::Poisson<pcl::PointNormal> poisson;
  const int depth = input.size() <= 100000 ? 8 : 9;
  poisson.setDepth(depth);
  poisson.setThreads(
      static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  poisson.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointNormal> vertices;
  std::vector<pcl::Vertices> polygons;
  poisson.reconstruct(vertices, polygons);
  meter.stop(m);
  m.values["depth"] = depth;
  if (quality) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(vertices.size());
    for (const pcl::PointNormal& p : vertices)
      points.emplace_back(p.x, p.y, p.z);
    recordMeshQuality(input, points, toTriangles(polygons), false, m);
  }
}

/** CGAL's triangles (indices into the input) as ours. */
template <typename Facets>
std::vector<TriangleIndices>
fromCgalFacets(const Facets& facets)
{
  std::vector<TriangleIndices> triangles;
  triangles.reserve(facets.size());
  for (const auto& f : facets)
    triangles.push_back({static_cast<std::uint32_t>(f[0]),
                         static_cast<std::uint32_t>(f[1]),
                         static_cast<std::uint32_t>(f[2])});
  return triangles;
}

std::vector<Point3>
cgalPoints(const Input& input)
{
  std::vector<Point3> points;
  points.reserve(input.points.size());
  for (const Eigen::Vector3d& p : input.points)
    points.emplace_back(p.x(), p.y(), p.z());
  return points;
}

void
runAdvancingFront(const Input& input, bool quality, Measurement& m)
{
  const std::vector<Point3> points = cgalPoints(input);
  std::vector<std::array<std::size_t, 3>> facets;
  AlgorithmMeter meter;
  CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(),
                                               std::back_inserter(facets));
  meter.stop(m);
  if (quality)
    recordMeshQuality(input, input.points, fromCgalFacets(facets), true, m);
}

/** CGAL's scale-space reconstruction as its manual's example runs it: 4 rounds of jet
 * smoothing (12 neighbours, degree 2), then the advancing front on the smoothed points
 * (no bound on the edge length). The triangles index the input points, so that its
 * mesh interpolates them as ours does. Single-threaded (CGAL_LINKED_WITH_TBB is not
 * defined here). */
void
runScaleSpace(const Input& input, bool quality, Measurement& m)
{
  using ScaleSpace = CGAL::Scale_space_surface_reconstruction_3<Kernel>;
  using Smoother = CGAL::Scale_space_reconstruction_3::Jet_smoother<Kernel>;
  using Mesher = CGAL::Scale_space_reconstruction_3::Advancing_front_mesher<Kernel>;
  const std::vector<Point3> points = cgalPoints(input);
  AlgorithmMeter meter;
  ScaleSpace reconstruction(points.begin(), points.end());
  reconstruction.increase_scale(4, Smoother());
  reconstruction.reconstruct_surface(Mesher());
  meter.stop(m);
  if (quality) {
    const std::vector<std::array<std::size_t, 3>> facets(reconstruction.facets_begin(),
                                                         reconstruction.facets_end());
    recordMeshQuality(input, input.points, fromCgalFacets(facets), true, m);
  }
}

// ---------------------------------------------------------------------------------

struct MethodRun
{
  std::string method;
  Measurement m;
};

struct InputRun
{
  const Input* input = nullptr;
  Measurement delaunay;
  Measurement core;
  std::vector<MethodRun> methods; // ours first
  bool peers = false;

  const Measurement*
  find(const std::string& method) const
  {
    for (const MethodRun& r : methods)
      if (r.method == method)
        return r.m.ok ? &r.m : nullptr;
    return nullptr;
  }
};

const char* const kOurs = "CoconeReconstruction";
const char* const kGreedy = "GreedyProjection";
const char* const kPoisson = "Poisson";
const char* const kFront = "AdvancingFront";
const char* const kScaleSpace = "ScaleSpace+AF";

std::string
yesNo(double value)
{
  if (std::isnan(value))
    return "-";
  return value != 0 ? "yes" : "no";
}

std::string
integerOrDash(double value)
{
  if (std::isnan(value))
    return "-";
  return count(value);
}

InputRun
runInput(Context& context, const Input& input)
{
  context.noteInput(input);
  InputRun run;
  run.input = &input;
  const std::size_t n = input.size();
  const int repeats = Context::repeatsFor(n);
  const double timeout = context.options.timeout;
  progress("reconstruction: " + input.name + " (" + std::to_string(n) + " points)");
  // Every method takes its turn in each round, so that a burst of load on the shared
  // machine hits the floor, ours and the peers alike. The floor, the core and ours run
  // every round whatever their time: their ratios are the targets.
  std::vector<Contestant> contestants = {
      {[&](int, Measurement& m) { runDelaunay(input, m); }, kNoBudget},
      {[&](int, Measurement& m) { runCore(input, m); }, kNoBudget},
      {[&](int r, Measurement& m) { runCocone(input, r == 0, m); }, kNoBudget}};
  // The random samples are there for our topology at the sizes users have; the peers
  // meet them up to kRandomPeerLimit, where their topology is compared too (beyond it,
  // 18 more runs of each peer at 1M and 4M would double the benchmark's time).
  run.peers = !(context.options.quick && n >= kQuickPeerLimit) &&
              !(input.kind == "random" && n > kRandomPeerLimit) &&
              !context.options.no_peers;
  if (run.peers) {
    contestants.push_back(
        {[&](int r, Measurement& m) { runGreedyProjection(input, r == 0, m); },
         Context::kPeerBudget});
    contestants.push_back({[&](int r, Measurement& m) { runPoisson(input, r == 0, m); },
                           Context::kPeerBudget});
    contestants.push_back(
        {[&](int r, Measurement& m) { runAdvancingFront(input, r == 0, m); },
         Context::kPeerBudget});
    // Scale space is the peer made for noise: it meets the noisy inputs and the scans.
    if (input.kind == "noisy" || input.kind == "real scan")
      contestants.push_back(
          {[&](int r, Measurement& m) { runScaleSpace(input, r == 0, m); },
           Context::kPeerBudget});
  }
  const std::vector<Measurement> results = takeTurns(repeats, contestants, timeout);
  run.delaunay = results[0];
  run.core = results[1];
  run.methods.push_back({kOurs, results[2]});
  if (run.peers) {
    run.methods.push_back({kGreedy, results[3]});
    run.methods.push_back({kPoisson, results[4]});
    run.methods.push_back({kFront, results[5]});
    if (results.size() > 6)
      run.methods.push_back({kScaleSpace, results[6]});
  }
  std::ostringstream line;
  line << "  Delaunay " << seconds(run.delaunay.seconds) << " s";
  for (const MethodRun& r : run.methods)
    line << ", " << r.method << " "
         << (r.m.ok ? seconds(r.m.seconds) + " s" : "failed (" + r.m.error + ")");
  progress(line.str());
  return run;
}

std::string
failure(const Measurement& m)
{
  return "failed: " + m.error;
}

} // namespace

void
runReconstructionSection(Context& context)
{
  std::vector<const Input*> inputs;
  for (const FileSpec& spec : dataFiles())
    if (context.selected(spec.name))
      if (const Input* input = context.fileInput(spec.name))
        inputs.push_back(input);
  if (context.selected("knot-10k"))
    inputs.push_back(&context.generated("knot", 10000));
  for (const std::size_t n : generatedSizes(context.options.quick))
    for (const GeneratedShape& g : generatedShapes()) {
      if (n >= kLargeSize && g.name == "torus")
        continue; // the jittered torus below is the 1M torus
      if (context.selected(generatedName(g.name, n)))
        inputs.push_back(&context.generated(g.name, n));
    }
  if (!context.options.quick && context.selected("torus-1M"))
    inputs.push_back(&context.largeTorus());
  if (!context.options.quick)
    for (const NoisySpec& spec : noisyInputs())
      if (context.selected(noisyName(spec)))
        inputs.push_back(&context.noisy(spec));
  for (const std::size_t n : context.options.random_sizes)
    for (const test::Shape shape : test::allShapes())
      if (context.selected(randomName(shape, n)))
        inputs.push_back(&context.randomSampled(shape, n));

  std::vector<InputRun> runs;
  for (const Input* input : inputs)
    runs.push_back(runInput(context, *input));

  Report& report = context.report;
  report.heading(2, "Reconstruction");
  report.paragraph(
      "Methods: **CoconeReconstruction** (ours, default parameters, all cores through TBB); "
      "**GreedyProjection** (pcl::GreedyProjectionTriangulation: normals from "
      "pcl::NormalEstimation with k = 20 as in PCL's tutorial, search radius 3 mean "
      "spacings, mu 2.5, at most 100 neighbours, surface angle pi/4, triangle angles "
      "pi/18 to 2pi/3; single-threaded; its time includes the normals); **Poisson** "
      "(pcl::Poisson, depth 8 up to 100k points and 9 above, other parameters PCL's "
      "defaults, OpenMP threads = cores; normals as above, flipped to point away from the "
      "centroid, which orients them consistently only on star-shaped objects; its time "
      "includes the normals; it creates new vertices, so 'used' is N/A); "
      "**AdvancingFront** (CGAL::advancing_front_surface_reconstruction with its default "
      "parameters, single-threaded); **ScaleSpace+AF**, on the noisy inputs and the real "
      "scans only (CGAL::Scale_space_surface_reconstruction_3 as its manual's example: 4 "
      "rounds of Jet_smoother with 12 neighbours, then Advancing_front_mesher with no "
      "length bound, single-threaded; its triangles join the input points). 'xDT' is the time over the bare CGAL Delaunay "
      "triangulation of the same points in the same run. Distances are two-sided (mesh to "
      "reference: its vertices and one random point per triangle; reference to mesh: up to "
      "100k points spread over the reference), in mean spacings; H is the larger maximum, "
      "'mean' the average of the two mean distances. Self-intersections are counted by "
      "pcl::cocone::countSelfIntersections (exact predicates), skipped above " +
      count(static_cast<double>(kSelfIntersectionLimit)) + " triangles.");

  // --- Delaunay floor and core ---------------------------------------------------
  report.heading(3, "Delaunay floor and our core");
  report.paragraph(
      "DT: bare CGAL Delaunay_triangulation_3 (EPICK, points with info, bulk "
      "insertion), single-threaded: what plain CGAL gives (our core runs the same "
      "spatial sort on every core, then the same insertion). Core: spatialOrder, then "
      "VoronoiCocone::compute, whose timings() split the triangulation (duplicates "
      "included) from the per-sample Voronoi geometry (poles, heights, cocone radii, "
      "marked triangles; parallel). geometry/DT uses the core's own split of the same "
      "run. Peak: resident memory growth.");
  Table floor({"input", "points", "DT s", "DT peak MB", "core s", "core DT part s",
               "geometry s", "geometry/DT", "core/DT", "core peak MB", "ours s",
               "ours/DT", "ours peak MB"});
  double worst_geometry = 0;
  std::string worst_geometry_input;
  std::vector<std::string> geometry_misses;
  for (const InputRun& r : runs) {
    const double dt = r.delaunay.ok ? r.delaunay.seconds : kNaN;
    const double geometry = r.core.value("t_geometry");
    const double core_dt = r.core.value("t_delaunay");
    const double share = geometry / core_dt;
    if (r.core.ok && std::isfinite(share)) {
      if (share > worst_geometry) {
        worst_geometry = share;
        worst_geometry_input = r.input->name;
      }
      if (share > 0.5)
        geometry_misses.push_back(r.input->name + " " + sig(share, 2));
    }
    const Measurement* ours = r.find(kOurs);
    floor.add(
        {r.input->name, count(static_cast<double>(r.input->size())),
         r.delaunay.ok ? seconds(dt) : failure(r.delaunay), sig(r.delaunay.peak_mb, 3),
         r.core.ok ? seconds(r.core.seconds) : failure(r.core), seconds(core_dt),
         seconds(geometry), sig(share, 2), ratio(r.core.seconds / dt),
         sig(r.core.peak_mb, 3), ours ? seconds(ours->seconds) : "failed",
         ours ? ratio(ours->seconds / dt) : "-", ours ? sig(ours->peak_mb, 3) : "-"});
  }
  report.table(floor);
  if (!runs.empty())
    context.setTarget("core geometry", "per-sample geometry <= 0.5x the Delaunay time",
                      geometry_misses.empty() ? 1 : 0,
                      "worst geometry/DT " + sig(worst_geometry, 2) + " (" +
                          worst_geometry_input + ")" +
                          (geometry_misses.empty()
                               ? ""
                               : "; above 0.5 on " +
                                     std::to_string(geometry_misses.size()) + " of " +
                                     std::to_string(runs.size()) + " inputs"));

  // --- paper Table 1 ------------------------------------------------------------
  Table paper({"paper model", "paper points", "paper triangles", "paper s (PIII 933)",
               "our input", "points", "triangles", "ours s", "ours xDT", "note"});
  for (const InputRun& r : runs) {
    if (!r.input->paper)
      continue;
    const PaperReconstructionRow& p = *r.input->paper;
    const Measurement* ours = r.find(kOurs);
    paper.add({p.name, count(p.points), count(p.triangles), count(p.seconds),
               r.input->name, count(static_cast<double>(r.input->unique)),
               ours ? count(ours->value("triangles")) : "failed",
               ours ? seconds(ours->seconds) : "-",
               ours ? ratio(ours->seconds / r.delaunay.seconds) : "-", r.input->note});
  }
  if (!paper.empty()) {
    report.heading(3, "Beside the paper's Table 1");
    report.paragraph(
        "ENGINE (11360) and OILPUMP (30931) are not available. A closed surface through n "
        "samples has about 2n triangles (2n - 4 + 4g).");
    report.table(paper);
  }

  // --- quality per input ----------------------------------------------------------
  report.heading(3, "Time, memory and quality per input");
  Table quality({"input", "method", "s", "xDT", "peak MB", "triangles", "used",
                 "NM edges", "NM vertices", "loops", "closed", "chi", "genus",
                 "oriented", "self-int.", "H", "mean"});
  for (const InputRun& r : runs) {
    for (const MethodRun& mr : r.methods) {
      const Measurement& m = mr.m;
      if (!m.ok) {
        quality.add({r.input->name, mr.method, failure(m)});
        continue;
      }
      std::string s = seconds(m.seconds);
      if (m.has("t_normals"))
        s += " (normals " + seconds(m.value("t_normals")) + ")";
      std::string method = mr.method;
      if (m.has("depth"))
        method += " d" + std::to_string(static_cast<int>(m.value("depth")));
      const double self = m.value("self_intersections");
      quality.add(
          {r.input->name, method, s, ratio(m.seconds / r.delaunay.seconds),
           sig(m.peak_mb, 3), count(m.value("triangles")),
           std::isnan(m.value("used")) ? "N/A" : percent(m.value("used"), 2),
           count(m.value("nm_edges")), count(m.value("nm_vertices")),
           integerOrDash(m.value("loops")), yesNo(m.value("closed")),
           count(m.value("chi")), m.value("genus") < 0 ? "-" : count(m.value("genus")),
           yesNo(m.value("oriented")), std::isnan(self) ? "skipped" : count(self),
           sig(m.value("d_hausdorff"), 2), sig(m.value("d_mean"), 2)});
    }
    if (!r.peers)
      quality.add({r.input->name, "(peers)",
                   context.options.no_peers ? "not run (--ours-only)"
                   : context.options.quick  ? "not run (--quick)"
                                            : "not run (random sample above 100k)"});
  }
  report.table(quality);
  report.paragraph(
      "Reference topology of each input: see the Inputs table. 'loops' counts boundary "
      "loops (only defined when the mesh is manifold); genus '-' means the mesh is not an "
      "orientable manifold.");

  // --- stage breakdown of ours on the largest input ------------------------------
  const InputRun* largest = nullptr;
  for (const InputRun& r : runs)
    if (r.find(kOurs) && (!largest || r.input->size() > largest->input->size()))
      largest = &r;
  if (largest) {
    const Measurement& m = *largest->find(kOurs);
    report.heading(3, "Where our time goes (" + largest->input->name + ")");
    Table stages({"stage", "s", "share of the CoconeReconstruction total", "xDT"});
    const double dt = largest->delaunay.seconds;
    const auto add = [&](const std::string& stage, double s) {
      stages.add({stage, seconds(s), percent(s / m.seconds), ratio(s / dt)});
    };
    add("bare Delaunay (its own run)", dt);
    add("core alone: Delaunay (its own run)", largest->core.value("t_delaunay"));
    add("core alone: geometry (its own run)", largest->core.value("t_geometry"));
    add("CoconeReconstruction: core (smoothing where on, Delaunay, geometry; by "
        "difference)",
        m.seconds - m.value("t_boundary") - m.value("t_candidates") -
            m.value("t_pruning") - m.value("t_walk") - m.value("t_stitching") -
            m.value("t_finishing") - m.value("t_restore"));
    add("BOUNDARY", m.value("t_boundary"));
    add("candidates, spacing, lids", m.value("t_candidates"));
    add("pruning", m.value("t_pruning"));
    add("walk", m.value("t_walk"));
    add("stitching", m.value("t_stitching"));
    add("finishing", m.value("t_finishing"));
    add("back at the input positions (denoised only)", m.value("t_restore"));
    add("total CoconeReconstruction", m.seconds);
    report.table(stages);
  }

  // --- targets ------------------------------------------------------------------
  // A closed mesh through few of the samples is no success either: a closed input
  // counts only with 0 loops and 95% of its samples in the mesh.
  std::vector<std::string> nonmanifold, holes, sparse, other_loops;
  std::size_t closed_inputs = 0, open_inputs = 0;
  for (const InputRun& r : runs) {
    const Measurement* ours = r.find(kOurs);
    if (!ours) {
      nonmanifold.push_back(r.input->name + " (failed)");
      continue;
    }
    if (ours->value("nm_edges") > 0)
      nonmanifold.push_back(r.input->name + " " + count(ours->value("nm_edges")));
    const double loops = ours->value("loops");
    const bool few_used = ours->value("used") < 0.95;
    if (r.input->closed == 1) {
      ++closed_inputs;
      if (!(loops == 0))
        holes.push_back(r.input->name + " " + integerOrDash(loops) + " loops");
      else if (few_used)
        holes.push_back(r.input->name + " closed through " +
                        percent(ours->value("used"), 0) + " of the samples");
      continue;
    }
    if (few_used)
      sparse.push_back(r.input->name + " " + percent(ours->value("used"), 0));
    if (r.input->closed == 0 && r.input->boundary_loops >= 0) {
      ++open_inputs;
      if (!(loops == static_cast<double>(r.input->boundary_loops)))
        other_loops.push_back(r.input->name + " " + integerOrDash(loops) + " for " +
                              std::to_string(r.input->boundary_loops));
    }
  }
  if (!runs.empty()) {
    context.setTarget(
        "no non-manifold edges", "zero non-manifold edges on every input",
        nonmanifold.empty() ? 1 : 0,
        nonmanifold.empty() ? "0 on all " + std::to_string(runs.size()) + " inputs"
                            : "non-manifold edges on: " + [&] {
                                std::string s;
                                for (const std::string& x : nonmanifold)
                                  s += (s.empty() ? "" : ", ") + x;
                                return s;
                              }());
    const auto join = [](const std::vector<std::string>& items) {
      std::string s;
      for (const std::string& x : items)
        s += (s.empty() ? "" : ", ") + x;
      return s;
    };
    std::string evidence = holes.empty()
                               ? "0 loops and 95% of the samples or more on all " +
                                     std::to_string(closed_inputs) + " closed inputs"
                               : "not on: " + join(holes);
    evidence += "; open inputs of known topology: the reference's loops on " +
                std::to_string(open_inputs - other_loops.size()) + " of " +
                std::to_string(open_inputs);
    if (!other_loops.empty())
      evidence += " (not on: " + join(other_loops) + ")";
    if (!sparse.empty())
      evidence +=
          "; fewer than 95% of the samples used on the other inputs: " + join(sparse);
    context.setTarget(
        "no holes where closed",
        "no boundary loop on inputs whose reference surface is closed, and "
        "95% of their samples or more in the mesh",
        holes.empty() ? 1 : 0, evidence);
  }
  // Noisy inputs (issue 23): the exact topology, 99% of the samples, Hausdorff within
  // 1% of the diagonal, no non-manifold edge and no self-intersection; beside scale
  // space, the peer made for noise. Where the noise itself puts a sample farther than
  // 1% (the cube at 0.5 spacings: 1.035%), the bound is that sample's distance: a mesh
  // through the samples cannot be nearer. The farthest of all the samples, as a peer's
  // used samples are not known (test_noise takes those of the mesh).
  {
    const auto exact = [](const Input& input, const Measurement& m) {
      const bool topology =
          m.value("nm_edges") == 0 && m.value("components") == 1 &&
          m.value("loops") == static_cast<double>(input.boundary_loops) &&
          m.value("genus") == static_cast<double>(input.genus);
      const double self = m.value("self_intersections");
      return topology && m.value("used") >= 0.99 && !(self > 0) &&
             m.value("d_hausdorff") * input.spacing <=
                 std::max(0.01 * input.diagonal, input.farthest_sample);
    };
    std::size_t noisy = 0, ours_exact = 0, scale_space_exact = 0, faster = 0, timed = 0;
    std::vector<std::string> misses;
    for (const InputRun& r : runs) {
      if (r.input->kind != "noisy")
        continue;
      ++noisy;
      const Measurement* ours = r.find(kOurs);
      const Measurement* scale_space = r.find(kScaleSpace);
      if (ours && exact(*r.input, *ours))
        ++ours_exact;
      else
        misses.push_back(r.input->name);
      if (scale_space && exact(*r.input, *scale_space))
        ++scale_space_exact;
      if (ours && scale_space) {
        ++timed;
        if (ours->seconds < scale_space->seconds)
          ++faster;
      }
    }
    if (noisy > 0) {
      std::string evidence = "ours on " + std::to_string(ours_exact) + " of " +
                             std::to_string(noisy) + ", scale space on " +
                             std::to_string(scale_space_exact) + "; ours faster on " +
                             std::to_string(faster) + " of " + std::to_string(timed);
      if (!misses.empty()) {
        evidence += "; ours not on: ";
        for (std::size_t i = 0; i < misses.size(); ++i)
          evidence += (i ? ", " : "") + misses[i];
      }
      context.setTarget(
          "noisy inputs",
          "exact topology (one component, the true loops and genus), 99% "
          "of the samples, Hausdorff <= 1% of the diagonal (or the farthest "
          "sample's own distance, where larger), no "
          "non-manifold edge or self-intersection; faster than scale space",
          misses.empty() && timed == noisy && faster == timed ? 1 : 0, evidence);
    }
  }
  // Large inputs: ours vs Delaunay and the peers.
  std::vector<std::string> speed_notes;
  bool speed_met = true, speed_evaluated = false;
  for (const InputRun& r : runs) {
    if (r.input->size() < 100000)
      continue;
    const Measurement* ours = r.find(kOurs);
    if (!ours || !r.peers)
      continue;
    for (const char* peer : {kGreedy, kFront}) {
      for (const MethodRun& mr : r.methods) {
        if (mr.method != peer)
          continue;
        speed_evaluated = true;
        if (!mr.m.ok) {
          speed_notes.push_back(r.input->name + " " + peer + " failed");
          continue;
        }
        const double factor = mr.m.seconds / ours->seconds;
        if (factor < 2)
          speed_met = false;
        speed_notes.push_back(r.input->name + " " + peer + " " + ratio(factor));
      }
    }
  }
  if (speed_evaluated) {
    std::string s;
    for (const std::string& x : speed_notes)
      s += (s.empty() ? "" : ", ") + x;
    context.setTarget(
        "faster than GP3 and AFSR above 100k",
        "ours >= 2x faster than GreedyProjection and AdvancingFront on every "
        "input of 100k points and more (peer time / ours)",
        speed_met ? 1 : 0, s);
  }
  // The jittered torus alone (the other 1M inputs have their own target below).
  for (const InputRun& r : runs) {
    if (r.input->size() < 500000 || r.input->kind != "generated" || !r.input->shape ||
        r.input->shape->name != "torus")
      continue;
    const Measurement* ours = r.find(kOurs);
    if (!ours || !r.delaunay.ok)
      continue;
    const double factor = ours->seconds / r.delaunay.seconds;
    context.setTarget(
        "1M reconstruction vs Delaunay",
        "reconstruction of the 1M torus within 2.5x the bare Delaunay time",
        factor <= 2.5 ? 1 : 0,
        ratio(factor) + " (" + seconds(ours->seconds) + " s vs DT " +
            seconds(r.delaunay.seconds) + " s)");
    context.setTarget("1M reconstruction absolute",
                      "about 8 s and < 1.5 GB on this 2-core machine",
                      ours->seconds <= 8.5 && ours->peak_mb < 1536 ? 1 : 0,
                      seconds(ours->seconds) + " s, peak " + sig(ours->peak_mb, 3) +
                          " MB (machine-dependent: see the steal share)");
  }
  // Issue 22: on random samples at 1M, the whole reconstruction within 2.2x the bare
  // Delaunay time of the same run.
  double worst = 0;
  std::string worst_input;
  std::size_t random_1m = 0;
  std::vector<std::string> random_failed;
  for (const InputRun& r : runs) {
    if (r.input->kind != "random" || r.input->size() != 1000000)
      continue;
    ++random_1m;
    const Measurement* ours = r.find(kOurs);
    if (!ours || !r.delaunay.ok) {
      random_failed.push_back(r.input->name);
      continue;
    }
    const double factor = ours->seconds / r.delaunay.seconds;
    if (factor > worst) {
      worst = factor;
      worst_input = r.input->name;
    }
  }
  if (random_1m > 0)
    context.setTarget("1M random samples vs Delaunay",
                      "whole reconstruction of each 1M random sample within 2.2x the "
                      "bare Delaunay time",
                      worst <= 2.2 && random_failed.empty() ? 1 : 0,
                      "worst " + ratio(worst) + " (" + worst_input + ") of " +
                          std::to_string(random_1m) + " inputs" +
                          (random_failed.empty()
                               ? std::string()
                               : "; failed: " + std::to_string(random_failed.size())));
}

} // namespace bench
} // namespace cocone
} // namespace pcl
