// SPDX-License-Identifier: GPL-3.0-or-later
// The LAS reader of pcl_cocone_io, on files written here byte by byte
// (support/las_file.h): every version and point format, scale and offset, the 64-bit
// count of LAS 1.4, and headers that lie or files that end early, which must fail with
// a one-line reason and allocate nothing.
#include <pcl/cocone/io/point_io.h>

#include "support/las_file.h"
#include "support/scratch_folder.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
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
using pcl::cocone::test::lasFile;
using pcl::cocone::test::LasLayout;
using pcl::cocone::test::lasMinimumRecordLength;
using pcl::cocone::test::LasPoint;

class LasReader : public ::testing::Test
{
protected:
  std::string
  write(const std::string& name, const std::string& bytes) const
  {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  pcl::cocone::test::ScratchFolder scratch_{"pcl_cocone_las_"};
  const fs::path& dir_ = scratch_.path();
};

/** A few points with distinct coordinates, intensities and classes. */
std::vector<LasPoint>
somePoints(std::size_t n)
{
  std::vector<LasPoint> points;
  for (std::size_t i = 0; i < n; ++i) {
    LasPoint p;
    p.x = static_cast<std::int32_t>(1000 * i + 17);
    p.y = -static_cast<std::int32_t>(250 * i) - 3;
    p.z = static_cast<std::int32_t>(i * i) - 40;
    p.intensity = static_cast<std::uint16_t>(60000 - 1000 * i);
    p.classification = static_cast<std::uint8_t>(2 + i % 7);
    points.push_back(p);
  }
  return points;
}

/** Loads \a path, which must succeed with the points of \a points under \a layout's
 * scale and offset (as floats of the double values). */
void
expectPoints(const std::string& path, const LasLayout& layout,
             const std::vector<LasPoint>& points)
{
  pcl::PCLPointCloud2 cloud;
  std::string error = "stale";
  ASSERT_TRUE(pcl::cocone::loadPointSamples(path, cloud, &error)) << error;
  EXPECT_TRUE(error.empty());
  ASSERT_EQ(static_cast<std::size_t>(cloud.width) * cloud.height, points.size());
  EXPECT_EQ(cloud.data.size(), points.size() * cloud.point_step);
  for (const char* name : {"x", "y", "z"}) {
    ASSERT_NE(findField(cloud, name), nullptr);
    EXPECT_EQ(findField(cloud, name)->datatype, PCLPointField::FLOAT32);
  }
  ASSERT_NE(findField(cloud, "intensity"), nullptr);
  ASSERT_NE(findField(cloud, "classification"), nullptr);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const LasPoint& p = points[i];
    EXPECT_EQ(valueAt<float>(cloud, i, "x"),
              static_cast<float>(p.x * layout.scale[0] + layout.offset[0]));
    EXPECT_EQ(valueAt<float>(cloud, i, "y"),
              static_cast<float>(p.y * layout.scale[1] + layout.offset[1]));
    EXPECT_EQ(valueAt<float>(cloud, i, "z"),
              static_cast<float>(p.z * layout.scale[2] + layout.offset[2]));
    EXPECT_EQ(valueAt<std::uint16_t>(cloud, i, "intensity"), p.intensity);
    EXPECT_EQ(valueAt<std::uint8_t>(cloud, i, "classification"), p.classification);
  }
  EXPECT_TRUE(cloud.is_dense);
}

/** Loads \a path, which must fail with a one-line reason naming the file and holding
 * \a expected; returns the reason. */
std::string
expectFailure(const std::string& path, const std::string& expected)
{
  pcl::PCLPointCloud2 cloud;
  std::string error;
  ::testing::internal::CaptureStderr();
  const bool ok = pcl::cocone::loadPointSamples(path, cloud, &error);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok) << path;
  EXPECT_TRUE(printed.empty()) << printed;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_NE(error.find(fs::path(path).filename().string()), std::string::npos) << error;
  EXPECT_NE(error.find(expected), std::string::npos) << error;
  EXPECT_TRUE(cloud.data.empty());
  return error;
}

TEST_F(LasReader, EveryVersionAndPointFormatWithScaleAndOffset)
{
  const std::vector<LasPoint> points = somePoints(9);
  for (unsigned minor = 0; minor <= 4; ++minor)
    for (unsigned format = 0; format <= 10; ++format) {
      SCOPED_TRACE("LAS 1." + std::to_string(minor) + " format " +
                   std::to_string(format));
      LasLayout layout;
      layout.minor = minor;
      layout.format = format;
      layout.scale = {0.001, 0.01, 0.25};
      layout.offset = {431000.5, -12.25, 100};
      expectPoints(write("f.las", lasFile(layout, points)), layout, points);
    }
}

TEST_F(LasReader, VariableLengthRecordsAndLongerRecordsAreSkipped)
{
  const std::vector<LasPoint> points = somePoints(5);
  LasLayout layout;
  layout.minor = 3;
  layout.format = 3;
  layout.vlr_body = 100;
  layout.record_length = lasMinimumRecordLength(3) + 11; // extra bytes per point
  expectPoints(write("vlr.las", lasFile(layout, points)), layout, points);
  // The extension is case-insensitive.
  expectPoints(write("VLR.LAS", lasFile(layout, points)), layout, points);
}

TEST_F(LasReader, Las14TakesTheSixtyFourBitCount)
{
  const std::vector<LasPoint> points = somePoints(6);
  LasLayout layout;
  layout.minor = 4;
  layout.format = 6; // legacy count 0, as the format requires
  layout.scale = {1e-4, 1e-4, 1e-4};
  layout.offset = {2.5, 3.5, -4.5};
  expectPoints(write("v14.las", lasFile(layout, points)), layout, points);
  // A 1.4 file of an old format may carry both counts, which then agree.
  layout.format = 1;
  layout.legacy_count = points.size();
  expectPoints(write("both.las", lasFile(layout, points)), layout, points);
  // Or only the legacy one.
  layout.count64 = 0;
  expectPoints(write("legacy.las", lasFile(layout, points)), layout, points);
  // Counts that disagree are an error.
  layout.legacy_count = 5;
  layout.count64 = 6;
  expectFailure(write("disagree.las", lasFile(layout, points)), "disagree");
  // A 64-bit count beyond what 32 bits hold, with the data missing: refused from the
  // header, before anything is allocated.
  layout.legacy_count = 0;
  layout.count64 = (std::uint64_t{1} << 40) + 3;
  expectFailure(write("huge.las", lasFile(layout, points)), "truncated");
}

TEST_F(LasReader, TruncatedFilesFail)
{
  const std::vector<LasPoint> points = somePoints(8);
  LasLayout layout;
  const std::string whole = lasFile(layout, points);
  // Within the records, just after the header, within the header, nearly empty.
  for (const std::size_t size : {whole.size() - 1, whole.size() - 20 * 3 - 7,
                                 std::size_t{228}, std::size_t{120}, std::size_t{4}})
    expectFailure(write("cut.las", whole.substr(0, size)), "truncated");
  // A count larger than the records there are.
  layout.legacy_count = 9;
  expectFailure(write("count.las", lasFile(layout, points)), "truncated");
  // LAS 1.4 needs its 375-byte header.
  layout = LasLayout();
  layout.minor = 4;
  expectFailure(write("v14.las", lasFile(layout, points).substr(0, 300)), "truncated");
}

TEST_F(LasReader, PointRecordsEndWhereTheRecordsAfterThemBegin)
{
  // LAS 1.3 may keep waveform data packets, LAS 1.4 extended VLRs, after the point
  // records. A count larger than the records there are must not read into them: their
  // bytes would come back as points, without a word.
  const std::vector<LasPoint> points = somePoints(6);
  for (const unsigned minor : {3u, 4u}) {
    SCOPED_TRACE("LAS 1." + std::to_string(minor));
    LasLayout layout;
    layout.minor = minor;
    layout.format = minor == 3 ? 1 : 6;
    layout.trailing_body = 4 * lasMinimumRecordLength(layout.format);
    expectPoints(write("trailing.las", lasFile(layout, points)), layout, points);
    if (minor == 3)
      layout.legacy_count = points.size() + 1;
    else
      layout.count64 = points.size() + 1;
    expectFailure(write("overlap.las", lasFile(layout, points)), "truncated");
  }
}

TEST_F(LasReader, BadHeadersFail)
{
  const std::vector<LasPoint> points = somePoints(3);
  const auto bad = [&](const std::string& name, LasLayout layout,
                       const std::string& expected) {
    SCOPED_TRACE(name);
    return expectFailure(write(name + ".las", lasFile(layout, points)), expected);
  };
  std::string text = lasFile(LasLayout(), points);
  text[0] = 'X';
  expectFailure(write("signature.las", text), "not a LAS file");
  expectFailure(write("empty.las", ""), "not a LAS file");

  LasLayout layout;
  layout.major = 2;
  bad("major", layout, "unsupported LAS version 2.2");
  layout = LasLayout();
  layout.minor = 5;
  bad("minor", layout, "unsupported LAS version 1.5");
  layout = LasLayout();
  layout.format = 11;
  layout.record_length = 80;
  bad("format", layout, "point data record format 11");
  layout = LasLayout();
  layout.format = 3;
  layout.record_length = lasMinimumRecordLength(3) - 1;
  bad("short_record", layout, "shorter than format 3's 34");
  layout = LasLayout();
  layout.minor = 4;
  layout.header_size = 227; // a 1.2 header in a 1.4 file
  bad("header_size", layout, "fewer than the 375");
  layout = LasLayout();
  layout.offset_to_points = 100;
  bad("offset_inside", layout, "within the header");
  layout = LasLayout();
  layout.offset_to_points = 1u << 30;
  bad("offset_beyond", layout, "beyond the file");
  layout = LasLayout();
  layout.scale = {0.01, 0, 0.01};
  bad("zero_scale", layout, "scale or offset of y");
  layout = LasLayout();
  layout.offset = {0, 0, std::nan("")};
  bad("nan_offset", layout, "scale or offset of z");
  layout = LasLayout();
  expectFailure(write("zero.las", lasFile(layout, {})), "no points");
}

TEST_F(LasReader, LazIsRefusedWithTheWayToConvertIt)
{
  const std::vector<LasPoint> points = somePoints(4);
  LasLayout layout;
  layout.format = 0x80u | 1u; // how LASzip marks compressed point data
  for (const char* name : {"scan.laz", "scan.las"}) {
    const std::string error =
        expectFailure(write(name, lasFile(layout, points)), "LAZ");
    EXPECT_NE(error.find("las2las"), std::string::npos) << error;
    EXPECT_NE(error.find("pdal translate"), std::string::npos) << error;
  }
  // An uncompressed file named .laz is read as what it is.
  layout.format = 1;
  expectPoints(write("plain.laz", lasFile(layout, points)), layout, points);
}

TEST_F(LasReader, CoordinatesBeyondFloatBecomeInfiniteNotUndefined)
{
  std::vector<LasPoint> points = somePoints(3);
  points[1].x = std::numeric_limits<std::int32_t>::max();
  LasLayout layout;
  // X * scale is finite as a double (about 2e39) but beyond float's range, so that the
  // reader's conversion to float is what is tested (a scale of 1e300 overflowed in the
  // double product already, and an infinite double converts to float without harm).
  layout.scale = {1e30, 1, 1};
  ASSERT_TRUE(std::isfinite(points[1].x * layout.scale[0]));
  ASSERT_GT(points[1].x * layout.scale[0], std::numeric_limits<float>::max());
  pcl::PCLPointCloud2 cloud;
  std::string error;
  ASSERT_TRUE(pcl::cocone::loadPointSamples(write("far.las", lasFile(layout, points)),
                                            cloud, &error))
      << error;
  EXPECT_TRUE(std::isinf(valueAt<float>(cloud, 1, "x")));
  EXPECT_FALSE(cloud.is_dense);
}

} // namespace
