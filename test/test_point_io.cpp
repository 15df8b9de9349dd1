// SPDX-License-Identifier: GPL-3.0-or-later
// The readers on small files written here (every format, every failure), then on the
// real data folder when it is there.
#include "support/data_paths.h"
#include "support/scratch_folder.h"

#include <pcl/cocone/io/point_io.h>
#include <pcl/common/io.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

using pcl::cocone::test::findField;
using pcl::cocone::test::valueAt;

namespace fs = std::filesystem;
using pcl::PCLPointField;

/** Each test gets its own folder, removed afterwards. */
class PointIo : public ::testing::Test
{
protected:
  std::string
  write(const std::string& name, const std::string& contents) const
  {
    const fs::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out << contents;
    return path.string();
  }

  std::string
  path(const std::string& name) const
  {
    return (dir_ / name).string();
  }

  pcl::cocone::test::ScratchFolder scratch_{"pcl_cocone_point_io_"};
  const fs::path& dir_ = scratch_.path();
};

/** x, y, z of every point, checking that they are single float fields. */
std::vector<float>
coordinates(const pcl::PCLPointCloud2& cloud)
{
  std::vector<float> xyz;
  for (const char* name : {"x", "y", "z"}) {
    const PCLPointField* field = findField(cloud, name);
    EXPECT_NE(field, nullptr) << name;
    if (!field)
      return xyz;
    EXPECT_EQ(field->datatype, PCLPointField::FLOAT32) << name;
    EXPECT_EQ(field->count, 1u) << name;
  }
  const std::size_t points = static_cast<std::size_t>(cloud.width) * cloud.height;
  EXPECT_EQ(cloud.data.size(), points * cloud.point_step);
  for (std::size_t i = 0; i < points; ++i)
    for (const char* name : {"x", "y", "z"})
      xyz.push_back(valueAt<float>(cloud, i, name));
  return xyz;
}

/** Runs \a load, a reader of \a path given where to put its reason. Both readers fail
 * the same way: false, a one-line reason, and nothing on stderr. Returns the reason. */
template <typename Load>
std::string
expectQuietFailure(const std::string& path, Load load)
{
  std::string error;
  ::testing::internal::CaptureStderr();
  const bool ok = load(&error);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok) << path;
  EXPECT_TRUE(printed.empty()) << printed;
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  return error;
}

/** Loads a file that must fail: false, an empty cloud, a one-line reason naming the
 * file, and nothing on stderr. Returns the reason. */
std::string
expectSamplesFailure(const std::string& path)
{
  pcl::PCLPointCloud2 cloud;
  cloud.width = 7; // something to be cleared
  cloud.height = 1;
  cloud.data.assign(84, 1);
  const std::string error = expectQuietFailure(path, [&](std::string* reason) {
    return pcl::cocone::loadPointSamples(path, cloud, reason);
  });
  EXPECT_NE(error.find(fs::path(path).filename().string()), std::string::npos) << error;
  EXPECT_EQ(cloud.width * cloud.height, 0u);
  EXPECT_TRUE(cloud.data.empty());
  EXPECT_TRUE(cloud.fields.empty());
  // The reason is optional.
  EXPECT_FALSE(pcl::cocone::loadPointSamples(path, cloud));
  return error;
}

std::string
expectFacesFailure(const std::string& path)
{
  std::vector<pcl::Vertices> faces(2);
  const std::string error = expectQuietFailure(path, [&](std::string* reason) {
    return pcl::cocone::loadMeshFaces(path, faces, reason);
  });
  EXPECT_TRUE(faces.empty());
  return error;
}

pcl::PCLPointCloud2
expectSamples(const std::string& path, std::size_t points)
{
  pcl::PCLPointCloud2 cloud;
  std::string error = "stale";
  ::testing::internal::CaptureStderr();
  const bool ok = pcl::cocone::loadPointSamples(path, cloud, &error);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(printed.empty()) << printed;
  EXPECT_EQ(static_cast<std::size_t>(cloud.width) * cloud.height, points);
  EXPECT_EQ(cloud.row_step, cloud.point_step * cloud.width);
  return cloud;
}

std::vector<pcl::Vertices>
expectFaces(const std::string& path, std::size_t count)
{
  std::vector<pcl::Vertices> faces;
  std::string error;
  EXPECT_TRUE(pcl::cocone::loadMeshFaces(path, faces, &error)) << error;
  EXPECT_EQ(faces.size(), count);
  return faces;
}

std::vector<pcl::index_t>
corners(const pcl::Vertices& face)
{
  return std::vector<pcl::index_t>(face.vertices.begin(), face.vertices.end());
}

// Binary PLY bodies are assembled value by value in either byte order.
template <typename T>
void
append(std::string& out, T value, bool big_endian)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  const bool host_big = *reinterpret_cast<const char*>(&probe) == 0;
  if (host_big != big_endian)
    std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

// ---------------------------------------------------------------------------------
// Column formats

TEST_F(PointIo, XyzColumnsCommentsBlankLinesAndNoFinalNewline)
{
  const std::string file = write("points.xyz", "# a comment\n"
                                               "1 2 3\n"
                                               "\n"
                                               "   \t \n"
                                               "4.5\t-5e-1  +6E2 0.1 0.2 0.3\r\n"
                                               "  # indented comment\n"
                                               "-1.25e+01 .5 7. extra words\n"
                                               "8 9 10");
  const pcl::PCLPointCloud2 cloud = expectSamples(file, 4);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_TRUE(cloud.is_dense);
  ASSERT_EQ(cloud.fields.size(), 3u);
  EXPECT_EQ(cloud.fields[0].name, "x");
  EXPECT_EQ(cloud.fields[1].name, "y");
  EXPECT_EQ(cloud.fields[2].name, "z");
  EXPECT_EQ(cloud.point_step, 12u);
  const std::vector<float> expected = {1,      2,    3, 4.5f, -0.5f, 600,
                                       -12.5f, 0.5f, 7, 8,    9,     10};
  EXPECT_EQ(coordinates(cloud), expected);
}

TEST_F(PointIo, XyzKeepsNonFinitePointsInOrder)
{
  const std::string file = write("nan.txt", "1 2 3\nnan nan nan\n4 inf 6\n7 8 9\n");
  const pcl::PCLPointCloud2 cloud = expectSamples(file, 4);
  EXPECT_FALSE(cloud.is_dense);
  const std::vector<float> xyz = coordinates(cloud);
  ASSERT_EQ(xyz.size(), 12u);
  EXPECT_EQ(xyz[0], 1);
  EXPECT_TRUE(std::isnan(xyz[3]) && std::isnan(xyz[4]) && std::isnan(xyz[5]));
  EXPECT_TRUE(std::isinf(xyz[7]));
  EXPECT_EQ(xyz[11], 9);
}

TEST_F(PointIo, XyzExtremeValues)
{
  // Below double's normal range and beyond float's: a text reader would give 0 (or a
  // denormal) and infinity.
  const std::string file = write("extreme.xyz", "1e-320 1e-400 1e300\n");
  const std::vector<float> xyz = coordinates(expectSamples(file, 1));
  ASSERT_EQ(xyz.size(), 3u);
  EXPECT_EQ(xyz[0], 0.0f);
  EXPECT_EQ(xyz[1], 0.0f);
  EXPECT_EQ(xyz[2], std::numeric_limits<float>::infinity());
}

TEST_F(PointIo, HoppePtsAndExtensionCase)
{
  const std::string file = write("hoppe.PTS", "# Created by a scanner\n"
                                              "p 0.5 0.25 0.125\n"
                                              "n 0 0 1\n"
                                              "p 1 2 3\n"
                                              "n 0 1 0\n");
  const std::vector<float> expected = {0.5f, 0.25f, 0.125f, 1, 2, 3};
  EXPECT_EQ(coordinates(expectSamples(file, 2)), expected);
  // Plain columns in a .pts file (Power Crust's knot) and an upper-case .XYZ.
  EXPECT_EQ(coordinates(expectSamples(write("plain.pts", " 0 0 0 \n1 1 1 \n"), 2)),
            (std::vector<float>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(coordinates(expectSamples(write("upper.XYZ", "1 2 3\n"), 1)),
            (std::vector<float>{1, 2, 3}));
}

TEST_F(PointIo, HoppeA3dStreamAsWritten)
{
  // What WA3dStream writes: comments, colour state before the first point, a normal
  // before each point, commands between points, and an end record after which the
  // file is no longer a3d.
  const std::string file = write("a3d.pts", "# Created by WA3dStream\n"
                                            "# Created by ioa3d\n"
                                            "d 0 0 0\n"
                                            "s 0 0 0\n"
                                            "g 1 0 0\n"
                                            "n 0 0 1\n"
                                            "p 0.5 0.25 0.125\n"
                                            "n 0 1 0\n"
                                            "p 1 2 3\n"
                                            "o 1 1 0\n"
                                            "O 0 3 0\n"
                                            "f 0 0 0\n"
                                            "p -4 5e1 6\n"
                                            "q 0 0 0\n"
                                            "no longer a3d\n");
  const std::vector<float> expected = {0.5f, 0.25f, 0.125f, 1, 2, 3, -4, 50, 6};
  EXPECT_EQ(coordinates(expectSamples(file, 3)), expected);
  // The third line was where the reader used to stop ("'d' is not a number").
  EXPECT_EQ(
      coordinates(expectSamples(write("d.pts", "# a\n# b\nd 0 0 0\np 1 2 3\n"), 1)),
      (std::vector<float>{1, 2, 3}));
}

TEST_F(PointIo, MalformedA3dStream)
{
  const std::string polygon = expectSamplesFailure(
      write("polygon.pts", "p 1 2 3\nP 0 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nE 0 0 0\n"));
  EXPECT_NE(polygon.find("line 2"), std::string::npos) << polygon;
  EXPECT_NE(polygon.find("polygon"), std::string::npos) << polygon;
  const std::string short_state =
      expectSamplesFailure(write("short.pts", "d 0 0\np 1 2 3\n"));
  EXPECT_NE(short_state.find("line 1"), std::string::npos) << short_state;
  const std::string word =
      expectSamplesFailure(write("word.pts", "n 0 x 1\np 1 2 3\n"));
  EXPECT_NE(word.find("'x'"), std::string::npos) << word;
  const std::string none =
      expectSamplesFailure(write("none.pts", "d 1 1 1\nq 0 0 0\n"));
  EXPECT_NE(none.find("no points"), std::string::npos) << none;
}

// ---------------------------------------------------------------------------------
// OBJ

TEST_F(PointIo, ObjVerticesAndFaces)
{
  const std::string file = write("mesh.obj", "# exported\n"
                                             "mtllib mesh.mtl\n"
                                             "o thing\n"
                                             "v 0 0 0\n"
                                             "v 1 0 0 1.0\n"
                                             "vt 0.5 0.5\n"
                                             "vn 0 0 1\n"
                                             "v 1 1 0 0.1 0.2 0.3\n"
                                             "v 0 1 0\n"
                                             "g part\n"
                                             "usemtl red\n"
                                             "s off\n"
                                             "f 1 2 3\n"
                                             "f 1/1 3/1 4/1\n"
                                             "f 1//1 2//1 3//1 4//1\n"
                                             "f -4/1/1 -3/1/1 -1/1/1\n"
                                             "l 1 2\n"
                                             "v 5 5 5\n"
                                             "f -1 1 2\n");
  const std::vector<float> expected = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5};
  EXPECT_EQ(coordinates(expectSamples(file, 5)), expected);
  const std::vector<pcl::Vertices> faces = expectFaces(file, 5);
  ASSERT_EQ(faces.size(), 5u);
  EXPECT_EQ(corners(faces[0]), (std::vector<pcl::index_t>{0, 1, 2}));
  EXPECT_EQ(corners(faces[1]), (std::vector<pcl::index_t>{0, 2, 3}));
  EXPECT_EQ(corners(faces[2]), (std::vector<pcl::index_t>{0, 1, 2, 3})); // quad kept
  EXPECT_EQ(corners(faces[3]), (std::vector<pcl::index_t>{0, 1, 3}));
  EXPECT_EQ(corners(faces[4]), (std::vector<pcl::index_t>{4, 0, 1}));
}

TEST_F(PointIo, ObjWithoutFaces)
{
  const std::string file = write("cloud.obj", "v 1 2 3\nv 4 5 6\n");
  expectSamples(file, 2);
  expectFaces(file, 0);
}

// ---------------------------------------------------------------------------------
// OFF

TEST_F(PointIo, OffVerticesAndFaces)
{
  const std::string file = write("mesh.off", "OFF\n"
                                             "# a comment line\n"
                                             "\n"
                                             "5 3 0\n"
                                             "0 0 0\n"
                                             "1 0 0 # trailing comment\n"
                                             "1 1 0\n"
                                             "0 1 0\n"
                                             "0.5 0.5 1\n"
                                             "3 0 1 2\n"
                                             "4 0 1 2 3 255 0 0\n"
                                             "3 3 2 4\n");
  const std::vector<float> expected = {0, 0, 0, 1, 0,    0,    1, 1,
                                       0, 0, 1, 0, 0.5f, 0.5f, 1};
  EXPECT_EQ(coordinates(expectSamples(file, 5)), expected);
  const std::vector<pcl::Vertices> faces = expectFaces(file, 3);
  ASSERT_EQ(faces.size(), 3u);
  EXPECT_EQ(corners(faces[0]), (std::vector<pcl::index_t>{0, 1, 2}));
  EXPECT_EQ(corners(faces[1]), (std::vector<pcl::index_t>{0, 1, 2, 3}));
  EXPECT_EQ(corners(faces[2]), (std::vector<pcl::index_t>{3, 2, 4}));
}

TEST_F(PointIo, OffVariants)
{
  // Colours and normals after x y z; counts on the header line; no header at all.
  const std::string coff = write("c.off", "COFF\n3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 "
                                          "0 255\n0 1 0 0 0 255 255\n3 0 1 2\n");
  EXPECT_EQ(coordinates(expectSamples(coff, 3)),
            (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  expectFaces(coff, 1);
  const std::string noff = write("n.off", "NOFF 2 0 0\n1 2 3 0 0 1\n4 5 6 0 1 0\n");
  EXPECT_EQ(coordinates(expectSamples(noff, 2)),
            (std::vector<float>{1, 2, 3, 4, 5, 6}));
  expectFaces(noff, 0);
  const std::string bare = write("bare.off", "2 0 0\n1 2 3\n4 5 6\n");
  expectSamples(bare, 2);
}

// ---------------------------------------------------------------------------------
// PLY

TEST_F(PointIo, PlyAsciiPropertiesBecomeTypedFields)
{
  const std::string text = "ply\r\n"
                           "format ascii 1.0\r\n"
                           "comment made by hand\r\n"
                           "obj_info anything\r\n"
                           "element vertex 3\r\n"
                           "property double x\r\n"
                           "property double y\r\n"
                           "property double z\r\n"
                           "property uchar red\r\n"
                           "property int label\r\n"
                           "property float confidence\r\n"
                           "element face 2\r\n"
                           "property list uchar int vertex_indices\r\n"
                           "element range_grid 2\r\n"
                           "property list uchar int vertex_indices\r\n"
                           "end_header\r\n"
                           "0.5 1.5 2.5 255 -7 0.25\r\n"
                           "3 4 5 0 100000 1\r\n"
                           "6 7 8 17 0 nan\r\n"
                           "3 0 1 2\r\n"
                           "4 2 1 0 1\r\n"
                           "1 0\r\n"
                           "0\r\n";
  const std::string file = write("typed.ply", text);
  const pcl::PCLPointCloud2 cloud = expectSamples(file, 3);
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_EQ(coordinates(cloud),
            (std::vector<float>{0.5f, 1.5f, 2.5f, 3, 4, 5, 6, 7, 8}));
  ASSERT_EQ(cloud.fields.size(), 6u);
  EXPECT_EQ(cloud.fields[3].name, "red");
  EXPECT_EQ(cloud.fields[3].datatype, PCLPointField::UINT8);
  EXPECT_EQ(cloud.fields[4].name, "label");
  EXPECT_EQ(cloud.fields[4].datatype, PCLPointField::INT32);
  EXPECT_EQ(cloud.fields[5].name, "confidence");
  EXPECT_EQ(cloud.fields[5].datatype, PCLPointField::FLOAT32);
  for (const PCLPointField& field : cloud.fields)
    EXPECT_EQ(field.offset % pcl::getFieldSize(field.datatype), 0u) << field.name;
  EXPECT_EQ(valueAt<std::uint8_t>(cloud, 0, "red"), 255);
  EXPECT_EQ(valueAt<std::uint8_t>(cloud, 2, "red"), 17);
  EXPECT_EQ(valueAt<std::int32_t>(cloud, 0, "label"), -7);
  EXPECT_EQ(valueAt<std::int32_t>(cloud, 1, "label"), 100000);
  EXPECT_EQ(valueAt<float>(cloud, 0, "confidence"), 0.25f);
  // NaN outside x, y, z does not make the cloud sparse.
  EXPECT_TRUE(std::isnan(valueAt<float>(cloud, 2, "confidence")));
  EXPECT_TRUE(cloud.is_dense);

  const std::vector<pcl::Vertices> faces = expectFaces(file, 2);
  ASSERT_EQ(faces.size(), 2u);
  EXPECT_EQ(corners(faces[0]), (std::vector<pcl::index_t>{0, 1, 2}));
  EXPECT_EQ(corners(faces[1]), (std::vector<pcl::index_t>{2, 1, 0, 1}));
}

TEST_F(PointIo, PlyAsciiNonFiniteCoordinates)
{
  const std::string file = write("nan.ply", "ply\nformat ascii 1.0\nelement vertex 2\n"
                                            "property float x\nproperty float y\n"
                                            "property float z\nend_header\n"
                                            "1 2 3\nnan 0 0\n");
  const pcl::PCLPointCloud2 cloud = expectSamples(file, 2);
  EXPECT_FALSE(cloud.is_dense);
  expectFaces(file, 0);
}

/** A binary PLY with a list-carrying element before the vertices, double coordinates,
 * an extra ushort property, then faces with ushort counts and uint indices plus a
 * per-face flag. */
std::string
binaryPly(bool big_endian)
{
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\n"
                     "comment leading element to be skipped\n"
                     "element camera 2\n"
                     "property float view\n"
                     "property list uchar short stuff\n"
                     "element vertex 4\n"
                     "property double x\n"
                     "property double y\n"
                     "property double z\n"
                     "property ushort tag\n"
                     "property float nx\n"
                     "element face 2\n"
                     "property uchar flag\n"
                     "property list ushort uint vertex_index\n"
                     "end_header\n";
  // camera: 2 instances with 1 and 0 list entries
  append<float>(text, 1.0f, big_endian);
  append<std::uint8_t>(text, 1, big_endian);
  append<std::int16_t>(text, -3, big_endian);
  append<float>(text, 2.0f, big_endian);
  append<std::uint8_t>(text, 0, big_endian);
  for (int i = 0; i < 4; ++i) {
    append<double>(text, i + 0.5, big_endian);
    append<double>(text, -i, big_endian);
    append<double>(text, 1e3 * i, big_endian);
    append<std::uint16_t>(text, static_cast<std::uint16_t>(1000 + i), big_endian);
    append<float>(text, 0.25f * i, big_endian);
  }
  append<std::uint8_t>(text, 9, big_endian);
  append<std::uint16_t>(text, 3, big_endian);
  for (std::uint32_t v : {0u, 1u, 2u})
    append<std::uint32_t>(text, v, big_endian);
  append<std::uint8_t>(text, 9, big_endian);
  append<std::uint16_t>(text, 4, big_endian);
  for (std::uint32_t v : {3u, 2u, 1u, 0u})
    append<std::uint32_t>(text, v, big_endian);
  return text;
}

TEST_F(PointIo, PlyBinaryBothByteOrders)
{
  for (const bool big_endian : {false, true}) {
    SCOPED_TRACE(big_endian ? "big endian" : "little endian");
    const std::string file =
        write(big_endian ? "be.ply" : "le.ply", binaryPly(big_endian));
    const pcl::PCLPointCloud2 cloud = expectSamples(file, 4);
    EXPECT_TRUE(cloud.is_dense);
    EXPECT_EQ(coordinates(cloud), (std::vector<float>{0.5f, 0, 0, 1.5f, -1, 1e3f, 2.5f,
                                                      -2, 2e3f, 3.5f, -3, 3e3f}));
    ASSERT_EQ(cloud.fields.size(), 5u);
    EXPECT_EQ(cloud.fields[3].name, "tag");
    EXPECT_EQ(cloud.fields[3].datatype, PCLPointField::UINT16);
    EXPECT_EQ(cloud.fields[4].name, "nx");
    EXPECT_EQ(valueAt<std::uint16_t>(cloud, 3, "tag"), 1003);
    EXPECT_EQ(valueAt<float>(cloud, 2, "nx"), 0.5f);
    const std::vector<pcl::Vertices> faces = expectFaces(file, 2);
    ASSERT_EQ(faces.size(), 2u);
    EXPECT_EQ(corners(faces[0]), (std::vector<pcl::index_t>{0, 1, 2}));
    EXPECT_EQ(corners(faces[1]), (std::vector<pcl::index_t>{3, 2, 1, 0}));
  }
}

/** Vertices stored in the fields' own types: float x y z, then a uchar, a ushort, a
 * float and a double, which the cloud aligns with gaps between them. */
std::string
fieldTypedPly(bool big_endian, std::size_t vertices_written)
{
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                     "property float z\nproperty uchar red\nproperty ushort tag\n"
                     "property float nx\nproperty double weight\nend_header\n";
  for (std::size_t i = 0; i < vertices_written; ++i) {
    const auto f = static_cast<float>(i);
    append<float>(text, f + 0.5f, big_endian);
    append<float>(text, -f, big_endian);
    append<float>(text, 1e3f * f, big_endian);
    append<std::uint8_t>(text, static_cast<std::uint8_t>(200 + i), big_endian);
    append<std::uint16_t>(text, static_cast<std::uint16_t>(60000 + i), big_endian);
    append<float>(text, f / 4, big_endian);
    append<double>(text, 1.0 / (1.0 + f), big_endian);
  }
  return text;
}

TEST_F(PointIo, PlyVerticesInTheFieldsOwnTypesReadAlikeInBothByteOrders)
{
  // In the host's byte order such vertices are copied by the reader's plan, in the
  // other one value by value: both must give the same cloud, byte for byte.
  const pcl::PCLPointCloud2 little =
      expectSamples(write("little.ply", fieldTypedPly(false, 5)), 5);
  const pcl::PCLPointCloud2 big =
      expectSamples(write("big.ply", fieldTypedPly(true, 5)), 5);
  EXPECT_EQ(little.data, big.data);
  ASSERT_EQ(little.fields.size(), big.fields.size());
  for (std::size_t f = 0; f < little.fields.size(); ++f) {
    EXPECT_EQ(little.fields[f].name, big.fields[f].name);
    EXPECT_EQ(little.fields[f].offset, big.fields[f].offset);
  }
  EXPECT_EQ(coordinates(little),
            (std::vector<float>{0.5f, 0, 0, 1.5f, -1, 1e3f, 2.5f, -2, 2e3f, 3.5f, -3,
                                3e3f, 4.5f, -4, 4e3f}));
  EXPECT_EQ(valueAt<std::uint8_t>(little, 4, "red"), 204);
  EXPECT_EQ(valueAt<std::uint16_t>(little, 3, "tag"), 60003);
  EXPECT_EQ(valueAt<float>(little, 2, "nx"), 0.5f);
  EXPECT_EQ(valueAt<double>(little, 1, "weight"), 0.5);
  // Ending within the vertices, either way, is refused.
  for (const bool big_endian : {false, true}) {
    const std::string error = expectSamplesFailure(
        write("cut.ply", fieldTypedPly(big_endian, 5)
                             .substr(0, fieldTypedPly(big_endian, 3).size() + 7)));
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  }
}

TEST_F(PointIo, PlyWithoutFaceElementHasNoFaces)
{
  const std::string file =
      write("points.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                          "property float x\nproperty float y\n"
                          "property float z\nend_header\n1 2 3\n");
  expectSamples(file, 1);
  expectFaces(file, 0);
}

// ---------------------------------------------------------------------------------
// PCD

TEST_F(PointIo, PcdAllEncodingsKeepFieldsAndOrganization)
{
  pcl::PointCloud<pcl::PointXYZI> points(3, 2); // organized: 3 wide, 2 high
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].x = static_cast<float>(i);
    points[i].y = 2.0f * i;
    points[i].z = -1.0f * i;
    points[i].intensity = 10.0f + i;
  }
  points[4].x = points[4].y = points[4].z = std::numeric_limits<float>::quiet_NaN();
  points.is_dense = false;
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(points, blob);
  pcl::PCDWriter writer;
  const std::string ascii = path("ascii.pcd");
  const std::string binary = path("binary.pcd");
  const std::string compressed = path("compressed.Pcd");
  ASSERT_EQ(writer.writeASCII(ascii, blob), 0);
  ASSERT_EQ(writer.writeBinary(binary, blob), 0);
  ASSERT_EQ(writer.writeBinaryCompressed(compressed, blob), 0);
  for (const std::string& file : {ascii, binary, compressed}) {
    SCOPED_TRACE(file);
    const pcl::PCLPointCloud2 cloud = expectSamples(file, 6);
    EXPECT_EQ(cloud.width, 3u);
    EXPECT_EQ(cloud.height, 2u);
    EXPECT_FALSE(cloud.is_dense);
    ASSERT_NE(findField(cloud, "intensity"), nullptr);
    const std::vector<float> xyz = coordinates(cloud);
    ASSERT_EQ(xyz.size(), 18u);
    EXPECT_EQ(xyz[3 * 5 + 1], 10.0f);
    EXPECT_TRUE(std::isnan(xyz[3 * 4]));
    EXPECT_EQ(valueAt<float>(cloud, 5, "intensity"), 15.0f);
  }
  expectFacesFailure(ascii); // not a mesh format
}

TEST_F(PointIo, PcdDoubleCoordinatesBecomeFloat)
{
  const std::string file = write("double.pcd", "# .PCD v0.7\n"
                                               "VERSION 0.7\n"
                                               "FIELDS x y z label\n"
                                               "SIZE 8 8 8 4\n"
                                               "TYPE F F F U\n"
                                               "COUNT 1 1 1 1\n"
                                               "WIDTH 2\n"
                                               "HEIGHT 1\n"
                                               "VIEWPOINT 0 0 0 1 0 0 0\n"
                                               "POINTS 2\n"
                                               "DATA ascii\n"
                                               "1.5 2.5 3.5 7\n"
                                               "4 5 6 8\n");
  const pcl::PCLPointCloud2 cloud = expectSamples(file, 2);
  EXPECT_EQ(coordinates(cloud), (std::vector<float>{1.5f, 2.5f, 3.5f, 4, 5, 6}));
  ASSERT_NE(findField(cloud, "label"), nullptr);
  EXPECT_EQ(findField(cloud, "label")->datatype, PCLPointField::UINT32);
  EXPECT_EQ(valueAt<std::uint32_t>(cloud, 1, "label"), 8u);
  EXPECT_TRUE(cloud.is_dense);
}

// ---------------------------------------------------------------------------------
// Failures: false, an empty cloud, one line naming the file, nothing on stderr.

TEST_F(PointIo, MissingDirectoryAndUnknownFiles)
{
  EXPECT_NE(expectSamplesFailure(path("missing.xyz")).find("no such file"),
            std::string::npos);
  fs::create_directory(path("folder.ply"));
  EXPECT_NE(expectSamplesFailure(path("folder.ply")).find("directory"),
            std::string::npos);
  EXPECT_NE(expectSamplesFailure(write("model.stl", "solid x\n")).find("extension"),
            std::string::npos);
  expectSamplesFailure(write("noextension", "1 2 3\n"));
  expectFacesFailure(path("missing.off"));
  expectFacesFailure(path("folder.ply"));
  expectFacesFailure(write("points.xyz", "1 2 3\n"));
}

TEST_F(PointIo, UnreadableFile)
{
  const std::string file = write("locked.xyz", "1 2 3\n");
  fs::permissions(file, fs::perms::none);
  if (std::FILE* probe = std::fopen(file.c_str(), "rb")) {
    std::fclose(probe);
    GTEST_SKIP() << "running with rights that read any file (root?)";
  }
  EXPECT_NE(expectSamplesFailure(file).find("cannot open"), std::string::npos);
}

TEST_F(PointIo, MalformedColumns)
{
  const std::string short_line =
      expectSamplesFailure(write("short.xyz", "1 2 3\n4 5 6\n7 8\n9 10 11\n"));
  EXPECT_NE(short_line.find("line 3"), std::string::npos) << short_line;
  EXPECT_NE(short_line.find("expected 3 coordinates"), std::string::npos) << short_line;
  const std::string word = expectSamplesFailure(write("word.xyz", "1 2 3\n4 five 6\n"));
  EXPECT_NE(word.find("line 2"), std::string::npos) << word;
  EXPECT_NE(word.find("'five'"), std::string::npos) << word;
  expectSamplesFailure(write("comma.txt", "1,5 2 3\n"));
  expectSamplesFailure(write("glued.xyz", "1 2 3abc\n"));
  expectSamplesFailure(write("count_header.xyz", "2\n1 2 3\n4 5 6\n"));
  expectSamplesFailure(write("hoppe.pts", "p 1 2\n"));
  expectSamplesFailure(write("binary.xyz", std::string("\x01\x02\x00\xff\n", 5)));
  const std::string empty = expectSamplesFailure(write("empty.xyz", ""));
  EXPECT_NE(empty.find("no points"), std::string::npos) << empty;
  expectSamplesFailure(write("comments.pts", "# nothing\n\n# here\n"));
}

TEST_F(PointIo, MalformedObjAndOff)
{
  expectSamplesFailure(write("nothing.obj", "# only a comment\nf 1 2 3\n"));
  expectSamplesFailure(write("short.obj", "v 1 2\n"));
  expectSamplesFailure(write("word.obj", "v 1 2 x\n"));
  expectSamplesFailure(write("empty.off", ""));
  expectSamplesFailure(write("header.off", "OFX\n1 0 0\n1 2 3\n"));
  expectSamplesFailure(write("four.off", "4OFF\n1 0 0\n1 2 3 4\n"));
  expectSamplesFailure(write("nocounts.off", "OFF\n"));
  expectSamplesFailure(write("zero.off", "OFF\n0 0 0\n"));
  const std::string truncated =
      expectSamplesFailure(write("truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"));
  EXPECT_NE(truncated.find("2 of 3"), std::string::npos) << truncated;
  const std::string word =
      expectSamplesFailure(write("word.off", "OFF\n2 0 0\n0 0 0\n1 zero 0\n"));
  EXPECT_NE(word.find("line 4"), std::string::npos) << word;
}

TEST_F(PointIo, MalformedPly)
{
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\n"
                             "property float x\nproperty float y\nproperty float z\n";
  expectSamplesFailure(write("magic.ply", "plx\n" + header.substr(4) + "end_header\n"));
  expectSamplesFailure(write("noend.ply", header));
  expectSamplesFailure(write("empty.ply", ""));
  const std::string truncated_file =
      write("truncated.ply", header + "end_header\n1 2 3\n");
  const std::string truncated = expectSamplesFailure(truncated_file);
  EXPECT_NE(truncated.find("1 of 3"), std::string::npos) << truncated;
  // No face element, but the faces reader does not call a broken file a mesh either.
  expectFacesFailure(truncated_file);
  const std::string few = expectSamplesFailure(
      write("few.ply", header + "end_header\n1 2 3\n4 5\n7 8 9\n"));
  EXPECT_NE(few.find("line 9"), std::string::npos) << few;
  expectSamplesFailure(
      write("many.ply", header + "end_header\n1 2 3\n4 5 6 7\n7 8 9\n"));
  expectSamplesFailure(write("word.ply", header + "end_header\n1 2 3\n4 x 6\n7 8 9\n"));
  expectSamplesFailure(write("noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                        "property float x\nproperty float y\n"
                                        "end_header\n1 2\n"));
  expectSamplesFailure(write("novertex.ply", "ply\nformat ascii 1.0\nend_header\n"));
  expectSamplesFailure(write("zero.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"
                                         "property float x\nproperty float y\n"
                                         "property float z\nend_header\n"));
  expectSamplesFailure(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                         "property quad x\nend_header\n1\n"));
  expectSamplesFailure(write("format.ply", "ply\nformat binary_middle_endian 1.0\n"
                                           "end_header\n"));
  expectSamplesFailure(write("range.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                          "property float x\nproperty float y\n"
                                          "property float z\nproperty uchar red\n"
                                          "end_header\n1 2 3 256\n"));
  // A header that promises far more than the file holds must not allocate it.
  expectSamplesFailure(write("huge.ply", "ply\nformat binary_little_endian 1.0\n"
                                         "element vertex 2000000000\n"
                                         "property float x\nproperty float y\n"
                                         "property float z\nend_header\n"));
  expectSamplesFailure(write("huge_ascii.ply", "ply\nformat ascii 1.0\n"
                                               "element vertex 2000000000\n"
                                               "property float x\nproperty float y\n"
                                               "property float z\nend_header\n"
                                               "1 2 3\n"));

  std::string binary = binaryPly(false);
  const std::string cut = expectSamplesFailure(
      write("cut.ply", binary.substr(0, binary.find("end_header\n") + 11 + 13 + 40)));
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
  // Cut inside the faces: the samples are fine, the faces are not.
  const std::string faces_cut =
      write("faces_cut.ply", binary.substr(0, binary.size() - 3));
  expectSamples(faces_cut, 4);
  expectFacesFailure(faces_cut);
}

TEST_F(PointIo, MalformedPcd)
{
  const std::string header = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                             "COUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                             "POINTS 3\n";
  // PCL's own reader crashes on the first two and prints (or misreads) on the others.
  expectSamplesFailure(write("empty.pcd", ""));
  expectSamplesFailure(write("garbage.pcd", "hello world\n"));
  expectSamplesFailure(write("short.pcd", header + "DATA ascii\n1 2 3\n4 5 6\n"));
  expectSamplesFailure(write("few.pcd", header + "DATA ascii\n1 2 3\n4 5\n7 8 9\n"));
  expectSamplesFailure(write("word.pcd", header + "DATA ascii\n1 2 3\n4 x 6\n7 8 9\n"));
  expectSamplesFailure(
      write("binary.pcd", header + "DATA binary\n" + std::string(35, 'a')));
  const std::string sizes_16_36("\x10\0\0\0\x24\0\0\0", 8);
  expectSamplesFailure(write("compressed.pcd", header + "DATA binary_compressed\n" +
                                                   sizes_16_36 + "abcdefgh"));
  expectSamplesFailure(write("corrupt.pcd", header + "DATA binary_compressed\n" +
                                                std::string("\x08\0\0\0\x24\0\0\0", 8) +
                                                "\xff\xff\xff\xff\xff\xff\xff\xff"));
  expectSamplesFailure(write("zero.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                         "TYPE F F F\nCOUNT 1 1 1\nWIDTH 0\nHEIGHT 1\n"
                                         "POINTS 0\nDATA ascii\n"));
  expectSamplesFailure(write("noz.pcd", "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\n"
                                        "COUNT 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
                                        "DATA ascii\n1 2\n"));
  expectSamplesFailure(write("size.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 3\n"
                                         "TYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
                                         "DATA ascii\n1 2 3\n"));
  // Headers PCL reads on from with a warning, or misreads: out of order, no HEIGHT,
  // an empty COUNT, a blank line, a second DATA line, a vertical tab in the data.
  expectSamplesFailure(write("order.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                          "TYPE F F F\nPOINTS 1\nCOUNT 1 1 1\nWIDTH 1\n"
                                          "HEIGHT 1\nDATA ascii\n1 2 3\n"));
  expectSamplesFailure(write("noheight.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                             "TYPE F F F\nWIDTH 1\nPOINTS 1\n"
                                             "DATA ascii\n1 2 3\n"));
  expectSamplesFailure(write("count.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                          "TYPE F F F\nCOUNT\nWIDTH 1\nHEIGHT 1\n"
                                          "POINTS 1\nDATA ascii\n1 2 3\n"));
  expectSamplesFailure(write("blank.pcd", "VERSION 0.7\nFIELDS x y z\n \nSIZE 4 4 4\n"
                                          "TYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
                                          "DATA ascii\n1 2 3\n"));
  expectSamplesFailure(write("twice.pcd", header + "DATA binary\nDATA binary\n" +
                                              std::string(36, '\0')));
  expectSamplesFailure(
      write("vtab.pcd", header + "DATA ascii\n1 2 3\n4\v5 6\n7 8 9\n"));
  expectSamplesFailure(write("mismatch.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                             "TYPE F F F\nWIDTH 2\nHEIGHT 2\nPOINTS 3\n"
                                             "DATA ascii\n1 2 3\n1 2 3\n1 2 3\n"));
}

TEST_F(PointIo, FaceIndicesOutOfRange)
{
  const std::string ply = write("range.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"
                                             "property float x\nproperty float y\n"
                                             "property float z\nelement face 1\n"
                                             "property list uchar int vertex_indices\n"
                                             "end_header\n0 0 0\n1 0 0\n0 1 0\n"
                                             "3 0 1 3\n");
  expectSamples(ply, 3); // the vertices themselves are fine
  const std::string ply_error = expectFacesFailure(ply);
  EXPECT_NE(ply_error.find("out of range"), std::string::npos) << ply_error;
  EXPECT_NE(ply_error.find("line 13"), std::string::npos) << ply_error;
  expectFacesFailure(write("negative.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"
                                           "property float x\nproperty float y\n"
                                           "property float z\nelement face 1\n"
                                           "property list uchar int vertex_indices\n"
                                           "end_header\n0 0 0\n1 0 0\n0 1 0\n"
                                           "3 0 1 -1\n"));
  expectFacesFailure(write("nolist.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"
                                         "property float x\nproperty float y\n"
                                         "property float z\nelement face 1\n"
                                         "property list uchar int corners\n"
                                         "end_header\n0 0 0\n1 0 0\n0 1 0\n"
                                         "3 0 1 2\n"));

  std::string binary = binaryPly(true);
  binary[binary.size() - 1] = 9; // last index of the last face: 9 of 4 vertices
  expectFacesFailure(write("range_binary.ply", binary));

  const std::string obj_error =
      expectFacesFailure(write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"));
  EXPECT_NE(obj_error.find("line 4"), std::string::npos) << obj_error;
  expectFacesFailure(write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"));
  expectFacesFailure(write("behind.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"));
  expectFacesFailure(write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"));
  expectFacesFailure(write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"));
  expectFacesFailure(write("short.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  expectFacesFailure(write("count.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"));
}

// ---------------------------------------------------------------------------------
// Sizes, counts and offsets from a file are bounded before anything is allocated.

/** Runs loadPointSamples (loadMeshFaces when \a faces is set) on \a path in a child
 * process whose address space may grow by \a megabytes only, so that a reader
 * allocating what a header claims fails the test instead of the machine; the child
 * reports through its exit code whether the reader refused the file with a reason. */
void
expectFailureWithin(const std::string& path, std::size_t megabytes, bool faces = false)
{
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // On top of what the process has mapped already (its libraries, the test's heap).
    std::size_t mapped_pages = 0;
    if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(statm, "%zu", &mapped_pages) != 1)
        mapped_pages = 0;
      std::fclose(statm);
    }
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const rlim_t bytes = mapped_pages * page + (megabytes << 20);
    const rlimit limit{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &limit);
    pcl::PCLPointCloud2 cloud;
    std::vector<pcl::Vertices> polygons;
    std::string error;
    const bool read = faces ? pcl::cocone::loadMeshFaces(path, polygons, &error)
                            : pcl::cocone::loadPointSamples(path, cloud, &error);
    const bool refused =
        !read && !error.empty() && error.find("out of memory") == std::string::npos;
    ::_exit(refused ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << path << ": not refused within " << megabytes << " MB (status " << status
      << ")";
}

TEST_F(PointIo, PcdCountOverflowIsRefused)
{
  // SIZE x COUNT wraps around 2^64: a division by zero (SIGFPE) in the check, and a
  // COUNT that wraps to a small point step reaches PCL, which crashes in
  // readBodyBinary.
  const std::string header = "VERSION 0.7\nFIELDS x y z w\nSIZE 4 4 4 4\nTYPE F F F F\n"
                             "COUNT 1 1 1 4611686018427387901\nWIDTH 10\nHEIGHT 1\n"
                             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n";
  const std::string file = write("count.pcd", header + std::string(400, '\0'));
  const std::string error = expectSamplesFailure(file);
  EXPECT_NE(error.find("'w' has an invalid SIZE, TYPE or COUNT"), std::string::npos)
      << error;
  // 4 * 4611686018427387904 wraps to 0, so the point step would be 12.
  std::string wrapped = header;
  wrapped.replace(wrapped.find("4611686018427387901"), 19, "4611686018427387904");
  expectSamplesFailure(write("wrapped.pcd", wrapped + std::string(400, '\0')));
  // The largest COUNT a 32-bit int holds is fine by itself, but not the point it makes.
  std::string large = header;
  large.replace(large.find("4611686018427387901"), 19, "2147483647");
  const std::string large_error =
      expectSamplesFailure(write("large.pcd", large + std::string(400, '\0')));
  EXPECT_NE(large_error.find("too large"), std::string::npos) << large_error;
}

TEST_F(PointIo, PcdSizeBeyondIntIsRefused)
{
  // An int cast made 4294967300 a 4: the check passed and PCL allocated gigabytes.
  const std::string file =
      write("size.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4294967300\n"
                        "TYPE F F F\nCOUNT 1 1 1\nWIDTH 10\nHEIGHT 1\n"
                        "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 10\nDATA binary\n" +
                            std::string(150, '\0'));
  const std::string error = expectSamplesFailure(file);
  EXPECT_NE(error.find("'z' has an invalid SIZE"), std::string::npos) << error;
  expectFailureWithin(file, 256);
  for (const char* size : {"3", "16", "0", "-4", "4.0"})
    expectSamplesFailure(write(std::string("size_") + size + ".pcd",
                               std::string("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 ") +
                                   size +
                                   "\nTYPE F F F\nWIDTH 1\nHEIGHT 1\n"
                                   "POINTS 1\nDATA ascii\n1 2 3\n"));
}

TEST_F(PointIo, HeadersClaimingMoreThanTheFileHoldsAllocateNothing)
{
  const std::string pcd = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                          "COUNT 1 1 1\nWIDTH 300000000\nHEIGHT 1\n"
                          "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 300000000\n";
  // 3.6 GB of binary data in 120 bytes.
  expectFailureWithin(
      write("binary.pcd", pcd + "DATA binary\n" + std::string(120, 'a')), 256);
  // A compressed block that claims to unpack to 3.6 GB from 16 bytes: LZF cannot grow
  // anything more than 88 times.
  std::string sizes(8, '\0');
  const std::uint32_t claimed[2] = {16, 3600000000u};
  std::memcpy(&sizes[0], claimed, sizeof claimed);
  const std::string lying = write("lying.pcd", pcd + "DATA binary_compressed\n" +
                                                   sizes + std::string(16, 'a'));
  EXPECT_NE(expectSamplesFailure(lying).find("too short"), std::string::npos);
  expectFailureWithin(lying, 256);
  // More than the 4 GiB a cloud can describe.
  std::string huge = pcd;
  huge.replace(huge.find("SIZE 4 4 4"), 10, "SIZE 8 8 8");
  huge.replace(huge.find("TYPE F F F"), 10, "TYPE F F F");
  const std::string beyond = expectSamplesFailure(
      write("beyond.pcd", huge + "DATA binary\n" + std::string(120, 'a')));
  EXPECT_NE(beyond.find("4 GiB"), std::string::npos) << beyond;

  expectFailureWithin(write("vertices.ply", "ply\nformat ascii 1.0\n"
                                            "element vertex 2000000000\n"
                                            "property double x\nproperty double y\n"
                                            "property double z\nend_header\n1 2 3\n"),
                      256);
  expectFailureWithin(write("vertices.off", "OFF\n2000000000 1 0\n0 0 0\n"), 256);
  expectFailureWithin(write("faces.off", "OFF\n3 2000000000 0\n0 0 0\n1 0 0\n0 1 0\n"
                                         "4000000000 0 1 2\n"),
                      256, true);
}

TEST_F(PointIo, MalformedCountsAreErrors)
{
  const std::string points = "0 0 0\n1 0 0\n0 1 0\n";
  expectSamplesFailure(write("edges.off", "OFF\n3 1 x\n" + points + "3 0 1 2\n"));
  expectSamplesFailure(write("extra.off", "OFF\n3 1 0 7\n" + points + "3 0 1 2\n"));
  expectSamplesFailure(write("inline.off", "OFF 3 1 0 0\n" + points + "3 0 1 2\n"));
  expectSamples(write("noedges.off", "OFF\n3 1\n" + points + "3 0 1 2\n"), 3);
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3 4\n"
                          "property float x\nproperty float y\nproperty float z\n"
                          "end_header\n";
  expectSamplesFailure(write("element.ply", ply + points));
  const std::string pcd_fields = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                 "COUNT 1 1 1\n";
  expectSamplesFailure(write("width.pcd", pcd_fields +
                                              "WIDTH 3 3\nHEIGHT 1\n"
                                              "POINTS 3\nDATA ascii\n" +
                                              points));
  expectSamplesFailure(write("points.pcd", pcd_fields +
                                               "WIDTH 3\nHEIGHT 1\n"
                                               "POINTS 3 x\nDATA ascii\n" +
                                               points));
  expectSamplesFailure(write("data.pcd", pcd_fields +
                                             "WIDTH 3\nHEIGHT 1\n"
                                             "POINTS 3\nDATA ascii binary\n" +
                                             points));
  expectSamplesFailure(write("count.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
                                          "TYPE F F F\nCOUNT 1 1 1.5\nWIDTH 1\n"
                                          "HEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n"));
}

TEST_F(PointIo, AsciiPlyWithMoreLinesThanDeclared)
{
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\n"
                             "property float x\nproperty float y\nproperty float z\n";
  const std::string extra = expectSamplesFailure(
      write("extra.ply", header + "end_header\n1 2 3\n4 5 6\n7 8 9\n\n"));
  EXPECT_NE(extra.find("line 10"), std::string::npos) << extra;
  EXPECT_NE(extra.find("more 'vertex' lines than the 2"), std::string::npos) << extra;
  expectFacesFailure(write("extra_faces.ply", header + "end_header\n1 2 3\n4 5 6\n"
                                                       "7 8 9\n"));
  // With faces after the vertices, the extra line is one line too many in all.
  const std::string faces = header + "element face 1\n"
                                     "property list uchar int vertex_indices\n"
                                     "end_header\n";
  const std::string mesh_file =
      write("extra_mesh.ply", faces + "1 2 3\n4 5 6\n7 8 9\n3 0 1 1\n");
  expectSamplesFailure(mesh_file);
  expectFacesFailure(mesh_file);
  // Blank lines at the end are not lines of data.
  expectSamples(write("blank.ply", faces + "1 2 3\n4 5 6\n3 0 1 1\n\n  \n"), 2);
}

/** Whether \a text is valid UTF-8 (RFC 3629), checked independently of the library. */
bool
isUtf8(const std::string& text)
{
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = c < 0x80         ? 1
                         : (c >> 5) == 6  ? 2
                         : (c >> 4) == 14 ? 3
                         : (c >> 3) == 30 ? 4
                                          : 0;
    if (length == 0 || i + length > text.size())
      return false;
    std::uint32_t code = length == 1 ? c : c & (0x7f >> length);
    for (std::size_t k = 1; k < length; ++k) {
      const auto b = static_cast<unsigned char>(text[i + k]);
      if ((b & 0xc0) != 0x80)
        return false;
      code = (code << 6) | (b & 0x3f);
    }
    const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < least[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff))
      return false;
    i += length;
  }
  return true;
}

TEST_F(PointIo, MessagesAreUtf8)
{
  const std::string type =
      expectSamplesFailure(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                             "property fl\xff\xfe"
                                             "at x\nend_header\n1\n"));
  EXPECT_TRUE(isUtf8(type)) << type;
  EXPECT_NE(type.find("'fl\\xff\\xfeat'"), std::string::npos) << type;
  // Valid UTF-8 in a file stays as it is; a sequence cut by the excerpt is escaped.
  const std::string word = expectSamplesFailure(write("word.xyz", "1 2 caf\xc3\xa9\n"));
  EXPECT_NE(word.find("'caf\xc3\xa9'"), std::string::npos) << word;
  const std::string cut = expectSamplesFailure(
      write("cut.xyz", "1 2 " + std::string(23, 'a') + "\xe2\x82\xac\n"));
  EXPECT_TRUE(isUtf8(cut)) << cut;
  for (const char* bytes :
       {"\x80", "\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x82", "\xff"}) {
    const std::string error =
        expectSamplesFailure(write("bytes.obj", std::string("v 1 2 ") + bytes + "\n"));
    EXPECT_TRUE(isUtf8(error)) << error;
  }
  // A file name that is not UTF-8 is escaped too.
  std::string name;
  pcl::PCLPointCloud2 cloud;
  EXPECT_FALSE(
      pcl::cocone::loadPointSamples(write("n\xe9.xyz", "1 2\n"), cloud, &name));
  EXPECT_TRUE(isUtf8(name)) << name;
  EXPECT_NE(name.find("n\\xe9.xyz"), std::string::npos) << name;

  EXPECT_EQ(pcl::cocone::utf8Escaped("plain \xe2\x82\xac \xf0\x9f\x98\x80"),
            "plain \xe2\x82\xac \xf0\x9f\x98\x80");
  EXPECT_EQ(pcl::cocone::utf8Escaped("\xc0\xaf|\xed\xa0\x80|\xf4\x90\x80\x80|\xe2\x82"),
            "\\xc0\\xaf|\\xed\\xa0\\x80|\\xf4\\x90\\x80\\x80|\\xe2\\x82");
}

// ---------------------------------------------------------------------------------
// The shared data folder (skipped when absent)

struct DataCase
{
  const char* file;
  std::uint32_t width;
  std::uint32_t height;
  long faces; ///< expected face count, -1 for formats without faces
  std::vector<std::string> fields;
};

void
PrintTo(const DataCase& data, std::ostream* out)
{
  *out << data.file;
}

class PointIoData : public ::testing::TestWithParam<DataCase>
{};

TEST_P(PointIoData, LoadsWithExpectedCounts)
{
  const DataCase& data = GetParam();
  PCL_COCONE_REQUIRE_DATA_FILE(file, data.file);
  const pcl::PCLPointCloud2 cloud =
      expectSamples(file, static_cast<std::size_t>(data.width) * data.height);
  EXPECT_EQ(cloud.width, data.width);
  EXPECT_EQ(cloud.height, data.height);
  std::vector<std::string> names;
  for (const PCLPointField& field : cloud.fields)
    names.push_back(field.name);
  EXPECT_EQ(names, data.fields);
  const std::vector<float> xyz = coordinates(cloud);
  const bool finite =
      std::all_of(xyz.begin(), xyz.end(), [](float v) { return std::isfinite(v); });
  EXPECT_EQ(cloud.is_dense, finite);

  if (data.faces < 0) {
    expectFacesFailure(file);
    return;
  }
  const std::vector<pcl::Vertices> faces =
      expectFaces(file, static_cast<std::size_t>(data.faces));
  for (const pcl::Vertices& face : faces) {
    ASSERT_GE(face.vertices.size(), 3u);
    for (const pcl::index_t v : face.vertices)
      ASSERT_TRUE(v >= 0 && static_cast<std::uint32_t>(v) < cloud.width);
  }
}

using Names = std::vector<std::string>;
const Names xyz_names = {"x", "y", "z"};
const Names normal_names = {"x", "y", "z", "nx", "ny", "nz"};

INSTANTIATE_TEST_SUITE_P(
    SharedData, PointIoData,
    ::testing::Values(
        DataCase{"bun_zipper_35947.ply", 35947, 1, 69451,
                 Names{"x", "y", "z", "confidence", "intensity"}},
        DataCase{"bun000_rawscan_40256.ply", 40256, 1, 0, xyz_names},
        DataCase{"armadillo_38294_normals.ply", 38294, 1, 0, normal_names},
        DataCase{"dragon_vrip_res3_22998.ply", 22998, 1, 47794, normal_names},
        DataCase{"gargoyle_95435_normals.ply", 95435, 1, 0, normal_names},
        DataCase{"fandisk_6475.obj", 6475, 1, 12946, xyz_names},
        DataCase{"foot_10010.off", 10010, 1, 20016, xyz_names},
        DataCase{"mannequin_11703.off", 11703, 1, 23402, xyz_names},
        DataCase{"rocker-arm_10044.off", 10044, 1, 20088, xyz_names},
        DataCase{"cactus_3318.pts", 3318, 1, -1, xyz_names},
        DataCase{"knot_1281.pts", 1281, 1, -1, xyz_names},
        DataCase{"3holes_4000_bluenoise.xyz", 4000, 1, -1, xyz_names},
        DataCase{"3holes_4000_whitenoise.xyz", 4000, 1, -1, xyz_names},
        DataCase{"kitten_5210_normals.xyz", 5210, 1, -1, xyz_names},
        DataCase{"pcl_bunny_397.pcd", 397, 1, -1, xyz_names},
        DataCase{"pcl_milk_13704.pcd", 13704, 1, -1, xyz_names},
        DataCase{"pcl_table_scene_mug_stereo_textured_640x480.pcd", 640, 480, -1,
                 Names{"x", "y", "z", "rgba"}},
        DataCase{"pcl_lidar_terrain_samp11-utm_38010.pcd", 38010, 1, -1, xyz_names}),
    [](const ::testing::TestParamInfo<DataCase>& info) {
      std::string name = fs::path(info.param.file).stem().string();
      std::replace_if(
          name.begin(), name.end(),
          [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
      return name;
    });

TEST(PointIoDataDetails, BunnyZipperExtraProperties)
{
  PCL_COCONE_REQUIRE_DATA_FILE(file, "bun_zipper_35947.ply");
  pcl::PCLPointCloud2 cloud;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(file, cloud));
  // First vertex line: -0.0378297 0.12794 0.00447467 0.850855 0.5
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 0, "x"), -0.0378297f);
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 0, "z"), 0.00447467f);
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 0, "confidence"), 0.850855f);
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 0, "intensity"), 0.5f);
}

TEST(PointIoDataDetails, KittenLastLineWithoutNewline)
{
  PCL_COCONE_REQUIRE_DATA_FILE(file, "kitten_5210_normals.xyz");
  pcl::PCLPointCloud2 cloud;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(file, cloud));
  ASSERT_EQ(cloud.width, 5210u);
  // Last line: -0.207238 0.241374 -0.164938 -0.224494 0.265859 -0.937508
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 5209, "x"), -0.207238f);
  EXPECT_FLOAT_EQ(valueAt<float>(cloud, 5209, "z"), -0.164938f);
}

TEST(PointIoDataDetails, TableSceneKeepsNanPoints)
{
  PCL_COCONE_REQUIRE_DATA_FILE(file, "pcl_table_scene_mug_stereo_textured_640x480.pcd");
  pcl::PCLPointCloud2 cloud;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(file, cloud));
  EXPECT_FALSE(cloud.is_dense);
  const std::vector<float> xyz = coordinates(cloud);
  std::size_t finite = 0;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    finite +=
        std::isfinite(xyz[i]) && std::isfinite(xyz[i + 1]) && std::isfinite(xyz[i + 2]);
  EXPECT_EQ(finite, 209280u); // as the data README counts them
}

TEST(PointIoDataDetails, GargoyleBinaryNormalsAreUnit)
{
  PCL_COCONE_REQUIRE_DATA_FILE(file, "gargoyle_95435_normals.ply");
  pcl::PCLPointCloud2 cloud;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(file, cloud));
  for (std::size_t i = 0; i < cloud.width; i += 997) {
    const float nx = valueAt<float>(cloud, i, "nx");
    const float ny = valueAt<float>(cloud, i, "ny");
    const float nz = valueAt<float>(cloud, i, "nz");
    EXPECT_NEAR(nx * nx + ny * ny + nz * nz, 1.0f, 1e-3f) << i;
  }
}

} // namespace
