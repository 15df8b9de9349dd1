// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a uniform grid over axis-aligned boxes, to find the boxes that meet a query
// box without looking at all of them. It knows entries only as ids with boxes (the
// mesher's triangles, or positions in a list of them). Never installed.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** An axis-aligned box, closed: its low and high corners. */
struct Box
{
  Eigen::Vector3d low;
  Eigen::Vector3d high;
};

/** Whether two boxes are strictly separated along some axis. Touching boxes are not
 * apart: the exact tests count touching as meeting. */
inline bool
boxesApart(const Box& a, const Box& b)
{
  return (a.high.array() < b.low.array()).any() ||
         (b.high.array() < a.low.array()).any();
}

/** A uniform grid of cubes over the boxes of entries (ids): an entry is listed in every
 * cell its box meets, except a large one (see kMostCells). Queries are read-only:
 * threads may query at once. Entries are never removed; an id may be inserted again
 * (it is then listed twice). */
class BoxGrid
{
public:
  /** An entry whose box meets more cells than this is kept in a flat list with its box
   * instead, and every query looks at it: a triangle far longer than the mean (a fill
   * across a wide hole, or the sparse background of a depth image) would fill many
   * cells: on PCL's stereo table scene some 900 triangles of the mesh spanned up to
   * 150 000 cells each. */
  static constexpr double kMostCells = 64;

  /** The side of the cells for boxes of triangles: twice the mean of the \a count edges
   * summing to \a edges (a triangle then spans a few cells); 1 when there is none. */
  static double cellSideFor(double edges, std::size_t count);

  /** An empty grid of cubes of side \a cell_side (> 0). */
  explicit BoxGrid(double cell_side) : cell_(cell_side) {}

  double
  cellSide() const
  {
    return cell_;
  }

  /** Makes room for \a cells occupied cells: without it the map rehashes as it
   * grows. */
  void
  reserve(std::size_t cells)
  {
    cells_.reserve(cells);
  }

  /** Lists entry \a id, of box \a box. */
  void insert(std::uint32_t id, const Box& box);

  /** Calls visit(id) for every entry listed in a cell that \a query meets (so for every
   * entry whose box meets \a query, and perhaps for others near it; an entry listed in
   * several of those cells, or inserted twice, is visited as often), and for every
   * large entry whose box meets \a query. When \a query meets more cells than the grid
   * has occupied ones, visiting its cells would cost more: every listed entry is then
   * looked at instead, and visited when box_of(id), its box, meets \a query. */
  template <typename BoxOf, typename Visit>
  void
  forEachNear(const Box& query, const BoxOf& box_of, Visit&& visit) const
  {
    if (cellCountOf(query) <= static_cast<double>(cells_.size())) {
      forEachCellOf(query, [&](CellKey key) {
        const auto found = cells_.find(key);
        if (found != cells_.end())
          for (const std::uint32_t id : found->second)
            visit(id);
      });
    }
    else {
      for (const auto& cell : cells_)
        for (const std::uint32_t id : cell.second)
          if (!boxesApart(box_of(id), query))
            visit(id);
    }
    visitLarge(query, visit);
  }

  /** Calls visit(id) exactly once for every entry whose box, box_of(id), meets \a query
   * (for an id inserted once). An entry listed in several cells is visited in the one
   * that holds the low corner of the common part of the two boxes. (Cell keys keep 21
   * bits per axis: on a grid over 2^21 cells wide, cells that far apart share a key,
   * and an entry may be visited twice.) */
  template <typename BoxOf, typename Visit>
  void
  forEachOverlapping(const Box& query, const BoxOf& box_of, Visit&& visit) const
  {
    const auto visit_in = [&](CellKey key, const std::vector<std::uint32_t>& listed) {
      for (const std::uint32_t id : listed) {
        const Box& box = box_of(id);
        if (keyOf(query.low.cwiseMax(box.low)) == key && !boxesApart(box, query))
          visit(id);
      }
    };
    if (cellCountOf(query) <= static_cast<double>(cells_.size())) {
      forEachCellOf(query, [&](CellKey key) {
        const auto found = cells_.find(key);
        if (found != cells_.end())
          visit_in(key, found->second);
      });
    }
    else { // a query wider than the grid
      for (const auto& [key, listed] : cells_)
        visit_in(key, listed);
    }
    visitLarge(query, visit);
  }

private:
  using CellKey = std::uint64_t;

  long
  cellIndex(double x) const
  {
    return static_cast<long>(std::floor(x / cell_));
  }

  static CellKey
  packCell(long x, long y, long z)
  {
    return (static_cast<CellKey>(x & 0x1FFFFF) << 42) |
           (static_cast<CellKey>(y & 0x1FFFFF) << 21) |
           static_cast<CellKey>(z & 0x1FFFFF);
  }

  /** The cell that holds \a p. */
  CellKey
  keyOf(const Eigen::Vector3d& p) const
  {
    return packCell(cellIndex(p.x()), cellIndex(p.y()), cellIndex(p.z()));
  }

  /** The number of cells \a box meets (a double: it can be huge). */
  double
  cellCountOf(const Box& box) const
  {
    double count = 1;
    for (int axis = 0; axis < 3; ++axis)
      count *=
          std::floor(box.high[axis] / cell_) - std::floor(box.low[axis] / cell_) + 1;
    return count;
  }

  /** Calls f(key) for every cell \a box meets. */
  template <typename F>
  void
  forEachCellOf(const Box& box, F&& f) const
  {
    for (long x = cellIndex(box.low.x()); x <= cellIndex(box.high.x()); ++x)
      for (long y = cellIndex(box.low.y()); y <= cellIndex(box.high.y()); ++y)
        for (long z = cellIndex(box.low.z()); z <= cellIndex(box.high.z()); ++z)
          f(packCell(x, y, z));
  }

  template <typename Visit>
  void
  visitLarge(const Box& query, Visit& visit) const
  {
    // Every query meets the large ones: their boxes are kept in a flat array.
    for (std::size_t k = 0; k < large_.size(); ++k)
      if (!boxesApart(large_boxes_[k], query))
        visit(large_[k]);
  }

  double cell_;
  std::unordered_map<CellKey, std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> large_; // entries over more than kMostCells cells
  std::vector<Box> large_boxes_;     // their boxes, in the same order
};

} // namespace detail
} // namespace cocone
} // namespace pcl
