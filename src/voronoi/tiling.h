// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the partition of the distinct samples into tiles balanced by count, each cut
// further into small leaves, the unit by which a tile's halo grows. Free of CGAL. Never
// installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** A kd-tree over the distinct samples. Its top levels cut them into \a tiles parts
 * whose counts differ by at most one leaf's worth; below, every tile is cut at medians
 * into leaves of at most \a leaf_size samples. Leaves are numbered depth first, so the
 * leaves of one tile are consecutive. Each node keeps the tight box of its samples: a
 * query for what may lie inside a ball or a half-space skips the empty space between
 * the parts of a surface. The cut depends only on the coordinates and indices, never on
 * the thread count. */
class KdTiling
{
public:
  static constexpr std::uint32_t kNone = ~std::uint32_t(0);

  struct Node
  {
    Eigen::AlignedBox3d box;                 // tight box of the node's samples
    std::uint32_t first = 0, last = 0;       // its samples: order()[first, last)
    std::uint32_t child[2] = {kNone, kNone}; // kNone for a leaf
    std::uint32_t leaf = kNone;              // the leaf's number, for a leaf
  };

  /** Cuts \a samples (indices into \a points, each distinct) into \a tiles tiles of
   * leaves of at most \a leaf_size samples. */
  KdTiling(const std::vector<Eigen::Vector3d>& points, std::vector<SampleIndex> samples,
           unsigned tiles, unsigned leaf_size);

  unsigned
  numTiles() const
  {
    return static_cast<unsigned>(tile_first_leaf_.size() - 1);
  }
  std::uint32_t
  numLeaves() const
  {
    return static_cast<std::uint32_t>(leaf_node_.size());
  }
  /** The leaves of tile t are firstLeaf(t) to firstLeaf(t + 1) - 1. */
  std::uint32_t
  firstLeaf(unsigned t) const
  {
    return tile_first_leaf_[t];
  }
  const Node&
  leaf(std::uint32_t l) const
  {
    return nodes_[leaf_node_[l]];
  }
  /** The samples, leaf after leaf. */
  const std::vector<SampleIndex>&
  order() const
  {
    return order_;
  }
  /** The tight box of all the samples. */
  const Eigen::AlignedBox3d&
  box() const
  {
    return nodes_[0].box;
  }
  /** The tight box of tile t's samples. */
  const Eigen::AlignedBox3d&
  tileBox(unsigned t) const
  {
    return tile_box_[t];
  }

  /** Calls \a visit(sample) for the samples of tile \a t, in the tiling's order. */
  template <typename Visit>
  void
  forEachSampleOfTile(unsigned t, const Visit& visit) const
  {
    for (std::uint32_t l = firstLeaf(t); l < firstLeaf(t + 1); ++l)
      for (std::uint32_t i = leaf(l).first; i < leaf(l).last; ++i)
        visit(order_[i]);
  }

  /** Calls \a visit(leaf number) for every leaf whose box \a meets (a predicate on
   * boxes that must hold for a node whenever it holds for a box inside it). */
  template <typename Meets, typename Visit>
  void
  visitLeaves(const Meets& meets, const Visit& visit) const
  {
    if (nodes_.empty())
      return;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!meets(node.box))
        continue;
      if (node.leaf != kNone) {
        visit(node.leaf);
        continue;
      }
      stack[top++] = node.child[0];
      stack[top++] = node.child[1];
    }
  }

private:
  std::uint32_t build(const std::vector<Eigen::Vector3d>& points, std::uint32_t first,
                      std::uint32_t last, unsigned tiles, unsigned leaf_size);

  std::vector<SampleIndex> order_;
  std::vector<Node> nodes_; // the root is node 0
  std::vector<std::uint32_t> leaf_node_;
  std::vector<std::uint32_t> tile_first_leaf_;
  std::vector<Eigen::AlignedBox3d> tile_box_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
