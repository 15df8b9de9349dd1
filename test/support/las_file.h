// SPDX-License-Identifier: GPL-3.0-or-later
//
// LAS files written byte by byte for the tests (and the fuzzers' seeds): a public
// header block of LAS 1.0 to 1.4, one variable-length record if asked for, and point
// records of any format 0 to 10. Every field the reader does not read is filled with a
// pattern, so that a reader looking at the wrong bytes is caught. Header-only, no
// dependency.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

struct LasPoint
{
  std::int32_t x = 0, y = 0, z = 0; ///< scaled integers, as stored
  std::uint16_t intensity = 0;
  std::uint8_t classification = 0; ///< below 32 for formats 0 to 5
};

struct LasLayout
{
  unsigned major = 1;
  unsigned minor = 2;
  unsigned format = 1;           ///< the byte as written (LAZ sets bit 7)
  std::size_t record_length = 0; ///< 0: the format's minimum
  std::size_t vlr_body = 0;      ///< bytes of one VLR's body; 0: no VLR
  std::array<double, 3> scale{0.01, 0.01, 0.01};
  std::array<double, 3> offset{0, 0, 0};
  std::optional<std::uint64_t> legacy_count; ///< default: the points' number (0 for
                                             ///< formats 6 to 10 in 1.4)
  std::optional<std::uint64_t> count64;      ///< LAS 1.4; default: the points' number
  std::optional<std::size_t> header_size;    ///< default: the version's
  std::optional<std::uint32_t> offset_to_points; ///< default: after header and VLR
  /** Bytes of the body of one record after the point data; 0: none. In LAS 1.3 it is
   * the waveform data packet record (global encoding bit 1, its start at byte 227), in
   * 1.4 an extended VLR (its start at byte 235, the count of them at 243). */
  std::size_t trailing_body = 0;
};

/** The shortest record of formats 0 to 10. */
inline std::size_t
lasMinimumRecordLength(unsigned format)
{
  constexpr std::size_t lengths[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
  return lengths[format & 0x3fu];
}

namespace detail {

template <typename T>
void
putLittle(std::string& out, std::size_t at, T value)
{
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  const bool host_little = *reinterpret_cast<const unsigned char*>(&probe) == 1;
  for (std::size_t k = 0; k < sizeof(T); ++k)
    out[at + k] = static_cast<char>(bytes[host_little ? k : sizeof(T) - 1 - k]);
}

} // namespace detail

/** The bytes of a LAS file of \a layout holding \a points. */
inline std::string
lasFile(const LasLayout& layout, const std::vector<LasPoint>& points)
{
  using detail::putLittle;
  const std::size_t header_size = layout.header_size ? *layout.header_size
                                                     : (layout.minor >= 4   ? 375
                                                        : layout.minor == 3 ? 235
                                                                            : 227);
  const std::size_t vlr_size = layout.vlr_body > 0 ? 54 + layout.vlr_body : 0;
  const std::uint32_t offset_to_points =
      layout.offset_to_points ? *layout.offset_to_points
                              : static_cast<std::uint32_t>(header_size + vlr_size);
  const std::size_t record_length = layout.record_length
                                        ? layout.record_length
                                        : lasMinimumRecordLength(layout.format);
  const bool extended = (layout.format & 0x3fu) >= 6;

  std::string out(std::max<std::size_t>(header_size, 227), '\x5a');
  std::memcpy(&out[0], "LASF", 4);
  out[24] = static_cast<char>(layout.major);
  out[25] = static_cast<char>(layout.minor);
  putLittle<std::uint16_t>(out, 94, static_cast<std::uint16_t>(header_size));
  putLittle<std::uint32_t>(out, 96, offset_to_points);
  putLittle<std::uint32_t>(out, 100, vlr_size > 0 ? 1 : 0);
  out[104] = static_cast<char>(layout.format);
  putLittle<std::uint16_t>(out, 105, static_cast<std::uint16_t>(record_length));
  const std::uint64_t n = points.size();
  const std::uint64_t legacy = layout.legacy_count
                                   ? *layout.legacy_count
                                   : (layout.minor >= 4 && extended ? 0 : n);
  putLittle<std::uint32_t>(out, 107, static_cast<std::uint32_t>(legacy));
  for (int k = 0; k < 3; ++k) {
    putLittle<double>(out, 131 + 8 * k, layout.scale[k]);
    putLittle<double>(out, 155 + 8 * k, layout.offset[k]);
  }
  if (header_size >= 375)
    putLittle<std::uint64_t>(out, 247, layout.count64 ? *layout.count64 : n);
  out.resize(header_size);

  if (vlr_size > 0) {
    std::string vlr(vlr_size, '\x3c');
    putLittle<std::uint16_t>(vlr, 0, 0);
    std::memcpy(&vlr[2], "LASF_Projection\0", 16);
    putLittle<std::uint16_t>(vlr, 18, 34735);
    putLittle<std::uint16_t>(vlr, 20, static_cast<std::uint16_t>(layout.vlr_body));
    out += vlr;
  }
  if (!layout.offset_to_points && out.size() < offset_to_points)
    out.resize(offset_to_points, '\0');

  for (const LasPoint& p : points) {
    std::string record(record_length, '\xa5');
    putLittle<std::int32_t>(record, 0, p.x);
    putLittle<std::int32_t>(record, 4, p.y);
    putLittle<std::int32_t>(record, 8, p.z);
    putLittle<std::uint16_t>(record, 12, p.intensity);
    if (extended)
      record[16] = static_cast<char>(p.classification);
    else // the upper three bits are the synthetic, key-point and withheld flags
      record[15] = static_cast<char>(0xe0u | (p.classification & 0x1fu));
    out += record;
  }

  if (layout.trailing_body > 0 && layout.minor >= 3) {
    const std::uint64_t start = out.size();
    std::string trailing(60 + layout.trailing_body, '\x3c');
    putLittle<std::uint16_t>(trailing, 0, 0);
    putLittle<std::uint64_t>(trailing, 20, layout.trailing_body);
    out += trailing;
    if (layout.minor == 3) {
      putLittle<std::uint16_t>(out, 6, 2); // waveform data packets internal
      putLittle<std::uint64_t>(out, 227, start);
    }
    else {
      putLittle<std::uint64_t>(out, 235, start);
      putLittle<std::uint32_t>(out, 243, 1);
    }
  }
  return out;
}

} // namespace test
} // namespace cocone
} // namespace pcl
