// SPDX-License-Identifier: GPL-3.0-or-later
//
// Writes the seed corpus of the fuzz targets: a few small, valid files per format that
// between them use every feature the readers know (both PLY byte orders and ascii,
// list properties before the vertices, the three PCD encodings, OBJ's face corner
// forms, OFF's header variants, a3d records, LAS versions and point formats).
// Generated, so that nothing is fetched.
//
//   make_seeds OUT_DIR   writes OUT_DIR/<format>/<name>
#include <pcl/PCLPointCloud2.h>
#include <pcl/cocone/io/writers.h>
#include <pcl/io/pcd_io.h>

#include "../test/support/las_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

fs::path out_dir;

void
put(const std::string& format, const std::string& name, const std::string& contents)
{
  fs::create_directories(out_dir / format);
  std::ofstream(out_dir / format / name, std::ios::binary) << contents;
}

template <typename T>
void
append(std::string& out, T value, bool big_endian)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  char first;
  std::memcpy(&first, &probe, 1);
  if ((first == 0) != big_endian)
    std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string
binaryPly(bool big_endian)
{
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\ncomment seed\nelement camera 1\nproperty float view\n"
                     "property list uchar short stuff\nelement vertex 3\n"
                     "property double x\nproperty double y\nproperty double z\n"
                     "property ushort tag\nelement face 1\nproperty uchar flag\n"
                     "property list ushort uint vertex_index\nend_header\n";
  append<float>(text, 1.0f, big_endian);
  append<std::uint8_t>(text, 1, big_endian);
  append<std::int16_t>(text, -3, big_endian);
  for (int i = 0; i < 3; ++i) {
    append<double>(text, i + 0.5, big_endian);
    append<double>(text, -i, big_endian);
    append<double>(text, 2.0 * i, big_endian);
    append<std::uint16_t>(text, static_cast<std::uint16_t>(7 + i), big_endian);
  }
  append<std::uint8_t>(text, 9, big_endian);
  append<std::uint16_t>(text, 3, big_endian);
  for (std::uint32_t v : {0u, 1u, 2u})
    append<std::uint32_t>(text, v, big_endian);
  return text;
}

pcl::PCLPointCloud2
smallCloud()
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
  cloud.width = 3;
  cloud.height = 2;
  cloud.point_step = 16;
  cloud.row_step = 48;
  cloud.data.resize(6 * 16);
  for (std::size_t i = 0; i < 24; ++i) {
    const float value = i == 16 ? std::numeric_limits<float>::quiet_NaN()
                                : 0.25f * static_cast<float>(i);
    std::memcpy(cloud.data.data() + 4 * i, &value, 4);
  }
  return cloud;
}

} // namespace

int
main(int argc, char** argv)
{
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds OUT_DIR\n");
    return 1;
  }
  out_dir = argv[1];

  put("columns", "plain.xyz", "1 2 3\n4.5 -5e-1 +6E2\n");
  put("columns", "normals.xyz",
      "# x y z nx ny nz\n0 0 0 0 0 1\n1 0 0 0 1 0\r\n"
      "nan inf -inf 1 0 0\n0 1 0 0 0 1");
  put("columns", "a3d.pts",
      "# Created by WA3dStream\nd 0 0 0\ns 0 0 0\ng 1 0 0\n"
      "n 0 0 1\np 0.5 0.25 0.125\no 1 1 0\nf 0 0 0\np 1 2 3\n"
      "q 0 0 0\nrest\n");

  put("obj", "mesh.obj",
      "# seed\nmtllib m.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\n"
      "vt 0.5 0.5\nvn 0 0 1\nv 1 1 0 0.1 0.2 0.3\nv 0 1 0\n"
      "g part\nusemtl red\ns off\nf 1 2 3\nf 1/1 3/1 4/1\n"
      "f 1//1 2//1 3//1 4//1\nf -4/1/1 -3/1/1 -1/1/1\nl 1 2\n"
      "v 5 5 5\nf -1 1 2\n");

  put("off", "mesh.off",
      "OFF\n# comment\n\n4 2 0\n0 0 0\n1 0 0 # trailing\n1 1 0\n"
      "0 1 0\n3 0 1 2\n4 0 1 2 3 255 0 0\n");
  put("off", "coff.off",
      "COFF\n3 1 3\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
      "0 1 0 0 0 255 255\n3 0 1 2\n");
  put("off", "noff.off", "NOFF 2 0 0\n1 2 3 0 0 1\n4 5 6 0 1 0\n");
  put("off", "bare.off", "2 0\n1 2 3\n4 5 6\n");

  put("ply", "ascii.ply",
      "ply\r\nformat ascii 1.0\r\ncomment seed\r\nobj_info x\r\n"
      "element vertex 3\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nproperty uchar red\r\nproperty int label\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\n"
      "element range_grid 2\r\nproperty list uchar int vertex_indices\r\n"
      "end_header\r\n0.5 1.5 2.5 255 -7\r\n3 4 5 0 100000\r\n"
      "6 7 8 17 0\r\n3 0 1 2\r\n1 0\r\n0\r\n");
  put("ply", "little.ply", binaryPly(false));
  put("ply", "big.ply", binaryPly(true));
  const std::vector<std::array<float, 3>> vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}};
  for (const char* name : {"written.ply", "written.obj"}) {
    const fs::path path =
        out_dir / (fs::path(name).extension() == ".ply" ? "ply" : "obj");
    fs::create_directories(path);
    if (!pcl::cocone::saveMesh((path / name).string(), vertices, triangles, "seeds"))
      return 1;
  }

  fs::create_directories(out_dir / "pcd");
  const pcl::PCLPointCloud2 cloud = smallCloud();
  pcl::PCDWriter writer;
  if (writer.writeASCII((out_dir / "pcd" / "ascii.pcd").string(), cloud) != 0 ||
      writer.writeBinary((out_dir / "pcd" / "binary.pcd").string(), cloud) != 0 ||
      writer.writeBinaryCompressed((out_dir / "pcd" / "compressed.pcd").string(),
                                   cloud) != 0)
    return 1;
  put("pcd", "double.pcd",
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z label\n"
      "SIZE 8 8 8 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 2\n"
      "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
      "1.5 2.5 3.5 7\n4 5 6 8\n");

  // LAS: every version's header, old and new point formats, a VLR, longer records, the
  // 64-bit count of 1.4, a record after the points (1.3's waveform data, 1.4's extended
  // VLR) (written by the tests' own writer).
  namespace las = pcl::cocone::test;
  const std::vector<las::LasPoint> points = {
      {100, -200, 300, 7, 2}, {-5, 0, 12345, 65535, 31}, {0, 0, 0, 0, 0}};
  const auto lasSeed = [&](const char* name, unsigned minor, unsigned format,
                           std::size_t vlr_body, std::size_t extra_bytes,
                           std::size_t trailing_body = 0) {
    las::LasLayout layout;
    layout.minor = minor;
    layout.format = format;
    layout.vlr_body = vlr_body;
    layout.record_length = las::lasMinimumRecordLength(format) + extra_bytes;
    layout.offset = {1000.5, -2000.25, 3};
    layout.trailing_body = trailing_body;
    put("las", name, las::lasFile(layout, points));
  };
  lasSeed("v12_format1.las", 2, 1, 0, 0);
  lasSeed("v12_format0_vlr.las", 2, 0, 40, 3);
  lasSeed("v13_format4.las", 3, 4, 0, 0);
  lasSeed("v14_format6.las", 4, 6, 26, 0);
  lasSeed("v14_format10.las", 4, 10, 0, 5);
  lasSeed("v13_format1_waveform.las", 3, 1, 0, 0, 24);
  lasSeed("v14_format7_evlr.las", 4, 7, 0, 0, 24);
  return 0;
}
