// SPDX-License-Identifier: GPL-3.0-or-later
// The three command-line tools run as a user runs them: as processes, on clouds written
// here, checking the exit code, the number of lines on stderr, the summary lines and
// the files they write (read back with the library's own readers).
#include <pcl/cocone/io/point_io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/las_file.h"
#include "support/process.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Args = std::vector<std::string>;
using pcl::cocone::test::expectOneLineFailure;
using pcl::cocone::test::expectSuccess;
using pcl::cocone::test::readText;
using pcl::cocone::test::runTool;
using pcl::cocone::test::sampleTrefoilKnot;
using pcl::cocone::test::shellQuote;
using pcl::cocone::test::ToolRun;

const std::string kBoundary = "pcl_boundary_sample_estimation";
const std::string kReconstruction = "pcl_cocone_reconstruction";
const std::string kDecimation = "pcl_voronoi_decimation";
const std::vector<std::string> kTools{kBoundary, kReconstruction, kDecimation};
const std::string kPipeline = "cocone_pipeline";

// The build passes the folder of the executables; without the tools (built with
// PCL_COCONE_BUILD_TOOLS=OFF) every test skips.
#ifdef PCL_COCONE_TOOL_DIR
const char* const kToolDir = PCL_COCONE_TOOL_DIR;
#else
const char* const kToolDir = nullptr;
#endif
// The pipeline example, when it is built.
#ifdef PCL_COCONE_EXAMPLE_DIR
const char* const kExampleDir = PCL_COCONE_EXAMPLE_DIR;
#else
const char* const kExampleDir = nullptr;
#endif

constexpr std::size_t kSpherePoints = 3000;
constexpr std::size_t kNanEvery = 100; // a NaN row after every 100th point

std::vector<pcl::PointXYZ>
fibonacciSphere(std::size_t n)
{
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<pcl::PointXYZ> points;
  for (std::size_t i = 0; i < n; ++i) {
    const double z =
        1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double r = std::sqrt(1.0 - z * z);
    const double phi = golden * static_cast<double>(i);
    points.emplace_back(static_cast<float>(r * std::cos(phi)),
                        static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
  }
  return points;
}

/** The samples, in files of several formats, shared by every test of the suite. */
class Tools : public ::testing::Test
{
protected:
  static void
  SetUpTestSuite()
  {
    dir_ = fs::path(::testing::TempDir()) /
           ("pcl_cocone_tools_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);

    sphere_ = fibonacciSphere(kSpherePoints);
    writeXyz("sphere.xyz", sphere_);
    // The upper half of a denser lattice: an open surface with one boundary circle.
    for (const pcl::PointXYZ& p : fibonacciSphere(4000))
      if (p.z >= 0)
        hemisphere_.push_back(p);
    writeXyz("hemisphere.xyz", hemisphere_);

    std::vector<pcl::PointXYZ> plane;
    for (int i = 0; i < 20; ++i)
      for (int j = 0; j < 20; ++j)
        plane.emplace_back(0.1f * i, 0.05f * j + 0.01f * i, 0.0f);
    writeXyz("plane.xyz", plane);

    // The sphere with an intensity field numbering the rows, so that a row of an
    // output can be traced back to its input row.
    pcl::PointCloud<pcl::PointXYZI> numbered;
    for (std::size_t i = 0; i < sphere_.size(); ++i) {
      pcl::PointXYZI p;
      p.x = sphere_[i].x;
      p.y = sphere_[i].y;
      p.z = sphere_[i].z;
      p.intensity = static_cast<float>(i);
      numbered.push_back(p);
    }
    pcl::io::savePCDFileBinary(path("sphere.pcd").string(), numbered);

    // The sphere with NaN rows in between.
    pcl::PointCloud<pcl::PointXYZ> with_nan;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t i = 0; i < sphere_.size(); ++i) {
      with_nan.push_back(sphere_[i]);
      if ((i + 1) % kNanEvery == 0)
        with_nan.push_back(pcl::PointXYZ(nan, nan, nan));
    }
    with_nan.is_dense = false;
    pcl::io::savePCDFileBinary(path("sphere_nan.pcd").string(), with_nan);

    writeText("garbage.xyz", "hello world\nthis is not a point cloud\n");
    writeText("garbage.pcd", "garbage\n\x01\x02\x03");
    writeText("empty.xyz", "# nothing but a comment\n\n");
    fs::create_directories(path("folder.xyz"));
    fs::create_directories(path("folder.pcd"));
    // The tools' own output goes elsewhere, so that a folder holds only what the tools
    // wrote into it.
    fs::create_directories(path("logs"));
  }

  void
  SetUp() override
  {
    if (!kToolDir)
      GTEST_SKIP() << "the tools are not built";
  }

  static void
  TearDownTestSuite()
  {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  static fs::path
  path(const std::string& name)
  {
    return dir_ / name;
  }

  static void
  writeText(const std::string& name, const std::string& text)
  {
    std::ofstream(path(name), std::ios::binary) << text;
  }

  static void
  writeXyz(const std::string& name, const std::vector<pcl::PointXYZ>& points)
  {
    std::ofstream out(path(name));
    char line[96];
    for (const pcl::PointXYZ& p : points) {
      std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p.x, p.y, p.z);
      out << line;
    }
  }

  /** Runs \a tool with \a args (each one argument, no shell interpretation), after
   * the shell text \a launcher (e.g. "ulimit -f 4; "). */
  static ToolRun
  run(const std::string& tool, const Args& args, const std::string& launcher = "")
  {
    static std::atomic<int> counter{0}; // some tests run tools side by side
    const std::string id = std::to_string(counter++);
    const fs::path program =
        tool == kPipeline ? fs::path(kExampleDir) / tool : fs::path(kToolDir) / tool;
    return runTool(launcher, program, args, path("logs") / ("stdout_" + id),
                   path("logs") / ("stderr_" + id));
  }

  static fs::path dir_;
  static std::vector<pcl::PointXYZ> sphere_;
  static std::vector<pcl::PointXYZ> hemisphere_;
};

fs::path Tools::dir_;
std::vector<pcl::PointXYZ> Tools::sphere_;
std::vector<pcl::PointXYZ> Tools::hemisphere_;

// --- checking outputs ----------------------------------------------------------------

/** After a bad argument a tool must stop before it loads anything. */
void
expectArgumentError(const ToolRun& result, const std::string& expected)
{
  expectOneLineFailure(result, expected);
  EXPECT_EQ(result.out.find("Loading"), std::string::npos)
      << "the tool went on after a bad argument: " << result.out;
}

pcl::PCLPointCloud2
loadCloud(const fs::path& file)
{
  pcl::PCLPointCloud2 cloud;
  std::string error;
  EXPECT_TRUE(pcl::cocone::loadPointSamples(file.string(), cloud, &error)) << error;
  return cloud;
}

std::size_t
rows(const pcl::PCLPointCloud2& cloud)
{
  return static_cast<std::size_t>(cloud.width) * cloud.height;
}

const pcl::PCLPointField*
findField(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  for (const pcl::PCLPointField& field : cloud.fields)
    if (field.name == name)
      return &field;
  return nullptr;
}

template <typename T>
T
valueAt(const pcl::PCLPointCloud2& cloud, std::size_t row,
        const pcl::PCLPointField& field)
{
  T value;
  std::memcpy(&value, &cloud.data[row * cloud.point_step + field.offset], sizeof value);
  return value;
}

/** The numbers of the reconstruction tool's summary line. */
struct Summary
{
  bool found = false;
  long vertices = 0, triangles = 0, loops = 0, euler = 0;
  bool closed = false, manifold = false;
};

Summary
meshSummary(const std::string& out)
{
  static const std::regex line(
      "vertices used (\\d+), triangles (\\d+), boundary loops (\\d+), Euler "
      "characteristic (-?\\d+), closed (yes|no), manifold (yes|no)\n");
  std::smatch m;
  Summary s;
  if (!std::regex_search(out, m, line))
    return s;
  s.found = true;
  s.vertices = std::stol(m[1]);
  s.triangles = std::stol(m[2]);
  s.loops = std::stol(m[3]);
  s.euler = std::stol(m[4]);
  s.closed = m[5] == "yes";
  s.manifold = m[6] == "yes";
  return s;
}

/** Faces of a mesh file, each checked to be a triangle of vertex ids below \a n. */
std::vector<pcl::Vertices>
loadTriangles(const fs::path& file, std::size_t n)
{
  std::vector<pcl::Vertices> faces;
  std::string error;
  EXPECT_TRUE(pcl::cocone::loadMeshFaces(file.string(), faces, &error)) << error;
  for (const pcl::Vertices& face : faces) {
    EXPECT_EQ(face.vertices.size(), 3u);
    for (const auto v : face.vertices)
      EXPECT_LT(static_cast<std::size_t>(v), n);
  }
  return faces;
}

// --- help ----------------------------------------------------------------------------

TEST_F(Tools, HelpListsEveryOptionWithDefaultAndRange)
{
  const std::vector<std::pair<std::string, Args>> options{
      {kBoundary,
       {"-rho", "-alpha", "-theta", "-band", "-no_rim_completion", "-rgb", "-threads",
        "-v"}},
      {kReconstruction,
       {"-theta", "-rho", "-alpha", "-boundary_ratio", "-no_boundary", "-no_stitch",
        "-threads", "-v"}},
      {kDecimation, {"-rho", "-theta", "-threads", "-v"}}};
  for (const auto& [tool, names] : options)
    for (const std::string help : {"-h", "--help"}) {
      SCOPED_TRACE(tool + " " + help);
      const ToolRun r = run(tool, {help});
      expectSuccess(r);
      for (const std::string& name : names)
        EXPECT_NE(r.out.find("  " + name + " "), std::string::npos) << name;
      EXPECT_NE(r.out.find("radians"), std::string::npos);
      EXPECT_NE(r.out.find("(0, 10]"), std::string::npos);   // rho's range
      EXPECT_NE(r.out.find("(0, pi/2)"), std::string::npos); // theta's range
      EXPECT_NE(r.out.find("default pi/8"), std::string::npos);
    }
}

TEST_F(Tools, HelpWinsOverOtherArguments)
{
  for (const std::string& tool : kTools) {
    const ToolRun r = run(tool, {"missing.xyz", "-foo", "-h"});
    expectSuccess(r);
    EXPECT_NE(r.out.find("Syntax is: " + tool), std::string::npos);
  }
}

// --- boundary samples ----------------------------------------------------------------

TEST_F(Tools, BoundaryWritesOneRowPerInputPointInOrder)
{
  const fs::path output = path("hemisphere_boundary.pcd");
  const ToolRun r = run(kBoundary, {path("hemisphere.xyz").string(), output.string()});
  expectSuccess(r);
  EXPECT_NE(r.out.find("Loading"), std::string::npos);
  EXPECT_NE(r.out.find("[done, "), std::string::npos);

  const pcl::PCLPointCloud2 cloud = loadCloud(output);
  ASSERT_EQ(rows(cloud), hemisphere_.size());
  const pcl::PCLPointField* flag = findField(cloud, "boundary_point");
  const pcl::PCLPointField* x = findField(cloud, "x");
  ASSERT_NE(flag, nullptr);
  ASSERT_NE(x, nullptr);
  EXPECT_EQ(flag->datatype, pcl::PCLPointField::UINT8);
  EXPECT_EQ(findField(cloud, "rgb"), nullptr);

  std::size_t flagged = 0;
  for (std::size_t i = 0; i < rows(cloud); ++i) {
    const auto value = valueAt<std::uint8_t>(cloud, i, *flag);
    EXPECT_LE(value, 1);
    flagged += value;
    EXPECT_EQ(valueAt<float>(cloud, i, *x), hemisphere_[i].x) << "row " << i;
  }
  // The rim is flagged, the interior is not.
  EXPECT_GT(flagged, 10u);
  EXPECT_LT(flagged, hemisphere_.size() / 10);
  EXPECT_NE(r.out.find(std::to_string(flagged) + " boundary samples of " +
                       std::to_string(hemisphere_.size()) + " points ("),
            std::string::npos)
      << r.out;
}

TEST_F(Tools, BoundaryRgbColoursBoundarySamplesRedAndKeepsTheFlag)
{
  const fs::path output = path("hemisphere_rgb.pcd");
  expectSuccess(
      run(kBoundary, {path("hemisphere.xyz").string(), output.string(), "-rgb"}));
  const pcl::PCLPointCloud2 cloud = loadCloud(output);
  ASSERT_EQ(rows(cloud), hemisphere_.size());
  const pcl::PCLPointField* flag = findField(cloud, "boundary_point");
  const pcl::PCLPointField* rgb = findField(cloud, "rgb");
  ASSERT_NE(flag, nullptr);
  ASSERT_NE(rgb, nullptr);
  EXPECT_EQ(rgb->datatype, pcl::PCLPointField::FLOAT32);
  std::size_t red = 0;
  for (std::size_t i = 0; i < rows(cloud); ++i) {
    // Packed like pcl::PointXYZRGB: the float's bits hold 0xAARRGGBB.
    const std::uint32_t colour = valueAt<std::uint32_t>(cloud, i, *rgb) & 0xffffffu;
    if (valueAt<std::uint8_t>(cloud, i, *flag)) {
      EXPECT_EQ(colour, 0xff0000u) << "row " << i;
      ++red;
    }
    else
      EXPECT_EQ(colour, 0xa0a0a0u) << "row " << i;
  }
  EXPECT_GT(red, 0u);
}

TEST_F(Tools, BoundaryBandFlagsMoreSamples)
{
  const auto flagged = [](const pcl::PCLPointCloud2& cloud) {
    const pcl::PCLPointField* flag = findField(cloud, "boundary_point");
    std::size_t n = 0;
    for (std::size_t i = 0; flag && i < rows(cloud); ++i)
      n += valueAt<std::uint8_t>(cloud, i, *flag);
    return n;
  };
  const fs::path plain = path("band0.pcd"), band = path("band2.pcd");
  expectSuccess(run(kBoundary, {path("hemisphere.xyz").string(), plain.string()}));
  expectSuccess(run(kBoundary, {path("hemisphere.xyz").string(), band.string(), "-band",
                                "2", "-rho", "0.99", "-alpha", "0.5", "-theta", "0.4",
                                "-threads", "1"}));
  EXPECT_GT(flagged(loadCloud(band)), flagged(loadCloud(plain)));

  // BOUNDARY as published flags part of the rim row; the default completes it.
  const fs::path published = path("as_published.pcd");
  expectSuccess(run(kBoundary, {path("hemisphere.xyz").string(), published.string(),
                                "-no_rim_completion"}));
  EXPECT_GT(flagged(loadCloud(published)), 0u);
  EXPECT_LT(flagged(loadCloud(published)), flagged(loadCloud(plain)));
}

TEST_F(Tools, BoundaryKeepsNanRowsUnflagged)
{
  const fs::path output = path("nan_boundary.pcd");
  expectSuccess(run(kBoundary, {path("sphere_nan.pcd").string(), output.string()}));
  const pcl::PCLPointCloud2 cloud = loadCloud(output);
  const std::size_t expected_rows = kSpherePoints + kSpherePoints / kNanEvery;
  ASSERT_EQ(rows(cloud), expected_rows);
  const pcl::PCLPointField* flag = findField(cloud, "boundary_point");
  const pcl::PCLPointField* x = findField(cloud, "x");
  ASSERT_NE(flag, nullptr);
  std::size_t nan_rows = 0;
  for (std::size_t i = 0; i < rows(cloud); ++i)
    if (std::isnan(valueAt<float>(cloud, i, *x))) {
      ++nan_rows;
      EXPECT_EQ(valueAt<std::uint8_t>(cloud, i, *flag), 0) << "row " << i;
    }
  EXPECT_EQ(nan_rows, kSpherePoints / kNanEvery);
}

// --- reconstruction ------------------------------------------------------------------

TEST_F(Tools, ReconstructionOfSphereIsClosedManifoldPly)
{
  const fs::path output = path("sphere.ply");
  const ToolRun r =
      run(kReconstruction, {path("sphere.xyz").string(), output.string()});
  expectSuccess(r);
  const Summary s = meshSummary(r.out);
  ASSERT_TRUE(s.found) << r.out;
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.euler, 2);
  EXPECT_EQ(s.loops, 0);
  EXPECT_EQ(s.vertices, static_cast<long>(kSpherePoints));
  EXPECT_EQ(r.out.find("note:"), std::string::npos);

  // Binary little-endian PLY, vertex i = input point i.
  EXPECT_EQ(readText(output).rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  const pcl::PCLPointCloud2 vertices = loadCloud(output);
  ASSERT_EQ(rows(vertices), kSpherePoints);
  const pcl::PCLPointField* z = findField(vertices, "z");
  ASSERT_NE(z, nullptr);
  for (std::size_t i = 0; i < kSpherePoints; i += 97)
    EXPECT_EQ(valueAt<float>(vertices, i, *z), sphere_[i].z) << "vertex " << i;
  EXPECT_EQ(static_cast<long>(loadTriangles(output, kSpherePoints).size()),
            s.triangles);
}

TEST_F(Tools, ReconstructionReadsLas)
{
  // The sphere as airborne LiDAR stores it: LAS 1.4, point format 6, 64-bit count,
  // integers of 0.1 mm around an offset.
  pcl::cocone::test::LasLayout layout;
  layout.minor = 4;
  layout.format = 6;
  layout.scale = {1e-4, 1e-4, 1e-4};
  layout.offset = {500, -20, 3};
  std::vector<pcl::cocone::test::LasPoint> points;
  for (const pcl::PointXYZ& p : sphere_) {
    pcl::cocone::test::LasPoint q;
    q.x = static_cast<std::int32_t>(std::lround(p.x / layout.scale[0]));
    q.y = static_cast<std::int32_t>(std::lround(p.y / layout.scale[1]));
    q.z = static_cast<std::int32_t>(std::lround(p.z / layout.scale[2]));
    points.push_back(q);
  }
  const fs::path input = path("sphere.las");
  std::ofstream(input, std::ios::binary) << pcl::cocone::test::lasFile(layout, points);
  const fs::path output = path("sphere_from_las.ply");
  const ToolRun r = run(kReconstruction, {input.string(), output.string()});
  expectSuccess(r);
  const Summary s = meshSummary(r.out);
  ASSERT_TRUE(s.found) << r.out;
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.euler, 2);
  EXPECT_EQ(s.vertices, static_cast<long>(kSpherePoints));
  // Vertex i is LAS record i, scaled and offset.
  const pcl::PCLPointCloud2 vertices = loadCloud(output);
  ASSERT_EQ(rows(vertices), kSpherePoints);
  const pcl::PCLPointField* x = findField(vertices, "x");
  ASSERT_NE(x, nullptr);
  for (std::size_t i = 0; i < kSpherePoints; i += 97)
    EXPECT_EQ(valueAt<float>(vertices, i, *x),
              static_cast<float>(points[i].x * layout.scale[0] + layout.offset[0]));

  // LAZ is refused in one line that says how to convert it.
  layout.format |= 0x80u;
  const fs::path laz = path("sphere.laz");
  std::ofstream(laz, std::ios::binary) << pcl::cocone::test::lasFile(layout, points);
  expectOneLineFailure(run(kReconstruction, {laz.string(), output.string()}),
                       "las2las");
}

TEST_F(Tools, ReconstructionWritesObjAndVtk)
{
  const fs::path obj = path("sphere.obj"), vtk = path("sphere.vtk");
  const ToolRun with_obj =
      run(kReconstruction, {path("sphere.xyz").string(), obj.string()});
  expectSuccess(with_obj);
  const Summary s = meshSummary(with_obj.out);
  ASSERT_TRUE(s.found);
  EXPECT_EQ(rows(loadCloud(obj)), kSpherePoints);
  EXPECT_EQ(static_cast<long>(loadTriangles(obj, kSpherePoints).size()), s.triangles);

  expectSuccess(run(kReconstruction, {path("sphere.xyz").string(), vtk.string()}));
  // Legacy VTK POLYDATA as vtkPolyDataReader (pcl_viewer) reads it.
  std::istringstream text(readText(vtk));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line.rfind("# vtk DataFile Version", 0), 0u);
  std::getline(text, line); // title
  std::getline(text, line);
  EXPECT_EQ(line, "ASCII");
  std::getline(text, line);
  EXPECT_EQ(line, "DATASET POLYDATA");
  std::string keyword, type;
  std::size_t points = 0, polygons = 0, size = 0;
  text >> keyword >> points >> type;
  EXPECT_EQ(keyword, "POINTS");
  EXPECT_EQ(points, kSpherePoints);
  EXPECT_EQ(type, "float");
  float coordinate = 0;
  for (std::size_t i = 0; i < 3 * points; ++i)
    text >> coordinate;
  text >> keyword >> polygons >> size;
  EXPECT_EQ(keyword, "POLYGONS");
  EXPECT_EQ(static_cast<long>(polygons), s.triangles);
  EXPECT_EQ(size, 4 * polygons);
  std::size_t corners = 0, id = 0, bad = 0;
  for (std::size_t f = 0; f < polygons && text >> corners; ++f) {
    bad += corners != 3;
    for (std::size_t k = 0; k < corners && text >> id; ++k)
      bad += id >= points;
  }
  EXPECT_TRUE(text.good());
  EXPECT_EQ(bad, 0u);
}

TEST_F(Tools, ReconstructionOfHemisphereKeepsItsBoundaryOpen)
{
  const fs::path output = path("hemisphere.ply");
  const ToolRun r =
      run(kReconstruction, {path("hemisphere.xyz").string(), output.string()});
  expectSuccess(r);
  const Summary s = meshSummary(r.out);
  ASSERT_TRUE(s.found) << r.out;
  EXPECT_FALSE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.loops, 1);
  EXPECT_EQ(s.euler, 1); // a disk
}

// A trefoil-knot tube far too sparse for its thinness: BOUNDARY flags nearly every
// sample, and boundary samples cast no vote. The reconstruction falls back to no
// boundary detection and the tool says so: the user gets the closed tube, and the
// reason why true boundaries would not have stayed open.
TEST_F(Tools, ReconstructionOfTooSparseCloudSaysWhy)
{
  const auto knotFile = [&](std::size_t n) {
    std::vector<pcl::PointXYZ> points;
    for (const Eigen::Vector3d& p : sampleTrefoilKnot(n).points)
      points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                          static_cast<float>(p.z()));
    const std::string name = "knot" + std::to_string(n) + ".xyz";
    writeXyz(name, points);
    return path(name).string();
  };

  // 1000 and 600 samples: the closed tube, and a note on stdout.
  for (const std::size_t n : {1000, 600}) {
    const ToolRun some =
        run(kReconstruction,
            {knotFile(n), path("knot" + std::to_string(n) + ".ply").string()});
    expectSuccess(some);
    EXPECT_NE(some.out.find("note: "), std::string::npos) << some.out;
    EXPECT_NE(some.out.find("boundary samples: the cloud is too sparse"),
              std::string::npos)
        << some.out;
    EXPECT_NE(some.out.find("reconstructed without it"), std::string::npos) << some.out;
    const Summary s = meshSummary(some.out);
    ASSERT_TRUE(s.found) << some.out;
    EXPECT_TRUE(s.closed) << some.out;
    EXPECT_GE(s.vertices, static_cast<long>(n * 95 / 100)) << some.out;
  }
  const std::string sparse = path("knot600.xyz").string();

  // Extreme parameter values flag every sample of a well-sampled cloud: the reason
  // names them, not the cloud.
  const std::string dense = knotFile(20000);
  const ToolRun alpha =
      run(kReconstruction, {dense, path("knot_alpha.ply").string(), "-alpha", "0.001"});
  const std::string alpha_text = alpha.out + alpha.err;
  EXPECT_NE(alpha_text.find("with -alpha 0.001 (default 0.52"), std::string::npos)
      << alpha_text;
  EXPECT_EQ(alpha_text.find("too sparse"), std::string::npos) << alpha_text;
  const ToolRun rho =
      run(kReconstruction, {dense, path("knot_rho.ply").string(), "-rho", "0.001"});
  const std::string rho_text = rho.out + rho.err;
  EXPECT_NE(rho_text.find("with -rho 0.001 (default 0.99)"), std::string::npos)
      << rho_text;

  // Without boundary detection the same cloud gives a closed surface, and no note.
  const ToolRun all = run(kReconstruction, {sparse, path("knot600_all.ply").string(),
                                            "-no_boundary", "-denoise", "off"});
  expectSuccess(all);
  EXPECT_EQ(all.out.find("note:"), std::string::npos) << all.out;
  const Summary t = meshSummary(all.out);
  ASSERT_TRUE(t.found) << all.out;
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.vertices, 600);
}

// On a terminal the stage line shows the share done; piped, the output stays as it was.
// script(1) gives the tool a pseudo-terminal.
TEST_F(Tools, ProgressShowsOnATerminalOnly)
{
  if (std::system("command -v script > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "script(1) is not installed: no pseudo-terminal to test with";
  const std::string input = path("sphere.pcd").string();
  for (const std::string& tool : kTools) {
    const fs::path log = path("logs") / ("terminal_" + tool);
    const std::string command =
        (fs::path(kToolDir) / tool).string() + " " + shellQuote(input) + " " +
        shellQuote(
            path("terminal_" + tool + (tool == kReconstruction ? ".ply" : ".pcd"))
                .string());
    ASSERT_EQ(std::system(("script -qec " + shellQuote(command) + " /dev/null > " +
                           shellQuote(log.string()) + " 2>&1")
                              .c_str()),
              0)
        << tool;
    const std::string shown = readText(log);
    EXPECT_NE(shown.find("%\b"), std::string::npos) << tool << ": " << shown;
    EXPECT_NE(shown.find("[done, "), std::string::npos) << tool << ": " << shown;
    const ToolRun piped = run(
        tool,
        {input,
         path("piped_" + tool + (tool == kReconstruction ? ".ply" : ".pcd")).string()});
    expectSuccess(piped);
    EXPECT_EQ(piped.out.find('\b'), std::string::npos) << tool << ": " << piped.out;
  }
}

TEST_F(Tools, ReconstructionDropsNanPointsAndRenumbersVertices)
{
  const fs::path output = path("sphere_nan.ply");
  const ToolRun r =
      run(kReconstruction, {path("sphere_nan.pcd").string(), output.string()});
  expectSuccess(r);
  const std::size_t dropped = kSpherePoints / kNanEvery;
  EXPECT_NE(r.out.find("note: " + std::to_string(dropped) +
                       " non-finite input points dropped; vertex ids renumbered"),
            std::string::npos)
      << r.out;
  const Summary s = meshSummary(r.out);
  ASSERT_TRUE(s.found);
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_EQ(s.euler, 2);
  // Every point is accounted for.
  EXPECT_NE(r.out.find("unused points " + std::to_string(dropped) + " of " +
                       std::to_string(kSpherePoints + dropped) + ": " +
                       std::to_string(dropped) +
                       " non-finite, 0 far, 0 duplicates, 0 left out of the mesh"),
            std::string::npos)
      << r.out;

  // The file holds the finite points in input order; every id is one of them.
  const pcl::PCLPointCloud2 vertices = loadCloud(output);
  ASSERT_EQ(rows(vertices), kSpherePoints);
  const pcl::PCLPointField* x = findField(vertices, "x");
  ASSERT_NE(x, nullptr);
  for (std::size_t i = 0; i < kSpherePoints; ++i)
    ASSERT_EQ(valueAt<float>(vertices, i, *x), sphere_[i].x) << "vertex " << i;
  EXPECT_EQ(static_cast<long>(loadTriangles(output, kSpherePoints).size()),
            s.triangles);
}

TEST_F(Tools, ReconstructionSummaryCountsDuplicatesAndOutliers)
{
  // The sphere, its first 25 points repeated, and 3 lone points inside it: outliers
  // that no triangle of a manifold surface through the sphere can use.
  std::vector<pcl::PointXYZ> points = sphere_;
  points.insert(points.end(), sphere_.begin(), sphere_.begin() + 25);
  points.emplace_back(0.0f, 0.0f, 0.0f);
  points.emplace_back(0.1f, 0.05f, 0.0f);
  points.emplace_back(-0.05f, 0.1f, 0.02f);
  writeXyz("sphere_extra.xyz", points);
  const ToolRun r = run(kReconstruction, {path("sphere_extra.xyz").string(),
                                          path("sphere_extra.ply").string()});
  expectSuccess(r);
  const Summary s = meshSummary(r.out);
  ASSERT_TRUE(s.found);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.vertices, static_cast<long>(kSpherePoints));
  const std::string expected = "unused points 28 of " + std::to_string(points.size()) +
                               ": 0 non-finite, 0 far, 25 duplicates, 3 left out of "
                               "the mesh";
  EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
  // The same without boundary detection, which skips BOUNDARY's counts.
  const ToolRun plain =
      run(kReconstruction, {path("sphere_extra.xyz").string(),
                            path("sphere_plain.ply").string(), "-no_boundary"});
  expectSuccess(plain);
  EXPECT_NE(plain.out.find(expected), std::string::npos) << plain.out;
}

TEST_F(Tools, ReconstructionAsIndependentJobsWritesTheSameMesh)
{
  // A random torus, which 3 tiles really cut (a sphere's tiles fall back to one).
  std::vector<pcl::PointXYZ> torus;
  for (const Eigen::Vector3d& p :
       pcl::cocone::test::sampleRandom(pcl::cocone::test::Shape::torus, 20000, 4)
           .points)
    torus.emplace_back(float(p.x()), float(p.y()), float(p.z()));
  writeXyz("torus.xyz", torus);
  const std::string input = path("torus.xyz").string();
  const ToolRun one = run(kReconstruction, {input, path("torus_1.ply").string()});
  expectSuccess(one);

  const std::string output = path("torus_jobs.ply").string();
  const auto job = [&](int r, const Args& extra = {}) {
    Args args{input, output, "-jobs", "3", "-job", std::to_string(r)};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(kReconstruction, args);
  };
  // Job 0 first: the other jobs' tiles are missing, which it says before it computes.
  const ToolRun early = job(0);
  expectOneLineFailure(early, "torus_jobs.ply.job-1-of-3.tiles is missing");
  EXPECT_EQ(early.out.find("Computing"), std::string::npos) << early.out;
  // Job 1 with another cocone angle: job 0 refuses its tiles.
  expectSuccess(job(1, {"-theta", "0.3"}));
  expectSuccess(job(2));
  expectOneLineFailure(job(0), "was made from another input or other options");
  const ToolRun first = job(1);
  expectSuccess(first);
  EXPECT_NE(
      first.out.find("job 1 of 3: tiles written to " + output + ".job-1-of-3.tiles"),
      std::string::npos)
      << first.out;
  const ToolRun last = job(0, {"-v"});
  expectSuccess(last);
  EXPECT_NE(last.out.find("in 3 tiles"), std::string::npos) << last.out;
  EXPECT_TRUE(readText(output) == readText(path("torus_1.ply")))
      << "the jobs' mesh differs from one run's";
  // Job 0 removes the tiles once the mesh is written.
  EXPECT_FALSE(fs::exists(output + ".job-1-of-3.tiles"));
  EXPECT_FALSE(fs::exists(output + ".job-2-of-3.tiles"));

  // A truncated file fails with its reason.
  expectSuccess(job(1));
  expectSuccess(job(2));
  fs::resize_file(output + ".job-2-of-3.tiles", 400);
  expectOneLineFailure(job(0), "job-2-of-3.tiles is truncated");
  // Job numbers are checked before anything is loaded.
  expectArgumentError(run(kReconstruction, {input, output, "-job", "1"}),
                      "-job needs -jobs");
  expectArgumentError(run(kReconstruction, {input, output, "-jobs", "2", "-job", "2"}),
                      "-job 2 must be below -jobs 2");
  expectArgumentError(run(kReconstruction, {input, output, "-wait", "10"}),
                      "-wait needs -jobs");

  // All three at once: job 0 waits for the others' files, and the mesh is the same.
  // (The files of the failed run above go first: job 0 takes any whole file made from
  // the same input and options, as the README says.)
  fs::remove(output + ".job-1-of-3.tiles");
  fs::remove(output + ".job-2-of-3.tiles");
  auto waiting = std::async(std::launch::async, [&] {
    return job(0, {"-wait", "600"});
  });
  expectSuccess(job(2));
  expectSuccess(job(1));
  expectSuccess(waiting.get());
  EXPECT_TRUE(readText(output) == readText(path("torus_1.ply")))
      << "the mesh of jobs run side by side differs from one run's";
  EXPECT_FALSE(fs::exists(output + ".job-1-of-3.tiles"));
  // A job that never comes: job 0 gives up after its wait, naming the file.
  expectSuccess(job(1));
  expectOneLineFailure(job(0, {"-wait", "1"}),
                       "torus_jobs.ply.job-2-of-3.tiles did not appear within the 1 s");
  // A file from other options is refused before the wait and the work.
  expectSuccess(job(2, {"-theta", "0.3"}));
  const ToolRun foreign = job(0, {"-wait", "600"});
  expectOneLineFailure(foreign, "was made from another input or other options");
  EXPECT_EQ(foreign.out.find("Computing"), std::string::npos) << foreign.out;
}

TEST_F(Tools, ReconstructionOptionsAreAcceptedAndVerboseShowsTheStages)
{
  const ToolRun r = run(kReconstruction,
                        {path("hemisphere.xyz").string(), path("options.PLY").string(),
                         "-no_stitch", "-boundary_ratio", "3", "-theta", "0.35", "-rho",
                         "1", "-alpha", "0.6", "-threads", "2", "-v"});
  expectSuccess(r);
  for (const std::string text :
       {"Parameters", "Candidate triangles", "Stitched holes", "Samples put back",
        "Crossing triangles removed", "Unused points", "ms : ", "Computing"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text;
  // The class's own PCL_DEBUG statistics show with -v.
  EXPECT_NE(r.out.find("[pcl::CoconeReconstruction::reconstruct]"), std::string::npos);
  EXPECT_TRUE(meshSummary(r.out).found);

  const ToolRun cocone =
      run(kReconstruction,
          {path("sphere.xyz").string(), path("plain.obj").string(), "-no_boundary"});
  expectSuccess(cocone);
  EXPECT_TRUE(meshSummary(cocone.out).closed);
}

// --- decimation ----------------------------------------------------------------------

TEST_F(Tools, DecimationKeepsInputRowsWithAllFieldsInOrder)
{
  const fs::path output = path("sphere_decimated.pcd");
  const ToolRun r = run(kDecimation, {path("sphere.pcd").string(), output.string()});
  expectSuccess(r);
  const pcl::PCLPointCloud2 cloud = loadCloud(output);
  const std::size_t kept = rows(cloud);
  EXPECT_GT(kept, 10u);
  EXPECT_LT(kept, kSpherePoints);
  EXPECT_NE(r.out.find("kept " + std::to_string(kept) + " of " +
                       std::to_string(kSpherePoints) + " points ("),
            std::string::npos)
      << r.out;

  const pcl::PCLPointField* x = findField(cloud, "x");
  const pcl::PCLPointField* y = findField(cloud, "y");
  const pcl::PCLPointField* z = findField(cloud, "z");
  const pcl::PCLPointField* row = findField(cloud, "intensity");
  ASSERT_TRUE(x && y && z && row);
  long previous = -1;
  for (std::size_t i = 0; i < kept; ++i) {
    const float number = valueAt<float>(cloud, i, *row);
    const long input = std::lround(number);
    ASSERT_TRUE(input >= 0 && input < static_cast<long>(kSpherePoints)) << number;
    EXPECT_GT(input, previous) << "rows out of input order";
    previous = input;
    const pcl::PointXYZ& p = sphere_[static_cast<std::size_t>(input)];
    EXPECT_EQ(valueAt<float>(cloud, i, *x), p.x);
    EXPECT_EQ(valueAt<float>(cloud, i, *y), p.y);
    EXPECT_EQ(valueAt<float>(cloud, i, *z), p.z);
  }
}

TEST_F(Tools, DecimationRemovesMoreWithLargerRhoAndNeverKeepsNan)
{
  const fs::path fewer = path("rho25.pcd"), more = path("rho40.pcd");
  expectSuccess(run(kDecimation, {path("sphere_nan.pcd").string(), fewer.string(),
                                  "-rho", "0.25", "-theta", "0.3", "-threads", "1"}));
  expectSuccess(run(kDecimation,
                    {path("sphere_nan.pcd").string(), more.string(), "-rho", "0.4"}));
  const pcl::PCLPointCloud2 a = loadCloud(fewer), b = loadCloud(more);
  EXPECT_GT(rows(a), rows(b));
  const pcl::PCLPointField* x = findField(a, "x");
  ASSERT_NE(x, nullptr);
  for (std::size_t i = 0; i < rows(a); ++i)
    EXPECT_FALSE(std::isnan(valueAt<float>(a, i, *x)));
}

// By default the rim of an open surface is thinned like the rest; -keep_rims gives
// DECIMATE as published, which keeps the outermost row, so it keeps more points.
TEST_F(Tools, DecimationKeepRimsKeepsMoreOfAnOpenSurface)
{
  const fs::path thinned = path("hemisphere_thinned.pcd"),
                 kept = path("hemisphere_rims.pcd");
  const ToolRun r =
      run(kDecimation, {path("hemisphere.xyz").string(), thinned.string(), "-v"});
  expectSuccess(r);
  EXPECT_NE(r.out.find("rims thinned"), std::string::npos) << r.out;
  const ToolRun k = run(kDecimation, {path("hemisphere.xyz").string(), kept.string(),
                                      "-keep_rims", "-v"});
  expectSuccess(k);
  EXPECT_NE(k.out.find("rims kept"), std::string::npos) << k.out;
  const pcl::PCLPointCloud2 with_rims = loadCloud(kept), without = loadCloud(thinned);
  EXPECT_GT(rows(with_rims), rows(without) + 10) << r.out << k.out;
}

TEST_F(Tools, FileNamesWithSpacesWork)
{
  fs::copy_file(path("sphere.xyz"), path("my sphere.xyz"),
                fs::copy_options::overwrite_existing);
  const ToolRun r = run(kDecimation, {path("my sphere.xyz").string(),
                                      path("my decimated sphere.pcd").string()});
  expectSuccess(r);
  EXPECT_TRUE(fs::exists(path("my decimated sphere.pcd")));
}

// --- bad arguments -------------------------------------------------------------------

TEST_F(Tools, MissingArgumentsFail)
{
  for (const std::string& tool : kTools) {
    SCOPED_TRACE(tool);
    expectArgumentError(run(tool, {}), "missing arguments");
    expectArgumentError(run(tool, {path("sphere.xyz").string()}), "missing arguments");
    expectArgumentError(run(tool, {path("sphere.xyz").string(), "a.pcd", "b.pcd"}),
                        "unexpected argument");
  }
}

TEST_F(Tools, BadOptionValuesFailBeforeLoading)
{
  const std::vector<std::pair<Args, std::string>> common{
      {{"-rho", "-1"}, "-rho"},
      {{"-rho", "0"}, "-rho"},
      {{"-rho", "10.5"}, "-rho"},
      {{"-rho", "abc"}, "not a number"},
      {{"-rho", "1x"}, "not a number"},
      {{"-rho", "nan"}, "not a number"},
      {{"-rho"}, "needs a value"},
      {{"-rho", "-theta", "0.3"}, "needs a value"},
      {{"-theta", "2"}, "-theta"},
      {{"-theta", "1.5707963267948966"}, "-theta"},
      {{"-theta", "0"}, "-theta"},
      {{"-threads", "-1"}, "-threads"},
      {{"-threads", "1.5"}, "not an integer"},
      {{"-rho", "0.5", "-rho", "0.6"}, "more than once"}};
  for (const std::string& tool : kTools)
    for (const auto& [options, expected] : common) {
      Args args{path("sphere.xyz").string(), path("never.out").string()};
      // Each tool's own output format, so that only the option is wrong.
      args[1] = path(tool == kReconstruction ? "never.ply" : "never.pcd").string();
      args.insert(args.end(), options.begin(), options.end());
      SCOPED_TRACE(tool + " " + options.front() +
                   (options.size() > 1 ? " " + options[1] : ""));
      expectArgumentError(run(tool, args), expected);
      EXPECT_FALSE(fs::exists(args[1]));
    }

  const std::string input = path("sphere.xyz").string();
  const std::string pcd = path("never.pcd").string(), ply = path("never.ply").string();
  expectArgumentError(run(kBoundary, {input, pcd, "-alpha", "0"}), "-alpha");
  expectArgumentError(run(kBoundary, {input, pcd, "-alpha", "1.6"}), "-alpha");
  expectArgumentError(run(kBoundary, {input, pcd, "-band", "65"}), "-band");
  expectArgumentError(run(kBoundary, {input, pcd, "-band", "2.5"}), "not an integer");
  expectArgumentError(run(kReconstruction, {input, ply, "-boundary_ratio", "0.1"}),
                      "-boundary_ratio");
  expectArgumentError(run(kReconstruction, {input, ply, "-boundary_ratio", "1001"}),
                      "-boundary_ratio");
  expectArgumentError(run(kReconstruction, {input, ply, "-alpha", "-0.5"}), "-alpha");
}

TEST_F(Tools, UnknownOptionsFail)
{
  const std::string input = path("sphere.xyz").string();
  for (const std::string& tool : kTools) {
    SCOPED_TRACE(tool);
    const std::string output =
        path(tool == kReconstruction ? "u.ply" : "u.pcd").string();
    expectArgumentError(run(tool, {input, output, "-foo"}), "unknown option '-foo'");
    expectArgumentError(run(tool, {input, output, "-theat", "0.3"}), "unknown option");
    expectArgumentError(run(tool, {input, output, "--rho", "0.3"}), "unknown option");
  }
  // Options of one tool are unknown to the others.
  expectArgumentError(
      run(kDecimation, {input, path("u.pcd").string(), "-alpha", "0.5"}),
      "unknown option '-alpha'");
  expectArgumentError(run(kBoundary, {input, path("u.pcd").string(), "-no_stitch"}),
                      "unknown option");
}

TEST_F(Tools, UnsupportedOutputExtensionsFail)
{
  const std::string input = path("sphere.xyz").string();
  expectArgumentError(run(kBoundary, {input, path("out.txt").string()}), "out.txt");
  expectArgumentError(run(kBoundary, {input, path("out.ply").string()}),
                      "expected .pcd");
  expectArgumentError(run(kDecimation, {input, path("out").string()}), "unsupported");
  expectArgumentError(run(kReconstruction, {input, path("out.stl").string()}), ".ply");
  expectArgumentError(run(kReconstruction, {input, path("out.pcd").string()}),
                      "unsupported");
}

// --- bad inputs ----------------------------------------------------------------------

TEST_F(Tools, MissingOrUnreadableInputFails)
{
  for (const std::string& tool : kTools) {
    SCOPED_TRACE(tool);
    const std::string output =
        path(tool == kReconstruction ? "i.ply" : "i.pcd").string();
    for (const std::string input : {"missing.xyz", "folder.xyz", "folder.pcd",
                                    "garbage.xyz", "garbage.pcd", "empty.xyz"}) {
      SCOPED_TRACE(input);
      // The reader's reason names the file.
      expectOneLineFailure(run(tool, {path(input).string(), output}), input);
      EXPECT_FALSE(fs::exists(output));
    }
  }
}

TEST_F(Tools, CoplanarInputFailsWithOneLine)
{
  for (const std::string& tool : kTools) {
    SCOPED_TRACE(tool);
    const std::string output =
        path(tool == kReconstruction ? "c.ply" : "c.pcd").string();
    const ToolRun r = run(tool, {path("plane.xyz").string(), output});
    expectOneLineFailure(r, "coplanar");
    EXPECT_FALSE(fs::exists(output));
  }
}

TEST_F(Tools, FailedSavesFail)
{
  const std::string input = path("sphere.xyz").string();
  for (const std::string& tool : kTools) {
    SCOPED_TRACE(tool);
    const std::string ext = tool == kReconstruction ? ".ply" : ".pcd";
    expectArgumentError(run(tool, {input, path("no/such/folder/out" + ext).string()}),
                        "does not exist");
    fs::create_directories(path("a_folder" + ext));
    expectArgumentError(run(tool, {input, path("a_folder" + ext).string()}), "folder");
    // A full disk shows only when writing: the tool must notice it.
    if (fs::exists("/dev/full")) {
      const fs::path full = path("full" + ext);
      fs::remove(full);
      fs::create_symlink("/dev/full", full);
      expectOneLineFailure(run(tool, {input, full.string()}), "cannot write");
    }
  }
}

TEST_F(Tools, HostilePcdHeadersFailWithOneLine)
{
  // The two reproductions of the reliability issue: a COUNT whose product with SIZE
  // overflows (SIGFPE in the check, or PCL's readBodyBinary crashing), and a SIZE that
  // an int cast cut to 4 (8.4 GB allocated, then "all points are collinear").
  const std::string count = "VERSION 0.7\nFIELDS x y z w\nSIZE 4 4 4 4\nTYPE F F F F\n"
                            "COUNT 1 1 1 4611686018427387901\nWIDTH 10\nHEIGHT 1\n"
                            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n";
  writeText("hostile_count.pcd", count + std::string(400, '\0'));
  const std::string size = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4294967300\n"
                           "TYPE F F F\nCOUNT 1 1 1\nWIDTH 10\nHEIGHT 1\n"
                           "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n";
  writeText("hostile_size.pcd", size + std::string(150, '\0'));
  for (const char* input : {"hostile_count.pcd", "hostile_size.pcd"}) {
    SCOPED_TRACE(input);
    const std::string output = path("hostile_out.pcd").string();
    expectOneLineFailure(run(kBoundary, {path(input).string(), output}),
                         "has an invalid SIZE, TYPE or COUNT");
    EXPECT_FALSE(fs::exists(output));
  }
}

// --- writing over the input ----------------------------------------------------------

/** The files of \a folder whose names start with a dot: the writers' temporary ones. */
std::vector<std::string>
hiddenFiles(const fs::path& folder)
{
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().front() == '.')
      names.push_back(entry.path().filename().string());
  return names;
}

/** A folder of its own for \a name, holding a copy of \a source as \a file. */
fs::path
freshCopy(const fs::path& folder, const fs::path& source, const std::string& file)
{
  fs::remove_all(folder);
  fs::create_directories(folder);
  fs::copy_file(source, folder / file);
  return folder / file;
}

/** The tools (and the pipeline example, when built) with an input of the format each
 * can also write, made from the sphere: the tool, the input, its contents. */
struct SameFileCase
{
  std::string tool;
  fs::path source;
  std::string file;
  Args options{};
};

/** The sphere as an ascii PLY of its vertices: an input the mesh writers do not write,
 * so that their output differs from it. */
fs::path
spherePly(const std::vector<pcl::PointXYZ>& sphere, const fs::path& file)
{
  std::ofstream out(file);
  out << "ply\nformat ascii 1.0\nelement vertex " << sphere.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  char line[96];
  for (const pcl::PointXYZ& p : sphere) {
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p.x, p.y, p.z);
    out << line;
  }
  return file;
}

TEST_F(Tools, OutputMayBeTheInput)
{
  const fs::path ply = spherePly(sphere_, path("sphere_points.ply"));
  std::vector<SameFileCase> cases = {{kBoundary, path("sphere.pcd"), "same.pcd"},
                                     {kDecimation, path("sphere.pcd"), "same.pcd"},
                                     {kReconstruction, ply, "same.ply"}};
  if (kExampleDir)
    cases.push_back({kPipeline, ply, "same.ply"});
  for (const SameFileCase& c : cases) {
    SCOPED_TRACE(c.tool);
    const fs::path folder = path("same_" + c.tool);
    const fs::path file = freshCopy(folder, c.source, c.file);
    const std::string before = readText(file);
    expectSuccess(run(c.tool, {file.string(), file.string()}));
    EXPECT_TRUE(readText(file) != before) << "the output did not replace the input";
    if (c.file == "same.pcd")
      EXPECT_GT(rows(loadCloud(file)), 0u);
    else
      EXPECT_FALSE(loadTriangles(file, kSpherePoints).empty());
    EXPECT_TRUE(hiddenFiles(folder).empty());
  }
}

TEST_F(Tools, FailedWriteLeavesTheInputAsItWas)
{
  const fs::path ply = spherePly(sphere_, path("limit_points.ply"));
  // The decimation keeps most samples at a small rho, so that its output too is far
  // larger than the limit.
  std::vector<SameFileCase> cases = {
      {kBoundary, path("sphere.pcd"), "same.pcd"},
      {kDecimation, path("sphere.pcd"), "same.pcd", {"-rho", "0.05"}},
      {kReconstruction, ply, "same.ply"}};
  if (kExampleDir)
    cases.push_back({kPipeline, ply, "same.ply"});
  for (const SameFileCase& c : cases) {
    SCOPED_TRACE(c.tool);
    const fs::path folder = path("limit_" + c.tool);
    const fs::path file = freshCopy(folder, c.source, c.file);
    const std::string before = readText(file);
    // Files may grow to 4 blocks (2 or 4 KB, whichever unit the shell counts in), far
    // less than any output here, but enough for the tools' stdout. Reading is not
    // limited. A tool ignores SIGXFSZ itself, so the write fails with EFBIG.
    Args args = {file.string(), file.string()};
    args.insert(args.end(), c.options.begin(), c.options.end());
    const ToolRun r = run(c.tool, args, "ulimit -f 4; ");
    if (c.tool == kPipeline) {
      EXPECT_EQ(r.exit_code, 1);
      EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    }
    else {
      expectOneLineFailure(r, "cannot write " + file.string() + ": File too large");
    }
    EXPECT_TRUE(readText(file) == before) << "the failed write changed the input";
    EXPECT_TRUE(hiddenFiles(folder).empty());
  }
}

} // namespace
