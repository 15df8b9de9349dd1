// SPDX-License-Identifier: GPL-3.0-or-later
// spatialOrder (core/voronoi_cocone.h): samples along a Z-order curve.
#include "common/parallel.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {

namespace {

/** Spreads the low 21 bits of \a x to every third bit (bit k goes to bit 3k). */
std::uint64_t
spreadBits(std::uint64_t x)
{
  x &= 0x1fffffu;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

} // namespace

std::vector<SampleIndex>
spatialOrder(const std::vector<Eigen::Vector3d>& points, unsigned threads)
{
  const std::size_t n = points.size();
  if (n >= kNoSample)
    return {};
  Eigen::Vector3d low =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite()) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  // One scale for all axes keeps the cells cubes; a flat cloud then uses fewer levels
  // of one axis, which costs nothing.
  const double extent = (high - low).maxCoeff();
  constexpr double kLevels = double((1u << 21) - 1);
  const double scale = extent > 0 ? kLevels / extent : 0;
  // Sorting (key, position) pairs breaks ties by position: the order is stable.
  std::vector<std::pair<std::uint64_t, SampleIndex>> keyed(n);
  detail::runInArena(threads, [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3d& p = points[i];
            std::uint64_t key = std::numeric_limits<std::uint64_t>::max();
            if (p.allFinite()) {
              const Eigen::Vector3d cell =
                  ((p - low) * scale).cwiseMin(kLevels).cwiseMax(0.0);
              key = spreadBits(static_cast<std::uint64_t>(cell.x())) |
                    spreadBits(static_cast<std::uint64_t>(cell.y())) << 1 |
                    spreadBits(static_cast<std::uint64_t>(cell.z())) << 2;
            }
            keyed[i] = {key, static_cast<SampleIndex>(i)};
          }
        });
    tbb::parallel_sort(keyed.begin(), keyed.end());
  });
  std::vector<SampleIndex> order(n);
  for (std::size_t k = 0; k < n; ++k)
    order[k] = keyed[k].second;
  return order;
}

} // namespace cocone
} // namespace pcl
