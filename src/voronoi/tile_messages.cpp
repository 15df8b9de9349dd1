// SPDX-License-Identifier: GPL-3.0-or-later
// The message of a process that built some of a diagram's tiles (tile_messages.h).
// The samples of a tile are not named: both ends hold the same tiling, and a tile's
// values follow its samples in the tiling's order.
#include "voronoi/tile_messages.h"

#include "common/status_guard.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

class Writer
{
public:
  template <typename T>
  void
  put(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "raw bytes only");
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(&value);
    buffer.insert(buffer.end(), bytes, bytes + sizeof(T));
  }

  std::vector<std::uint8_t> buffer;
};

class Reader
{
public:
  explicit Reader(const std::vector<std::uint8_t>& buffer) : buffer_(buffer) {}

  template <typename T>
  T
  get()
  {
    if (buffer_.size() - position_ < sizeof(T))
      throw StageFailure{Status::internal_error,
                         "a tile message from another process is truncated"};
    T value;
    std::memcpy(&value, buffer_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }

  std::size_t
  remaining() const
  {
    return buffer_.size() - position_;
  }

  bool
  atEnd() const
  {
    return position_ == buffer_.size();
  }

private:
  const std::vector<std::uint8_t>& buffer_;
  std::size_t position_ = 0;
};

[[noreturn]] void
malformed(const std::string& what)
{
  throw StageFailure{Status::internal_error,
                     "a tile message from another process " + what};
}

void
putVector(Writer& out, const Eigen::Vector3d& v)
{
  out.put(v.x());
  out.put(v.y());
  out.put(v.z());
}

Eigen::Vector3d
getVector(Reader& in)
{
  const double x = in.get<double>();
  const double y = in.get<double>();
  const double z = in.get<double>();
  return {x, y, z};
}

} // namespace

std::uint64_t
diagramFingerprint(const DiagramState& d, const KdTiling& tiling)
{
  // FNV-1a over the counts and the coordinates, in the tiling's order.
  std::uint64_t hash = 0xcbf29ce484222325ull;
  const auto mix = [&](const void* bytes, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(bytes);
    for (std::size_t i = 0; i < size; ++i) {
      hash ^= p[i];
      hash *= 0x100000001b3ull;
    }
  };
  const std::uint64_t counts[3] = {d.centered.size(), d.unique_count,
                                   tiling.numTiles()};
  mix(counts, sizeof counts);
  for (const SampleIndex s : tiling.order())
    mix(d.centered[s].data(), 3 * sizeof(double));
  return hash;
}

namespace {
enum MessageKind : std::uint8_t
{
  kOutgrown = 0,
  kComplete = 1,
  kFailed = 2
};
} // namespace

std::vector<std::uint8_t>
packTiles(const KdTiling& tiling, const std::vector<unsigned>& tiles, bool complete,
          std::uint64_t fingerprint, const DiagramState& d,
          std::vector<TileContribution>& contributions)
{
  Writer out;
  out.put(std::uint8_t(complete ? kComplete : kOutgrown));
  out.put(fingerprint);
  if (!complete)
    return std::move(out.buffer);
  out.put(std::uint32_t(tiles.size()));
  for (const unsigned t : tiles) {
    out.put(std::uint32_t(t));
    tiling.forEachSampleOfTile(t, [&](SampleIndex s) {
      putVector(out, d.pole_vector[s]);
      putVector(out, d.positive_pole[s]);
      putVector(out, d.negative_pole[s]);
      out.put(d.height[s]);
      out.put(d.radius[s]);
      out.put(d.unbounded[s]);
    });
    TileContribution& tile = contributions[t];
    out.put(std::uint64_t(tile.cells.size()));
    for (const std::array<SampleIndex, 4>& cell : tile.cells)
      for (const SampleIndex s : cell)
        out.put(s);
    out.put(std::uint64_t(tile.marks.size()));
    // Field by field: the struct's padding is no part of the message.
    for (const MarkedTriangle& mark : tile.marks) {
      for (const SampleIndex s : mark.vertex)
        out.put(s);
      out.put(mark.marked_by);
    }
    tile = TileContribution();
  }
  return std::move(out.buffer);
}

std::vector<std::uint8_t>
packFailure(const std::string& reason)
{
  std::vector<std::uint8_t> message(1 + reason.size());
  message[0] = kFailed;
  std::copy(reason.begin(), reason.end(), message.begin() + 1);
  return message;
}

bool
unpackTiles(const std::vector<std::uint8_t>& message, unsigned sender,
            unsigned processes, const KdTiling& tiling, std::uint64_t fingerprint,
            DiagramState& d, std::vector<TileContribution>& contributions)
{
  Reader in(message);
  const std::uint8_t kind = in.get<std::uint8_t>();
  if (kind == kFailed)
    throw StageFailure{Status::internal_error,
                       "process " + std::to_string(sender) + " failed: " +
                           std::string(message.begin() + 1, message.end())};
  if (kind != kComplete && kind != kOutgrown)
    malformed("is of unknown kind " + std::to_string(kind));
  if (in.get<std::uint64_t>() != fingerprint)
    malformed("was made from other points or another tiling (same input, options "
              "and build on every process?)");
  if (kind == kOutgrown) {
    if (!in.atEnd())
      malformed("has bytes beyond its end");
    return false;
  }
  const std::size_t n = d.pole_vector.size();
  const auto check_sample = [&](SampleIndex s, bool may_be_infinite) {
    if (s < n || (may_be_infinite && s == kNoSample))
      return s;
    malformed("names sample " + std::to_string(s) + " of " + std::to_string(n));
  };
  // Exactly the tiles dealt to the sender, in ascending order.
  std::vector<unsigned> dealt;
  for (unsigned t = sender; t < tiling.numTiles(); t += processes)
    dealt.push_back(t);
  const std::uint32_t count = in.get<std::uint32_t>();
  if (count != dealt.size())
    malformed("holds " + std::to_string(count) + " tiles, not the " +
              std::to_string(dealt.size()) + " dealt to process " +
              std::to_string(sender));
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t t = in.get<std::uint32_t>();
    if (t != dealt[k])
      malformed("names tile " + std::to_string(t) + " where tile " +
                std::to_string(dealt[k]) + " was dealt to process " +
                std::to_string(sender));
    tiling.forEachSampleOfTile(t, [&](SampleIndex s) {
      d.pole_vector[s] = getVector(in);
      d.positive_pole[s] = getVector(in);
      d.negative_pole[s] = getVector(in);
      d.height[s] = in.get<double>();
      d.radius[s] = in.get<double>();
      d.unbounded[s] = in.get<std::uint8_t>();
    });
    TileContribution& tile = contributions[t];
    // Counts are checked against the bytes left before anything is allocated.
    const std::uint64_t cells = in.get<std::uint64_t>();
    if (cells > in.remaining() / (4 * sizeof(SampleIndex)))
      malformed("is truncated");
    tile.cells.resize(cells);
    for (std::array<SampleIndex, 4>& cell : tile.cells)
      for (int k = 0; k < 4; ++k)
        cell[k] = check_sample(in.get<SampleIndex>(), k == 3);
    const std::uint64_t marks = in.get<std::uint64_t>();
    if (marks > in.remaining() / (3 * sizeof(SampleIndex) + 1))
      malformed("is truncated");
    tile.marks.resize(marks);
    for (MarkedTriangle& mark : tile.marks) {
      for (SampleIndex& s : mark.vertex)
        s = check_sample(in.get<SampleIndex>(), false);
      mark.marked_by = in.get<std::uint8_t>();
    }
  }
  if (!in.atEnd())
    malformed("has bytes beyond its last tile");
  return true;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
