// SPDX-License-Identifier: GPL-3.0-or-later
//
// cocone_pipeline: the whole chain in one program, as a downstream project would write
// it against the installed package (it uses only installed headers and PCL, so this
// file also compiles on its own):
//
//   read (any format) -> pcl::StatisticalOutlierRemoval -> pcl::VoronoiDecimation
//   (optional) -> pcl::CoconeReconstruction -> binary PLY + topology summary
//
// With --demo OUT_DIR it first generates its own scene (an open hemisphere, an open
// cylinder, a closed sphere and a few outliers), so that it can be tried without data.
//
// Error policy, as in the module's tools: PCL's own console output is silenced unless
// -v is given, the classes' getErrorMessage() and the readers' error strings become one
// line "cocone_pipeline: <reason>" on stderr, and the exit code is 1.
#include <pcl/PolygonMesh.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/common/io.h>
#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

constexpr const char* kProgram = "cocone_pipeline";

// ---------------------------------------------------------------------------------
// Errors and command line

/** One line on stderr, exit code 1. Control characters are replaced so that any file
 * name still gives exactly one line, and bytes that are not UTF-8 escaped. */
[[noreturn]] void
fail(std::string message)
{
  for (char& c : message)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = '?';
  std::fflush(stdout);
  std::fprintf(stderr, "%s: %s\n", kProgram, pcl::cocone::utf8Escaped(message).c_str());
  std::exit(EXIT_FAILURE);
}

struct Settings
{
  std::string input;
  std::string output;
  unsigned mean_k = 8;  // neighbours for the mean distance of outlier removal
  double std_mul = 3.0; // outlier threshold: mean + std_mul * standard deviation
  std::optional<double> decimate; // VoronoiDecimation's rho; no decimation when empty
  bool verbose = false;
  std::optional<std::string> demo_dir;
};

void
printHelp()
{
  // Kept to 88 columns, like the tools' help.
  static const char* const text[] = {
      "%s: removes outliers (pcl::StatisticalOutlierRemoval), optionally",
      "  decimates (pcl::VoronoiDecimation), reconstructs a triangle mesh with COCONE",
      "  and boundary detection (pcl::CoconeReconstruction) and reports its topology.",
      "",
      "Syntax is: %s INPUT OUTPUT.ply <options>",
      "       or: %s --demo OUT_DIR",
      "  INPUT            the samples: .pcd .ply .obj .off .xyz .pts .txt .las (a mesh's",
      "                   vertices are the samples; NaN points are dropped)",
      "  OUTPUT.ply       the mesh, binary PLY; its vertices are the points left",
      "                   after outlier removal and decimation",
      "  --demo OUT_DIR   generate a scene (open hemisphere, open cylinder, closed",
      "                   sphere, outliers) into OUT_DIR/scene.pcd, run the pipeline",
      "                   on it and write OUT_DIR/mesh.ply and OUT_DIR/boundary.pcd",
      "                   (boundary samples red); exit 1 unless the expected",
      "                   topology comes out",
      "",
      "where options are:",
      "  -mean_k K        outlier removal: neighbours for the mean distance",
      "                   (default 8; valid [1, 1000])",
      "  -std_mul S       outlier removal: points whose mean distance exceeds the",
      "                   mean by more than S standard deviations are removed",
      "                   (default 3; valid (0, 100])",
      "  -decimate RHO    decimate with VoronoiDecimation's ratio bound RHO, useful",
      "                   0.25 to 0.4 (default off; valid (0, 10])",
      "  -v               verbose: PCL's messages, parameters, reconstruction details",
      "  -h, --help       print this help and exit",
  };
  for (std::string line : text) {
    const std::size_t name = line.find("%s");
    if (name != std::string::npos)
      line.replace(name, 2, kProgram);
    std::printf("%s\n", line.c_str());
  }
}

double
parseNumber(const std::string& option, const char* text, double low, bool low_open,
            double high, bool integer)
{
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  const bool whole = *text != '\0' &&
                     !std::isspace(static_cast<unsigned char>(*text)) && end &&
                     *end == '\0';
  char range[64];
  std::snprintf(range, sizeof range, "%c%g, %g]", low_open ? '(' : '[', low, high);
  if (!whole || errno == ERANGE || !std::isfinite(value) ||
      (integer && value != std::floor(value)))
    fail(option + ": '" + text + "' is not " + (integer ? "an integer" : "a number") +
         " (expected a value in " + range + ")");
  if ((low_open ? value <= low : value < low) || value > high)
    fail(option + ": " + text + " is outside the valid range " + range);
  return value;
}

Settings
parseCommandLine(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
      printHelp();
      std::exit(EXIT_SUCCESS);
    }

  Settings settings;
  std::vector<std::string> positional;
  std::vector<std::string> seen;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 2 || arg[0] != '-') {
      positional.push_back(arg);
      continue;
    }
    // A typo such as -meank must not be ignored silently.
    static const std::array<const char*, 5> known{"-mean_k", "-std_mul", "-decimate",
                                                  "-v", "--demo"};
    if (std::find(known.begin(), known.end(), arg) == known.end())
      fail("unknown option '" + arg + "' (see " + kProgram + " -h)");
    if (std::find(seen.begin(), seen.end(), arg) != seen.end())
      fail(arg + " is given more than once");
    seen.push_back(arg);
    if (arg == "-v") {
      settings.verbose = true;
      continue;
    }
    if (i + 1 >= argc ||
        std::find(known.begin(), known.end(), std::string(argv[i + 1])) != known.end())
      fail(arg + " needs a value (see " + kProgram + " -h)");
    const char* value = argv[++i];
    if (arg == "-mean_k")
      settings.mean_k =
          static_cast<unsigned>(parseNumber(arg, value, 1, false, 1000, true));
    else if (arg == "-std_mul")
      settings.std_mul = parseNumber(arg, value, 0, true, 100, false);
    else if (arg == "-decimate")
      settings.decimate = parseNumber(arg, value, 0, true, 10, false);
    else
      settings.demo_dir = value;
  }

  if (settings.demo_dir) {
    if (!positional.empty())
      fail("unexpected argument '" + positional.front() + "' with --demo OUT_DIR");
    return settings;
  }
  if (positional.size() != 2)
    fail(positional.size() < 2 ? std::string("missing arguments: expected INPUT "
                                             "OUTPUT.ply (see ") +
                                     kProgram + " -h)"
                               : "unexpected argument '" + positional[2] +
                                     "': expected only INPUT OUTPUT.ply");
  settings.input = positional[0];
  settings.output = positional[1];

  // Checked now rather than after the computation.
  std::string extension = fs::path(settings.output).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".ply")
    fail("unsupported output format '" + settings.output + "' (expected .ply)");
  std::error_code ec;
  const fs::path folder = fs::path(settings.output).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, ec))
    fail("cannot write " + settings.output + ": folder " + folder.string() +
         " does not exist");
  if (fs::is_directory(settings.output, ec))
    fail("cannot write " + settings.output + ": it is a folder");
  return settings;
}

// ---------------------------------------------------------------------------------
// The pipeline

// With -v the classes print PCL_DEBUG lines while they run; a stage line is then ended
// at once so that those do not land in the middle of it.
bool verbose_stages = false;

/** Prints "<what> [done, X ms]" around \a work, like PCL's tools, or "[failed]" when
 * \a work returns false (the caller then fails with the reason). */
template <typename Work>
bool
stage(const std::string& what, Work&& work)
{
  std::printf(verbose_stages ? "%s ...\n" : "%s ", what.c_str());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  const bool ok = work();
  const std::chrono::duration<double, std::milli> elapsed =
      std::chrono::steady_clock::now() - start;
  if (ok)
    std::printf("[done, %.0f ms]\n", elapsed.count());
  else
    std::printf("[failed]\n");
  return ok;
}

struct Result
{
  std::size_t points_read = 0;
  std::size_t points_finite = 0;
  std::size_t after_outliers = 0;
  std::size_t after_decimation = 0;
  pcl::Indices kept;     // input rows that reached the reconstruction
  pcl::PolygonMesh mesh; // its cloud: those rows, x y z
  std::vector<std::uint8_t> boundary_flags; // per mesh vertex
  std::size_t boundary_samples = 0;
  pcl::cocone::MeshTopology topology;
};

Result
runPipeline(const Settings& settings)
{
  Result result;

  // 1. Read: the module's readers accept every format the tools accept.
  pcl::PCLPointCloud2 blob;
  std::string error;
  if (!stage("Loading " + settings.input, [&] {
        return pcl::cocone::loadPointSamples(settings.input, blob, &error);
      }))
    fail(error);
  Cloud::Ptr input(new Cloud);
  pcl::fromPCLPointCloud2(blob, *input);
  result.points_read = input->size();

  // StatisticalOutlierRemoval gives NaN points distance 0 and keeps them, so they are
  // taken out first.
  pcl::IndicesPtr finite(new pcl::Indices);
  for (std::size_t i = 0; i < input->size(); ++i)
    if (pcl::isXYZFinite((*input)[i]))
      finite->push_back(static_cast<pcl::index_t>(i));
  result.points_finite = finite->size();
  // It also reads past its neighbour lists when the cloud has no K + 1 points.
  if (finite->size() <= settings.mean_k)
    fail(settings.input + " has " + std::to_string(finite->size()) +
         " finite points; outlier removal with -mean_k " +
         std::to_string(settings.mean_k) + " needs more than " +
         std::to_string(settings.mean_k));

  if (settings.verbose) {
    std::printf("  outlier removal: mean_k %u, std_mul %g; decimation: ",
                settings.mean_k, settings.std_mul);
    if (settings.decimate)
      std::printf("rho %g\n", *settings.decimate);
    else
      std::printf("off\n");
  }

  // 2. Outlier removal.
  pcl::Indices inliers;
  stage("Removing outliers", [&] {
    pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
    sor.setInputCloud(input);
    sor.setIndices(finite);
    sor.setMeanK(static_cast<int>(settings.mean_k));
    sor.setStddevMulThresh(settings.std_mul);
    sor.filter(inliers);
    return true;
  });
  result.after_outliers = inliers.size();
  Cloud::Ptr cloud(new Cloud);
  pcl::copyPointCloud(*input, inliers, *cloud);
  result.kept = inliers;

  // 3. Decimation (optional): keeps original points, thins flat regions most.
  if (settings.decimate) {
    pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
    decimation.setInputCloud(cloud);
    decimation.setRatioBound(*settings.decimate);
    pcl::Indices kept;
    if (!stage("Decimating", [&] {
          decimation.filter(kept);
          return !kept.empty();
        }))
      fail("decimation failed: " + decimation.getErrorMessage());
    Cloud::Ptr decimated(new Cloud);
    pcl::copyPointCloud(*cloud, kept, *decimated);
    pcl::Indices rows;
    for (const pcl::index_t k : kept)
      rows.push_back(result.kept[k]);
    result.kept = rows;
    cloud = decimated;
  }
  result.after_decimation = cloud->size();

  // 4. Reconstruction: the mesh's vertex ids index `cloud`, which it copies.
  pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
  cocone.setInputCloud(cloud);
  if (!stage("Reconstructing", [&] {
        cocone.reconstruct(result.mesh);
        return !result.mesh.polygons.empty();
      }))
    fail("reconstruction failed: " + (cocone.getErrorMessage().empty()
                                          ? std::string("no triangle")
                                          : cocone.getErrorMessage()));
  result.boundary_flags = cocone.getBoundarySamples();
  result.boundary_samples = static_cast<std::size_t>(
      std::count(result.boundary_flags.begin(), result.boundary_flags.end(), 1));
  if (settings.verbose)
    std::printf("  candidates %zu, pruned %zu, stitched %zu holes (%zu triangles), "
                "unused points %zu\n",
                cocone.getNumberOfCandidateTriangles(),
                cocone.getNumberOfPrunedTriangles(), cocone.getNumberOfStitchedHoles(),
                cocone.getNumberOfStitchedTriangles(),
                cocone.getUnusedIndices().size());

  std::vector<pcl::cocone::TriangleIndices> triangles;
  triangles.reserve(result.mesh.polygons.size());
  for (const pcl::Vertices& polygon : result.mesh.polygons)
    triangles.push_back({static_cast<std::uint32_t>(polygon.vertices[0]),
                         static_cast<std::uint32_t>(polygon.vertices[1]),
                         static_cast<std::uint32_t>(polygon.vertices[2])});
  result.topology = pcl::cocone::analyzeTriangleMesh(triangles);

  // 5. Write, with the module's writer: binary PLY, written beside the output and
  // renamed into place, so that a failed write leaves the files as they were (and the
  // output may be the input).
  std::vector<std::array<float, 3>> vertices;
  vertices.reserve(cloud->size());
  for (const pcl::PointXYZ& p : *cloud)
    vertices.push_back({p.x, p.y, p.z});
  if (!stage("Saving " + settings.output, [&] {
        return pcl::cocone::saveMesh(settings.output, vertices, triangles, kProgram,
                                     &error);
      }))
    fail(error);
  return result;
}

void
printSummary(const Result& r, const Settings& settings)
{
  std::printf("points: %zu read", r.points_read);
  if (r.points_finite != r.points_read)
    std::printf(" (%zu finite)", r.points_finite);
  std::printf(", %zu after outlier removal", r.after_outliers);
  if (settings.decimate)
    std::printf(", %zu after decimation", r.after_decimation);
  std::printf("\n");
  const pcl::cocone::MeshTopology& t = r.topology;
  std::printf("mesh: %zu boundary samples, %zu vertices used, %zu triangles, "
              "%zu components, %zu boundary loops, genus %ld, closed %s, manifold %s\n",
              r.boundary_samples, t.vertices, t.triangles, t.components,
              t.boundary_loops.size(), t.genus(), t.isClosed() ? "yes" : "no",
              t.isManifold() ? "yes" : "no");
}

// ---------------------------------------------------------------------------------
// Demo scene

/** Uniform in [0, 1) from the generator's bits directly: std::uniform_real_distribution
 * is implementation-defined, and the demo should give the same scene everywhere. */
double
uniform(std::mt19937& rng)
{
  return static_cast<double>(rng()) / 4294967296.0;
}

/** The Fibonacci lattice on a sphere: near-uniform, no two points close. Points lying
 * exactly on a sphere are all co-spherical, the worst case for a Delaunay
 * triangulation, so each is moved radially by at most 1e-5 of the radius. */
void
addSphere(Cloud& cloud, std::size_t n, const Eigen::Vector3f& centre, float radius,
          bool upper_half_only, std::mt19937& rng)
{
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double z =
        1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    if (upper_half_only && z < 0)
      continue;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = golden * static_cast<double>(i);
    const double scale = radius * (1.0 + 1e-5 * (2.0 * uniform(rng) - 1.0));
    cloud.emplace_back(centre.x() + static_cast<float>(scale * r * std::cos(phi)),
                       centre.y() + static_cast<float>(scale * r * std::sin(phi)),
                       centre.z() + static_cast<float>(scale * z));
  }
}

/** An open cylinder (axis z) sampled on a staggered lattice of near-equilateral
 * triangles with spacing about \a spacing, jittered radially like the spheres. */
void
addOpenCylinder(Cloud& cloud, const Eigen::Vector3f& centre, float radius, float height,
                float spacing, std::mt19937& rng)
{
  const int around = static_cast<int>(std::round(2 * M_PI * radius / spacing));
  const double row = spacing * std::sqrt(3.0) / 2;
  const int rows = static_cast<int>(std::round(height / row)) + 1;
  for (int j = 0; j < rows; ++j) {
    const double z = -height / 2 + height * j / (rows - 1);
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * M_PI * (i + 0.5 * (j % 2)) / around;
      const double scale = radius * (1.0 + 1e-5 * (2.0 * uniform(rng) - 1.0));
      cloud.emplace_back(centre.x() + static_cast<float>(scale * std::cos(phi)),
                         centre.y() + static_cast<float>(scale * std::sin(phi)),
                         centre.z() + static_cast<float>(z));
    }
  }
}

int
runDemo(const std::string& dir)
{
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    fail("cannot create folder " + dir);

  // Three shapes side by side at a common spacing of about 0.06: a hemisphere (one
  // boundary loop, its equator), an open cylinder (two loops) and a sphere (closed).
  std::mt19937 rng(2001);
  Cloud scene;
  addSphere(scene, 3500, {0, 0, 0}, 1.0f, true, rng);
  addOpenCylinder(scene, {3, 0, 0.5f}, 0.5f, 2.0f, 0.06f, rng);
  addSphere(scene, 3500, {6, 0, 0.5f}, 1.0f, false, rng);
  const std::size_t surface_points = scene.size();

  // Outliers: random points at least 0.3 (five spacings) from every surface sample.
  const std::size_t outliers = 30;
  while (scene.size() < surface_points + outliers) {
    const Eigen::Vector3f p(static_cast<float>(-1.5 + 9.0 * uniform(rng)),
                            static_cast<float>(-1.5 + 3.0 * uniform(rng)),
                            static_cast<float>(-1.0 + 3.0 * uniform(rng)));
    bool far = true;
    for (std::size_t i = 0; i < surface_points && far; ++i)
      far = (scene[i].getVector3fMap() - p).squaredNorm() >= 0.09f;
    if (far)
      scene.emplace_back(p.x(), p.y(), p.z());
  }

  Settings settings;
  settings.input = (fs::path(dir) / "scene.pcd").string();
  settings.output = (fs::path(dir) / "mesh.ply").string();
  pcl::PCLPointCloud2 scene_blob;
  pcl::toPCLPointCloud2(scene, scene_blob);
  std::string error;
  if (!pcl::cocone::saveCloud(settings.input, scene_blob, &error))
    fail(error);
  std::printf("Generated %s: open hemisphere, open cylinder, closed sphere (%zu "
              "points) and %zu outliers\n",
              settings.input.c_str(), surface_points, outliers);

  const Result result = runPipeline(settings);
  printSummary(result, settings);

  // The boundary samples in red on grey, for pcl_viewer.
  pcl::PointCloud<pcl::PointXYZRGB> coloured;
  for (std::size_t v = 0; v < result.kept.size(); ++v) {
    pcl::PointXYZRGB p;
    p.getVector3fMap() = scene[result.kept[v]].getVector3fMap();
    const bool flagged = result.boundary_flags[v] != 0;
    p.r = flagged ? 230 : 170;
    p.g = p.b = flagged ? 30 : 170;
    coloured.push_back(p);
  }
  const std::string boundary = (fs::path(dir) / "boundary.pcd").string();
  pcl::PCLPointCloud2 coloured_blob;
  pcl::toPCLPointCloud2(coloured, coloured_blob);
  if (!pcl::cocone::saveCloud(boundary, coloured_blob, &error))
    fail(error);

  // What a correct run gives: every outlier gone, three manifold components of genus 0
  // with three boundary loops (hemisphere 1, cylinder 2), no surface point lost.
  const std::size_t outliers_left = static_cast<std::size_t>(
      std::count_if(result.kept.begin(), result.kept.end(), [&](pcl::index_t i) {
        return static_cast<std::size_t>(i) >= surface_points;
      }));
  const pcl::cocone::MeshTopology& t = result.topology;
  if (outliers_left != 0)
    fail(std::to_string(outliers_left) + " outliers survived outlier removal");
  if (!t.isManifold() || t.components != 3 || t.boundary_loops.size() != 3 ||
      t.genus() != 0)
    fail("unexpected topology: expected 3 manifold components of genus 0 with 3 "
         "boundary loops");
  std::printf("demo result as expected: all %zu outliers removed; hemisphere, cylinder "
              "and sphere reconstructed with 3 boundary loops\n",
              outliers);
  std::printf("view: pcl_viewer %s   pcl_viewer %s   pcl_viewer %s\n",
              settings.input.c_str(), boundary.c_str(), settings.output.c_str());
  return 0;
}

} // namespace

int
main(int argc, char** argv)
{
  const Settings settings = parseCommandLine(argc, argv);
  // Past a file size limit (ulimit -f) a write would raise SIGXFSZ and end the program
  // with a core dump; ignored, the write fails with its reason, as any other.
  std::signal(SIGXFSZ, SIG_IGN);
  // The classes report failures with PCL_ERROR and in getErrorMessage(); the latter
  // becomes this program's one line, so PCL's console stays quiet unless asked for.
  pcl::console::setVerbosityLevel(settings.verbose ? pcl::console::L_DEBUG
                                                   : pcl::console::L_ALWAYS);
  verbose_stages = settings.verbose;
  if (settings.demo_dir)
    return runDemo(*settings.demo_dir);

  const Result result = runPipeline(settings);
  printSummary(result, settings);
  return 0;
}
