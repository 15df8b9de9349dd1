// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/box_grid.h"

namespace pcl {
namespace cocone {
namespace detail {

double
BoxGrid::cellSideFor(double edges, std::size_t count)
{
  return count > 0 && edges > 0 ? 2 * edges / static_cast<double>(count) : 1;
}

void
BoxGrid::insert(std::uint32_t id, const Box& box)
{
  if (cellCountOf(box) > kMostCells) {
    large_.push_back(id);
    large_boxes_.push_back(box);
    return;
  }
  forEachCellOf(box, [&](CellKey key) { cells_[key].push_back(id); });
}

} // namespace detail
} // namespace cocone
} // namespace pcl
