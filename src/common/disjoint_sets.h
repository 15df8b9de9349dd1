// SPDX-License-Identifier: GPL-3.0-or-later
// Private: union-find over 0..n-1, shared by the mesh analysis and the mesher. Never
// installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Disjoint sets with path halving; the smaller index becomes the root, so the roots
 * do not depend on the order of the unions' arguments. */
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t n) : parent_(n)
  {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t(0));
  }

  std::uint32_t
  find(std::uint32_t x)
  {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  void
  unite(std::uint32_t a, std::uint32_t b)
  {
    a = find(a);
    b = find(b);
    if (a < b)
      parent_[b] = a;
    else if (b < a)
      parent_[a] = b;
  }

private:
  std::vector<std::uint32_t> parent_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
