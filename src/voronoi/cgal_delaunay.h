// SPDX-License-Identifier: GPL-3.0-or-later
// Private: CGAL's Delaunay triangulation as the core uses it, with a sample index on
// every vertex and a cell number on every cell. The only header that includes CGAL's
// triangulation; included by the files that build one (the diagram and the
// relaxation's generators). Never installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>

#include <Eigen/Core>

#include <cstdint>
#include <limits>

namespace pcl {
namespace cocone {
namespace detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<SampleIndex, Kernel>;

constexpr std::uint32_t kNoCellIndex = std::numeric_limits<std::uint32_t>::max();

/** A Delaunay cell with an index for per-cell arrays (kNoCellIndex until numbered).
 * Circumcenters live in such an array rather than in the cell: a smaller cell makes
 * the triangulation itself faster, and the centers are needed only after it. */
template <typename GT, typename Cb = CGAL::Delaunay_triangulation_cell_base_3<GT>>
class VoronoiCellBase : public Cb
{
public:
  using Vertex_handle = typename Cb::Vertex_handle;
  using Cell_handle = typename Cb::Cell_handle;

  template <typename TDS2>
  struct Rebind_TDS
  {
    using Cb2 = typename Cb::template Rebind_TDS<TDS2>::Other;
    using Other = VoronoiCellBase<GT, Cb2>;
  };

  VoronoiCellBase() : Cb() {}
  VoronoiCellBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2,
                  Vertex_handle v3)
    : Cb(v0, v1, v2, v3)
  {}
  VoronoiCellBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2,
                  Vertex_handle v3, Cell_handle n0, Cell_handle n1, Cell_handle n2,
                  Cell_handle n3)
    : Cb(v0, v1, v2, v3, n0, n1, n2, n3)
  {}

  /** Index into per-cell arrays; kNoCellIndex when the cell has none. */
  std::uint32_t&
  cellIndex()
  {
    return index_;
  }
  std::uint32_t
  cellIndex() const
  {
    return index_;
  }

private:
  std::uint32_t index_ = kNoCellIndex;
};

using CellBase = VoronoiCellBase<Kernel>;
/** A triangulation filled by one thread (decimation's relaxation): CGAL's sequential
 * data structure, faster than the concurrent one on one core. */
using SequentialDelaunay = CGAL::Delaunay_triangulation_3<
    Kernel, CGAL::Triangulation_data_structure_3<VertexBase, CellBase>>;
/** CGAL's concurrent triangulation: with a lock grid, points go in on every core
 * (tiled_delaunay.cpp, insertSamples).
 * Its cells come out in an order that depends on the thread schedule, but the cells
 * themselves do not (the triangulation of a point set is unique, degenerate cases
 * decided by symbolic perturbation), and nothing read from it depends on their order
 * (cell_geometry.h). */
using Tds =
    CGAL::Triangulation_data_structure_3<VertexBase, CellBase, CGAL::Parallel_tag>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
/** The locks of the concurrent insertion: a grid over the points' box. */
using DelaunayLocks = Delaunay::Lock_data_structure;
using VertexHandle = Delaunay::Vertex_handle;
using CellHandle = Delaunay::Cell_handle;

inline Eigen::Vector3d
toEigen(const Point& p)
{
  return {p.x(), p.y(), p.z()};
}

} // namespace detail
} // namespace cocone
} // namespace pcl
