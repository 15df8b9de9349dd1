// SPDX-License-Identifier: GPL-3.0-or-later
// KdTiling (tiling.h): tiles balanced by count, cut into leaves at medians.
#include "voronoi/tiling.h"

#include <algorithm>
#include <stdexcept>

namespace pcl {
namespace cocone {
namespace detail {

KdTiling::KdTiling(const std::vector<Eigen::Vector3d>& points,
                   std::vector<SampleIndex> samples, unsigned tiles, unsigned leaf_size)
  : order_(std::move(samples))
{
  if (order_.empty())
    throw std::invalid_argument("KdTiling: no samples");
  tiles = std::max(1u, std::min<unsigned>(tiles, static_cast<unsigned>(order_.size())));
  // Every part of a tile holds a sample: the cut never makes an empty node.
  leaf_size = std::max(1u, leaf_size);
  nodes_.reserve(2 * (order_.size() / leaf_size + tiles) + 1);
  tile_first_leaf_.push_back(0);
  build(points, 0, static_cast<std::uint32_t>(order_.size()), tiles, leaf_size);
}

std::uint32_t
KdTiling::build(const std::vector<Eigen::Vector3d>& points, std::uint32_t first,
                std::uint32_t last, unsigned tiles, unsigned leaf_size)
{
  const std::uint32_t id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box;
  for (std::uint32_t i = first; i < last; ++i)
    box.extend(points[order_[i]]);
  nodes_[id].box = box;
  nodes_[id].first = first;
  nodes_[id].last = last;

  const std::uint32_t count = last - first;
  if (tiles <= 1 && count <= leaf_size) {
    nodes_[id].leaf = static_cast<std::uint32_t>(leaf_node_.size());
    leaf_node_.push_back(id);
  }
  else {
    // Tiles split their count in proportion (7 tiles: 3 and 4); leaves at the median.
    const unsigned low_tiles = tiles / 2;
    const std::uint32_t split =
        first + (tiles > 1 ? static_cast<std::uint32_t>(std::uint64_t(count) *
                                                        low_tiles / tiles)
                           : count / 2);
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    // Ties on the coordinate go by index: the cut is a function of the points alone.
    std::nth_element(order_.begin() + first, order_.begin() + split,
                     order_.begin() + last, [&](SampleIndex a, SampleIndex b) {
                       const double ca = points[a][axis], cb = points[b][axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    const unsigned high_tiles = tiles > 1 ? tiles - low_tiles : 0;
    const std::uint32_t low =
        build(points, first, split, tiles > 1 ? low_tiles : 0, leaf_size);
    const std::uint32_t high = build(points, split, last, high_tiles, leaf_size);
    nodes_[id].child[0] = low;
    nodes_[id].child[1] = high;
  }
  // tiles == 1: this node is a whole tile; 0: a part of one.
  if (tiles == 1) {
    tile_box_.push_back(box);
    tile_first_leaf_.push_back(static_cast<std::uint32_t>(leaf_node_.size()));
  }
  return id;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
