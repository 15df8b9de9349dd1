// SPDX-License-Identifier: GPL-3.0-or-later
//
// LAS 1.0 to 1.4 (ASPRS LAS specification), the format airborne LiDAR comes in: a
// header, variable-length records, then fixed-size point records of one of the point
// data record formats 0 to 10, each starting with its coordinates as three 32-bit
// integers that the header's scale and offset turn into x, y, z.
//
// Our own parser, because neither library the project already uses has one: PCL 1.13
// reads no LAS, and Debian's VTK 9.1 is built without its LAS reader (vtkPDALReader
// needs PDAL). PDAL or LASlib would be large dependencies for 12 bytes a point.
//
// What is read: x, y, z (X * scale + offset, in double, then rounded to float as every
// reader does), the intensity and the classification, which sit at fixed offsets in
// every format. Extra bytes, variable-length records, waveform packets and extended
// records are skipped. LAZ (LASzip compression) is refused with the commands that
// decompress it.
//
// Every number of the header is checked against the file's size before anything is
// allocated: the header size against its version's, the offset to the point data, the
// record length against its format's minimum, and the point count (the legacy 32-bit
// count, or in LAS 1.4 the 64-bit one) against the bytes between the offset and the
// end of the file or the first record after the points (waveform data, extended VLR).
#include "readers.h"

#include "cloud_layout.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

// Offsets of the public header block (the same in every version; 1.3 and 1.4 append).
constexpr std::size_t kGlobalEncoding = 6;
constexpr std::size_t kVersionMajor = 24;
constexpr std::size_t kVersionMinor = 25;
constexpr std::size_t kHeaderSize = 94;
constexpr std::size_t kOffsetToPoints = 96;
constexpr std::size_t kPointFormat = 104;
constexpr std::size_t kRecordLength = 105;
constexpr std::size_t kLegacyPointCount = 107;
constexpr std::size_t kScale = 131;          // x, y, z: three doubles
constexpr std::size_t kOffset = 155;         // x, y, z: three doubles
constexpr std::size_t kWaveformStart = 227;  // LAS 1.3
constexpr std::size_t kFirstEvlrStart = 235; // LAS 1.4
constexpr std::size_t kEvlrCount = 243;      // LAS 1.4
constexpr std::size_t kPointCount64 = 247;   // LAS 1.4

/** The header's size in each version: 227 bytes up to 1.2, 235 in 1.3 (the waveform
 * data's start), 375 in 1.4 (extended records and 64-bit counts). */
std::size_t
headerSizeOfVersion(unsigned minor)
{
  return minor >= 4 ? 375 : minor == 3 ? 235 : 227;
}

/** The shortest record of point data record formats 0 to 10 (LAS 1.4, table 7 ff.). */
constexpr std::uint16_t kMinimumRecordLength[] = {20, 28, 26, 34, 57, 63,
                                                  30, 36, 38, 59, 67};

/** The value of type T stored little-endian at \a bytes, whatever the host order. */
template <typename T>
T
little(const std::uint8_t* bytes)
{
  std::uint8_t ordered[sizeof(T)];
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  for (std::size_t k = 0; k < sizeof(T); ++k)
    ordered[k] = bytes[first == 1 ? k : sizeof(T) - 1 - k];
  T value;
  std::memcpy(&value, ordered, sizeof(T));
  return value;
}

} // namespace

void
readLas(const Source& source, std::string_view text, pcl::PCLPointCloud2& cloud)
{
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  const std::size_t size = text.size();
  if (size < 4 || std::memcmp(bytes, "LASF", 4) != 0)
    source.fail("not a LAS file (it does not start with 'LASF')");
  if (size < headerSizeOfVersion(0))
    source.fail("truncated: " + std::to_string(size) +
                " bytes, shorter than a LAS header (227 bytes)");
  const unsigned major = bytes[kVersionMajor];
  const unsigned minor = bytes[kVersionMinor];
  if (major != 1 || minor > 4)
    source.fail("unsupported LAS version " + std::to_string(major) + "." +
                std::to_string(minor) + " (readable: 1.0 to 1.4)");
  const std::size_t header_size = little<std::uint16_t>(bytes + kHeaderSize);
  const std::size_t required = headerSizeOfVersion(minor);
  if (header_size < required)
    source.fail("the LAS " + std::to_string(major) + "." + std::to_string(minor) +
                " header declares " + std::to_string(header_size) +
                " bytes, fewer than the " + std::to_string(required) +
                " of its version");
  if (size < header_size)
    source.fail("truncated: the file ends within the LAS header");

  // LASzip marks compressed point data by setting the high bits of the format.
  const unsigned format_byte = bytes[kPointFormat];
  if (format_byte & 0xc0u)
    source.fail("the point data are LASzip-compressed (LAZ), which is not supported: "
                "decompress the file to LAS first, e.g. 'las2las -i IN.laz -o "
                "OUT.las' (LAStools) or 'pdal translate IN.laz OUT.las' (PDAL)");
  if (format_byte >= std::size(kMinimumRecordLength))
    source.fail("unknown LAS point data record format " + std::to_string(format_byte) +
                " (readable: 0 to 10)");
  const std::size_t record_length = little<std::uint16_t>(bytes + kRecordLength);
  if (record_length < kMinimumRecordLength[format_byte])
    source.fail("LAS point records of " + std::to_string(record_length) +
                " bytes, shorter than format " + std::to_string(format_byte) + "'s " +
                std::to_string(kMinimumRecordLength[format_byte]));

  const std::size_t offset_to_points = little<std::uint32_t>(bytes + kOffsetToPoints);
  if (offset_to_points < header_size)
    source.fail("the LAS point data start at byte " + std::to_string(offset_to_points) +
                ", within the header of " + std::to_string(header_size) + " bytes");
  if (offset_to_points > size)
    source.fail("truncated: the LAS point data start at byte " +
                std::to_string(offset_to_points) + ", beyond the file's " +
                std::to_string(size) + " bytes");

  // LAS 1.4 has a 64-bit count; its legacy 32-bit one is 0 when the count does not fit
  // (or the format is 6 to 10), and otherwise must agree.
  const std::uint64_t legacy = little<std::uint32_t>(bytes + kLegacyPointCount);
  std::uint64_t points = legacy;
  if (minor >= 4) {
    const auto extended = little<std::uint64_t>(bytes + kPointCount64);
    if (extended != 0 && legacy != 0 && extended != legacy)
      source.fail("the LAS 1.4 header's point counts disagree (legacy " +
                  std::to_string(legacy) + ", 64-bit " + std::to_string(extended) +
                  ")");
    if (extended != 0)
      points = extended;
  }
  if (points == 0)
    source.fail("no points (the LAS header's point count is 0)");
  // The point records end where a record after them begins: LAS 1.3's waveform data
  // packets (when the global encoding says they are in the file) or LAS 1.4's first
  // extended VLR. A start before the point data or beyond the file's end locates
  // nothing that could be read as points, and is left alone.
  std::size_t points_end = size;
  const auto endPointsAt = [&](std::uint64_t start) {
    if (start >= offset_to_points && start < points_end)
      points_end = static_cast<std::size_t>(start);
  };
  if (minor >= 3 && (little<std::uint16_t>(bytes + kGlobalEncoding) & 2u))
    endPointsAt(little<std::uint64_t>(bytes + kWaveformStart));
  if (minor >= 4 && little<std::uint32_t>(bytes + kEvlrCount) > 0)
    endPointsAt(little<std::uint64_t>(bytes + kFirstEvlrStart));
  const std::size_t available = (points_end - offset_to_points) / record_length;
  if (points > available)
    source.fail("truncated: the LAS header declares " + std::to_string(points) +
                " points of " + std::to_string(record_length) +
                " bytes, the file holds " + std::to_string(available) +
                (points_end < size ? " before the records that follow them at byte " +
                                         std::to_string(points_end)
                                   : std::string()));

  double scale[3];
  double offset[3];
  for (int k = 0; k < 3; ++k) {
    scale[k] = little<double>(bytes + kScale + 8 * k);
    offset[k] = little<double>(bytes + kOffset + 8 * k);
    if (!std::isfinite(scale[k]) || scale[k] == 0 || !std::isfinite(offset[k]))
      source.fail("the LAS header's scale or offset of " + std::string(1, "xyz"[k]) +
                  " is zero or not finite");
  }

  cloud = pcl::PCLPointCloud2();
  appendField(cloud, "x", Field::FLOAT32);
  appendField(cloud, "y", Field::FLOAT32);
  appendField(cloud, "z", Field::FLOAT32);
  appendField(cloud, "intensity", Field::UINT16);
  appendField(cloud, "classification", Field::UINT8);
  finishLayout(cloud, static_cast<std::size_t>(points));
  const std::uint32_t intensity_at = cloud.fields[3].offset;
  const std::uint32_t class_at = cloud.fields[4].offset;
  // Formats 0 to 5 keep the class in the low 5 bits of byte 15; 6 to 10 in byte 16.
  const bool extended_format = format_byte >= 6;

  const std::uint8_t* record = bytes + offset_to_points;
  std::uint8_t* point = cloud.data.data();
  for (std::size_t i = 0; i < points; ++i) {
    float xyz[3];
    for (int k = 0; k < 3; ++k)
      xyz[k] = toFloat(little<std::int32_t>(record + 4 * k) * scale[k] + offset[k]);
    std::memcpy(point, xyz, sizeof xyz);
    const auto intensity = little<std::uint16_t>(record + 12);
    std::memcpy(point + intensity_at, &intensity, sizeof intensity);
    point[class_at] = extended_format ? record[16] : record[15] & 0x1fu;
    record += record_length;
    point += cloud.point_step;
  }
  cloud.is_dense = allFinite(cloud);
}

} // namespace io_internal
} // namespace cocone
} // namespace pcl
