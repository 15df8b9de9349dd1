// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the CGAL types behind VoronoiCocone and the per-sample Voronoi geometry
// shared by the first computation and by decimation. Never installed.
#pragma once

#include "common/parallel.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>


#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

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
  VoronoiCellBase(Vertex_handle v0, Vertex_handle v1, Vertex_handle v2, Vertex_handle v3)
  : Cb(v0, v1, v2, v3)
  {}
  VoronoiCellBase(Vertex_handle v0,
                  Vertex_handle v1,
                  Vertex_handle v2,
                  Vertex_handle v3,
                  Cell_handle n0,
                  Cell_handle n1,
                  Cell_handle n2,
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
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using VertexHandle = Delaunay::Vertex_handle;
using CellHandle = Delaunay::Cell_handle;


inline Eigen::Vector3d
toEigen(const Point& p)
{
  return {p.x(), p.y(), p.z()};
}

/** Marks on samples that clear() forgets in O(1) (a round number per sample), so that
 * repeats and membership are decided without sorting or searching. Grows to the
 * largest sample marked; meant to be kept per thread and reused. */
class SampleMarks
{
public:
  /** Starts a new round, with nothing marked. */
  void
  clear()
  {
    if (++round_ == 0) { // wrapped: forget every earlier round
      std::fill(round_of_.begin(), round_of_.end(), 0);
      round_ = 1;
    }
  }

  /** Marks s; false if it was marked already in this round. */
  bool
  mark(SampleIndex s)
  {
    if (s >= round_of_.size())
      round_of_.resize(std::max<std::size_t>(s + 1, 2 * round_of_.size()), 0);
    return std::exchange(round_of_[s], round_) != round_;
  }

  bool
  isMarked(SampleIndex s) const
  {
    return s < round_of_.size() && round_of_[s] == round_;
  }

private:
  std::vector<std::uint32_t> round_of_;
  std::uint32_t round_ = 1;
};

/** The Delaunay triangulation as VoronoiCocone keeps it once the per-sample geometry is
 * done: the samples of every cell and the star of every sample, in flat arrays. It
 * answers the neighbour queries of stitching and decimation in 32 bytes per cell, where
 * CGAL's triangulation, which is freed, takes about 80 (a 72-byte cell, and a 48-byte
 * vertex per 6 or 7 cells). */
struct DelaunayStars
{
  /** Per cell, its four samples; kNoSample stands for the infinite vertex. */
  std::vector<std::array<SampleIndex, 4> > cell_samples;
  /** CSR by sample: the cells incident to sample s are cells[offsets[s]] to
   * cells[offsets[s + 1] - 1], ascending; empty for duplicates. */
  std::vector<std::uint32_t> offsets, cells;

  bool
  empty() const
  {
    return offsets.empty();
  }

  /** Appends the finite Delaunay neighbours of sample \a s (a representative) to
   * \a out, each once, unsorted; \a seen is scratch. */
  void
  appendNeighbours(SampleIndex s, SampleMarks& seen, std::vector<SampleIndex>& out) const
  {
    seen.clear();
    for (std::uint32_t k = offsets[s]; k < offsets[s + 1]; ++k)
      for (const SampleIndex w : cell_samples[cells[k]])
        if (w != s && w != kNoSample && seen.mark(w))
          out.push_back(w);
  }

  void
  clear()
  {
    std::vector<std::array<SampleIndex, 4> >().swap(cell_samples);
    std::vector<std::uint32_t>().swap(offsets);
    std::vector<std::uint32_t>().swap(cells);
  }
};

/** Classification of a point relative to the double cone of a cocone. */
enum class ConeSide
{
  upper,  // cos(angle(x, v)) > sin(theta)
  inside, // |cos| <= sin(theta): in the cocone
  lower   // cos < -sin(theta)
};

/** How a Voronoi edge (segment or ray, relative to the sample) meets a cocone. */
struct EdgeInCocone
{
  bool meets = false;      // some point of the edge lies in the cocone
  bool unbounded = false;  // the ray's direction lies in the cocone: r_p is infinite
  double max_distance2 = 0; // largest squared distance from p of a point inside
};

/** Clips the Voronoi edge start + t * direction (t in [0, 1] for a segment, t >= 0 for a
 * ray), given relative to the sample, against the cocone of axis \a axis (unit) and
 * angle theta (sin_theta = sin(theta)). */
EdgeInCocone
clipVoronoiEdge(const Eigen::Vector3d& start,
                const Eigen::Vector3d& direction,
                bool is_ray,
                const Eigen::Vector3d& axis,
                double sin_theta);

} // namespace detail

/** The state behind VoronoiCocone; shared with decimation.cpp. Per-sample arrays are
 * indexed by input index and filled for representatives only. */
struct VoronoiCocone::Impl
{
  Status status = Status::not_computed;
  VoronoiCocone::Timings timings;
  std::string message;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centered;
  std::vector<SampleIndex> representative;
  detail::DelaunayStars stars; // after compute(); cleared by decimate()
  std::size_t unique_count = 0;

  std::vector<Eigen::Vector3d> pole_vector;
  std::vector<Eigen::Vector3d> positive_pole; // centered frame
  std::vector<Eigen::Vector3d> negative_pole; // centered frame
  std::vector<double> height;                 // NaN: no negative pole
  std::vector<double> radius;                 // +inf: unbounded cocone
  std::vector<std::uint8_t> unbounded;

  std::vector<MarkedTriangle> triangles;
  std::vector<std::uint32_t> triangle_offsets; // CSR by sample, size n + 1
  std::vector<std::uint32_t> triangle_ids;

  double
  ratio(SampleIndex i) const
  {
    const double h = height[i];
    const double r = radius[i];
    if (!(h > 0) || !std::isfinite(r))
      return std::numeric_limits<double>::infinity();
    return r / h;
  }
};

} // namespace cocone
} // namespace pcl
