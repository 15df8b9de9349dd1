// SPDX-License-Identifier: GPL-3.0-or-later
// The writers of pcl_cocone_io: what they write reads back through the library's own
// readers as the same floats and triangles, and a write that cannot happen says why.
#include "support/scratch_folder.h"

#include <pcl/cocone/io/point_io.h>
#include <pcl/cocone/io/writers.h>

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

namespace fs = std::filesystem;

/** Each test gets its own folder, removed afterwards. */
class Writers : public ::testing::Test
{
protected:
  std::string
  path(const std::string& name) const
  {
    return (dir_ / name).string();
  }

  pcl::cocone::test::ScratchFolder scratch_{"pcl_cocone_writers_"};
  const fs::path& dir_ = scratch_.path();
};

std::string
contentsOf(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

using Vertices = std::vector<std::array<float, 3>>;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// Values whose shortest decimal form needs all nine digits, and one that is tiny.
const Vertices kVertices = {{0.1f, -2.5f, 3.0f},
                            {1.0f / 3.0f, 1e-30f, -7.0f},
                            {123456.789f, 0.0f, -0.0f},
                            {2.0f, 2.0f / 3.0f, 1e10f}};
const Triangles kTriangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 1}};

TEST_F(Writers, MeshesReadBackExactlyInEveryFormat)
{
  for (const char* name : {"mesh.ply", "mesh.vtk", "MESH.OBJ"}) {
    SCOPED_TRACE(name);
    const std::string file = path(name);
    std::string error = "stale";
    ASSERT_TRUE(pcl::cocone::saveMesh(file, kVertices, kTriangles, "the_test", &error))
        << error;
    EXPECT_TRUE(error.empty());
    EXPECT_NE(contentsOf(file).find("written by the_test"), std::string::npos);
    if (fs::path(name).extension() == ".vtk")
      continue; // no reader of ours for VTK
    pcl::PCLPointCloud2 cloud;
    ASSERT_TRUE(pcl::cocone::loadPointSamples(file, cloud, &error)) << error;
    ASSERT_EQ(cloud.width, kVertices.size());
    for (std::size_t i = 0; i < kVertices.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        float value;
        std::memcpy(&value,
                    cloud.data.data() + i * cloud.point_step + cloud.fields[k].offset,
                    sizeof value);
        EXPECT_EQ(value, kVertices[i][k]) << i << " " << k;
      }
    std::vector<pcl::Vertices> faces;
    ASSERT_TRUE(pcl::cocone::loadMeshFaces(file, faces, &error)) << error;
    ASSERT_EQ(faces.size(), kTriangles.size());
    for (std::size_t t = 0; t < kTriangles.size(); ++t)
      EXPECT_EQ(
          std::vector<pcl::index_t>(faces[t].vertices.begin(), faces[t].vertices.end()),
          (std::vector<pcl::index_t>(kTriangles[t].begin(), kTriangles[t].end())));
  }
}

TEST_F(Writers, VtkIsLegacyAsciiPolydata)
{
  const std::string file = path("mesh.vtk");
  ASSERT_TRUE(pcl::cocone::saveMesh(file, kVertices, kTriangles, "x"));
  const std::string text = contentsOf(file);
  EXPECT_EQ(text.rfind("# vtk DataFile Version 3.0\n", 0), 0u);
  EXPECT_NE(text.find("DATASET POLYDATA\nPOINTS 4 float\n0.1 -2.5 3\n"),
            std::string::npos);
  EXPECT_NE(text.find("POLYGONS 3 12\n3 0 1 2\n3 0 2 3\n3 3 2 1\n"), std::string::npos);
}

TEST_F(Writers, CloudKeepsItsFieldsAndOrganization)
{
  pcl::PCLPointCloud2 cloud;
  for (const char* name : {"x", "y", "z", "intensity"}) {
    pcl::PCLPointField field;
    field.name = name;
    field.offset = static_cast<std::uint32_t>(4 * cloud.fields.size());
    field.datatype = pcl::PCLPointField::FLOAT32;
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.width = 2;
  cloud.height = 3;
  cloud.point_step = 16;
  cloud.row_step = 32;
  cloud.data.resize(6 * 16);
  for (std::size_t i = 0; i < cloud.data.size() / 4; ++i) {
    const float value = 0.5f * static_cast<float>(i);
    std::memcpy(cloud.data.data() + 4 * i, &value, 4);
  }
  const std::string file = path("cloud.pcd");
  std::string error;
  ASSERT_TRUE(pcl::cocone::saveCloud(file, cloud, &error)) << error;
  pcl::PCLPointCloud2 back;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(file, back, &error)) << error;
  EXPECT_EQ(back.width, 2u);
  EXPECT_EQ(back.height, 3u);
  ASSERT_EQ(back.fields.size(), 4u);
  EXPECT_EQ(back.fields[3].name, "intensity");
  EXPECT_EQ(back.data, cloud.data);
}

TEST_F(Writers, FailuresSayWhyInOneLine)
{
  std::string error;
  EXPECT_FALSE(
      pcl::cocone::saveMesh(path("mesh.stl"), kVertices, kTriangles, "x", &error));
  EXPECT_NE(error.find("unsupported mesh format"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(path("mesh.stl")));

  const std::string missing = path("no/such/folder/mesh.ply");
  EXPECT_FALSE(pcl::cocone::saveMesh(missing, kVertices, kTriangles, "x", &error));
  EXPECT_NE(error.find("cannot write " + missing + ": "), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);

  pcl::PCLPointCloud2 broken;
  broken.width = 3;
  broken.height = 1;
  broken.point_step = 12;
  broken.data.resize(20);
  EXPECT_FALSE(pcl::cocone::saveCloud(path("broken.pcd"), broken, &error));
  EXPECT_NE(error.find("inconsistent data size"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(path("broken.pcd")));

  // The reason is optional.
  EXPECT_FALSE(pcl::cocone::writeFile(missing, "abc", 3));
}

/** The names in \a folder, sorted: a write must leave no temporary file behind. */
std::vector<std::string>
namesIn(const fs::path& folder)
{
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST_F(Writers, ReplacingAFileKeepsItsPermissionsAndLeavesNothingElse)
{
  const std::string file = path("data.bin");
  ASSERT_TRUE(pcl::cocone::writeFile(file, "old contents", 12));
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write |
                            fs::perms::group_read);
  std::string error = "stale";
  ASSERT_TRUE(pcl::cocone::writeFile(file, "new", 3, &error)) << error;
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(contentsOf(file), "new");
  EXPECT_EQ(fs::status(file).permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(namesIn(dir_), std::vector<std::string>{"data.bin"});
}

TEST_F(Writers, ALinkStaysALinkAndItsTargetIsReplaced)
{
  fs::create_directories(dir_ / "real");
  const std::string target = path("real/mesh.ply");
  ASSERT_TRUE(pcl::cocone::writeFile(target, "old", 3));
  fs::create_symlink("real/mesh.ply", dir_ / "link.ply");
  ASSERT_TRUE(pcl::cocone::saveMesh(path("link.ply"), kVertices, kTriangles, "x"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.ply"));
  // A link to that link: both stay.
  fs::create_symlink("link.ply", dir_ / "link2.ply");
  ASSERT_TRUE(pcl::cocone::saveMesh(path("link2.ply"), kVertices, kTriangles, "y"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "link2.ply"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.ply"));
  EXPECT_NE(contentsOf(target).find("written by y"), std::string::npos);
  EXPECT_EQ(contentsOf(target).rfind("ply\n", 0), 0u);
  EXPECT_EQ(namesIn(dir_ / "real"), std::vector<std::string>{"mesh.ply"});
}

TEST_F(Writers, AFailedWriteLeavesTheFileAsItWas)
{
  const std::string file = path("mesh.ply");
  ASSERT_TRUE(pcl::cocone::writeFile(file, "the input", 9));
  // In a child: files may grow to 1000 bytes only, and SIGXFSZ is ignored, as the
  // tools do, so that the write fails with EFBIG instead of ending the process.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const std::string big(5000, 'x');
    std::string error;
    const bool written = pcl::cocone::writeFile(file, big.data(), big.size(), &error);
    ::_exit(!written && error == "cannot write " + file + ": File too large" ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(contentsOf(file), "the input");
  EXPECT_EQ(namesIn(dir_), std::vector<std::string>{"mesh.ply"});
}

TEST_F(Writers, AFileWeMayNotWriteIsNotReplaced)
{
  const std::string file = path("locked.pcd");
  ASSERT_TRUE(pcl::cocone::writeFile(file, "locked", 6));
  fs::permissions(file, fs::perms::owner_read);
  if (::access(file.c_str(), W_OK) == 0)
    GTEST_SKIP() << "running with rights that write any file (root?)";
  std::string error;
  EXPECT_FALSE(pcl::cocone::writeFile(file, "new", 3, &error));
  EXPECT_NE(error.find("Permission denied"), std::string::npos) << error;
  EXPECT_EQ(contentsOf(file), "locked");
}

TEST_F(Writers, MeshForWritingDropsNonFiniteAndFarPointsAndRenumbers)
{
  // Points 1 (NaN) and 4 (infinite) are not finite, 3 is far; 0, 2, 5 and 6 remain,
  // as vertices 0 to 3.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  pcl::PointCloud<pcl::PointXYZ> points;
  for (const pcl::PointXYZ& p :
       {pcl::PointXYZ(0, 0, 0), pcl::PointXYZ(nan, 0, 0), pcl::PointXYZ(1, 0, 0),
        pcl::PointXYZ(1e30f, 1e30f, 1e30f), pcl::PointXYZ(0, INFINITY, 0),
        pcl::PointXYZ(0, 1, 0), pcl::PointXYZ(0, 0, 1)})
    points.push_back(p);
  const Triangles triangles = {{0, 2, 5}, {0, 5, 6}, {2, 6, 5}};
  pcl::cocone::MeshForWriting mesh;
  std::string error = "stale";
  ASSERT_TRUE(pcl::cocone::meshForWriting(points, triangles, {3}, mesh, &error))
      << error;
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(mesh.vertices, (Vertices{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  EXPECT_EQ(mesh.triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {1, 3, 2}}));
  EXPECT_EQ(mesh.non_finite_dropped, 2u);
  EXPECT_EQ(mesh.far_dropped, 1u);

  // What the tool writes reads back as those vertices and triangles.
  const std::string file = path("written.obj");
  ASSERT_TRUE(pcl::cocone::saveMesh(file, mesh.vertices, mesh.triangles, "t", &error))
      << error;
  std::vector<pcl::Vertices> faces;
  ASSERT_TRUE(pcl::cocone::loadMeshFaces(file, faces, &error)) << error;
  ASSERT_EQ(faces.size(), 3u);
  EXPECT_EQ(
      std::vector<pcl::index_t>(faces[2].vertices.begin(), faces[2].vertices.end()),
      (std::vector<pcl::index_t>{1, 3, 2}));

  // A triangle on a dropped or missing point, or a far index beyond the cloud, is a
  // caller's error, reported and leaving the mesh empty.
  for (const auto& [bad_triangles, far, expected] :
       std::vector<std::tuple<Triangles, pcl::Indices, std::string>>{
           {{{0, 1, 2}}, {3}, "uses point 1, which is not finite or far"},
           {{{0, 3, 2}}, {3}, "uses point 3, which is not finite or far"},
           {{{0, 2, 7}}, {3}, "uses point 7, beyond the cloud"},
           {{{0, 2, 5}}, {7}, "far point 7 is not a point of the cloud"},
           {{{0, 2, 5}}, {-1}, "far point -1 is not a point of the cloud"}}) {
    EXPECT_FALSE(pcl::cocone::meshForWriting(points, bad_triangles, far, mesh, &error));
    EXPECT_NE(error.find(expected), std::string::npos) << error;
    EXPECT_TRUE(mesh.vertices.empty() && mesh.triangles.empty());
  }
}

TEST_F(Writers, MeshFormatsAreKnownByExtension)
{
  for (const char* name : {"a.ply", "b/c.OBJ", "d.Vtk"})
    EXPECT_TRUE(pcl::cocone::isMeshFormat(name)) << name;
  for (const char* name : {"a.stl", "ply", "a.ply.gz", "", "a.pcd"})
    EXPECT_FALSE(pcl::cocone::isMeshFormat(name)) << name;
}

} // namespace
