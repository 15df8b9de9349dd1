// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_io_speed: how fast pcl_cocone_io loads and saves large files, the way the
// tools do it. Generates N random points (and, for the mesh, 2N - 4 triangles, as many
// as a closed surface through them has), then times:
//   - saveCloud to binary PCD, and loadPointSamples of it plus the conversion to
//     pcl::PointCloud<pcl::PointXYZ> that the tools make (toXyz);
//   - saveMesh to binary PLY, and loadPointSamples of it (its vertices) plus the same
//     conversion;
//   - a LAS file of format 1 (written here), loaded the same way.
// Every write includes the fsync of the atomic write (writeFile). Prints seconds and
// MB/s (file bytes over seconds) per step, the best of --repeat runs.
//
//   pcl_cocone_io_speed [--points N] [--dir FOLDER] [--repeat R]
// (defaults: 10000000 points, /tmp, 3 runs)
#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/las_file.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

double
bestSeconds(int repeat, const std::function<void()>& step)
{
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    step();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                  .count());
  }
  return best;
}

std::size_t point_count = 0;

/** One row of the table: the step, its file's size, its time, the file's bytes and the
 * points per second. */
void
row(const std::string& step, const std::string& path, double seconds)
{
  const double megabytes = static_cast<double>(fs::file_size(path)) / 1e6;
  std::printf("| %s | %.0f MB | %.3f s | %.0f MB/s | %.1f M/s |\n", step.c_str(),
              megabytes, seconds, megabytes / seconds,
              static_cast<double>(point_count) / seconds / 1e6);
  std::fflush(stdout);
}

[[noreturn]] void
die(const std::string& message)
{
  std::fprintf(stderr, "pcl_cocone_io_speed: %s\n", message.c_str());
  std::exit(1);
}

/** Times loading \a path as the tools do, best of \a repeat: loadPointSamples, then
 * the conversion to pcl::PointCloud<pcl::PointXYZ> (toXyz), each on its own row. */
void
timeLoad(const std::string& what, const std::string& path, std::size_t expected,
         int repeat)
{
  // For reference: the file's bytes alone, read whole as the readers do.
  row("  its bytes alone (one fread into fresh memory)", path, bestSeconds(repeat, [&] {
        std::vector<char> bytes(fs::file_size(path));
        std::FILE* file = std::fopen(path.c_str(), "rb");
        if (!file || std::fread(bytes.data(), 1, bytes.size(), file) != bytes.size())
          die("cannot read " + path);
        std::fclose(file);
      }));
  pcl::PCLPointCloud2 blob;
  row("load " + what + " (loadPointSamples)", path, bestSeconds(repeat, [&] {
        std::string error;
        if (!pcl::cocone::loadPointSamples(path, blob, &error))
          die(error);
      }));
  pcl::PointCloud<pcl::PointXYZ> xyz;
  row("  then fromPCLPointCloud2 to PointXYZ (the tools' toXyz)", path,
      bestSeconds(repeat, [&] { pcl::fromPCLPointCloud2(blob, xyz); }));
  if (xyz.size() != expected)
    die(path + ": read " + std::to_string(xyz.size()) + " points");
}

} // namespace

int
main(int argc, char** argv)
{
  std::size_t n = 10000000;
  fs::path dir = "/tmp";
  int repeat = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--points")
      n = std::strtoull(argv[i + 1], nullptr, 10);
    else if (option == "--dir")
      dir = argv[i + 1];
    else if (option == "--repeat")
      repeat = std::max(1, std::atoi(argv[i + 1]));
    else
      die("unknown option " + option);
  }
  if (n < 4)
    die("--points must be at least 4");
  point_count = n;

  std::mt19937_64 random(1);
  std::uniform_real_distribution<float> uniform(-100.0f, 100.0f);
  std::vector<std::array<float, 3>> vertices(n);
  for (auto& v : vertices)
    v = {uniform(random), uniform(random), uniform(random)};
  std::uniform_int_distribution<std::uint32_t> index(0,
                                                     static_cast<std::uint32_t>(n - 1));
  std::vector<std::array<std::uint32_t, 3>> triangles(2 * n - 4);
  for (auto& t : triangles)
    t = {index(random), index(random), index(random)};

  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    cloud[i] = pcl::PointXYZ(vertices[i][0], vertices[i][1], vertices[i][2]);
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);

  const std::string tag = std::to_string(::getpid());
  const std::string pcd = (dir / ("io_speed_" + tag + ".pcd")).string();
  const std::string ply = (dir / ("io_speed_" + tag + ".ply")).string();
  const std::string points_ply = (dir / ("io_speed_points_" + tag + ".ply")).string();
  const std::string las = (dir / ("io_speed_" + tag + ".las")).string();
  std::string error;

  std::printf("%zu points, %zu triangles, best of %d\n\n", n, triangles.size(), repeat);
  std::printf("| step | file | time | file speed | points |\n|---|---|---|---|---|\n");
  row("save binary PCD (saveCloud)", pcd, bestSeconds(repeat, [&] {
        if (!pcl::cocone::saveCloud(pcd, blob, &error))
          die(error);
      }));
  timeLoad("binary PCD", pcd, n, repeat);
  row("save binary PLY mesh (saveMesh, 2n-4 triangles)", ply, bestSeconds(repeat, [&] {
        if (!pcl::cocone::saveMesh(ply, vertices, triangles, "io_speed", &error))
          die(error);
      }));
  // The encoding alone: a link named .ply to /dev/null, which writeFile writes
  // directly (a device), without file system, rename or fsync.
  const std::string null_ply = (dir / ("io_speed_null_" + tag + ".ply")).string();
  fs::create_symlink("/dev/null", null_ply);
  const double encoding = bestSeconds(repeat, [&] {
    if (!pcl::cocone::saveMesh(null_ply, vertices, triangles, "io_speed", &error))
      die(error);
  });
  fs::remove(null_ply);
  row("  saveMesh's encoding alone (written to /dev/null)", ply, encoding);
  // For reference: the same number of bytes written by writeFile alone (the atomic
  // write with its fsync), the floor of any save.
  {
    const std::string bytes(fs::file_size(ply), '\x5a');
    row("  writeFile of as many bytes (the floor of a save)", ply,
        bestSeconds(repeat, [&] {
          if (!pcl::cocone::writeFile(ply, bytes.data(), bytes.size(), &error))
            die(error);
        }));
    if (!pcl::cocone::saveMesh(ply, vertices, triangles, "io_speed", &error))
      die(error);
  }
  timeLoad("binary PLY mesh's vertices", ply, n, repeat);
  if (!pcl::cocone::saveMesh(points_ply, vertices, {}, "io_speed", &error))
    die(error);
  timeLoad("binary PLY points, no faces", points_ply, n, repeat);

  std::vector<pcl::cocone::test::LasPoint> las_points(n);
  for (std::size_t i = 0; i < n; ++i)
    las_points[i] = {static_cast<std::int32_t>(vertices[i][0] * 1000),
                     static_cast<std::int32_t>(vertices[i][1] * 1000),
                     static_cast<std::int32_t>(vertices[i][2] * 1000), 0, 2};
  pcl::cocone::test::LasLayout layout;
  layout.scale = {0.001, 0.001, 0.001};
  {
    const std::string bytes = pcl::cocone::test::lasFile(layout, las_points);
    if (!pcl::cocone::writeFile(las, bytes.data(), bytes.size(), &error))
      die(error);
  }
  timeLoad("LAS 1.2 point format 1", las, n, repeat);

  for (const std::string& path : {pcd, ply, points_ply, las})
    fs::remove(path);
  return 0;
}
