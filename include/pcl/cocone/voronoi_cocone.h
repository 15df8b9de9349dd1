// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The Voronoi/cocone core shared by BoundarySampleEstimation, CoconeReconstruction and
 * VoronoiDecimation. It is compiled once into the library; CGAL stays behind its
 * private implementation, so this header needs only Eigen and the standard library.
 */
#pragma once

#include <pcl/cocone/export.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Index of a sample: its position in the point array given to
 * VoronoiCocone::compute. */
using SampleIndex = std::uint32_t;

/** \brief Marks "no sample" wherever a SampleIndex is expected. */
constexpr SampleIndex kNoSample = std::numeric_limits<SampleIndex>::max();

/** \brief Outcome of a core computation. Every failure comes with a one-line message
 * (VoronoiCocone::errorMessage); no exception crosses the core's boundary. */
enum class Status
{
  ok,                   ///< the diagram was built
  not_computed,         ///< compute() has not run (or failed) yet
  too_few_points,       ///< fewer than 4 distinct points
  non_finite_input,     ///< a coordinate is NaN or infinite
  degenerate_dimension, ///< all points are coplanar or collinear: there is no 3D cell
  too_many_points,      ///< more points than a SampleIndex can address
  invalid_parameter,    ///< a parameter is outside its documented range
  internal_error        ///< CGAL reported a failure or memory ran out
};

/** \brief Human-readable name of a status, e.g. "degenerate_dimension". */
PCL_COCONE_EXPORT const char*
toString(Status status);

/** \brief A Delaunay triangle whose dual Voronoi edge meets the cocone of at least one
 * of its vertices.
 *
 * Bit k of \a marked_by is set when the cocone of vertex[k] meets the Voronoi edge dual
 * to the triangle (paper: the triangle is among CANDIDATETRIANGLES(vertex[k])). The
 * vertices are representative sample indices, in no particular order. */
struct MarkedTriangle
{
  std::array<SampleIndex, 3> vertex;
  std::uint8_t marked_by;

  /** \brief True when vertex[k] marks the triangle. */
  bool
  isMarkedBy(int k) const
  {
    return (marked_by >> k) & 1u;
  }
};

/** \brief A read-only view of a contiguous run of indices. */
struct IndexRange
{
  const std::uint32_t* first = nullptr;
  const std::uint32_t* last = nullptr;
  const std::uint32_t*
  begin() const
  {
    return first;
  }
  const std::uint32_t*
  end() const
  {
    return last;
  }
  std::size_t
  size() const
  {
    return static_cast<std::size_t>(last - first);
  }
  bool
  empty() const
  {
    return first == last;
  }
};

/** \brief Result of DECIMATE: for every sample, the ratio bound from which on it is
 * removed.
 *
 * Sample i is kept by DECIMATE(P, rho) exactly when `level[i] >= rho`. Removed
 * duplicates get level 0. The levels nest: the set kept at a larger rho is a subset of
 * the set kept at a smaller one, and each is exactly what a separate run at that rho
 * returns (the removal order is the same prefix). Samples never removed get +infinity.
 */
struct DecimationLevels
{
  std::vector<double> level;     ///< one entry per input sample
  double largest_ratio_bound = 0; ///< the rho the run went up to
  std::size_t removals = 0;       ///< Delaunay vertex removals performed
};

/** \brief Voronoi cell geometry of a point sample: one 3D Delaunay triangulation, and per
 * sample its poles, pole vector, height, cocone radius and the Delaunay triangles its
 * cocone marks.
 *
 * Definitions (Dey et al. 2001, section 2; Amenta, Choi, Dey, Leekha 2000):
 * - positive pole p+: the Voronoi vertex of the cell V_p farthest from p; at infinity
 *   when V_p is unbounded (p on the convex hull);
 * - pole vector v_p: unit vector along p+ - p; for an unbounded cell, the average of the
 *   outward normals of the convex-hull triangles at p;
 * - negative pole p-: the Voronoi vertex of V_p farthest from p with (p- - p).v_p < 0;
 * - height h_p = |p- - p|: an estimate of the local feature size;
 * - cocone C_p: the points y of V_p with |cos angle(y - p, v_p)| <= sin(theta);
 * - cocone radius r_p: the largest distance from p to a point of a Voronoi edge of V_p
 *   inside C_p (infinite when an unbounded Voronoi edge runs inside the cocone);
 * - ratio r_p / h_p: small where the cell is long and thin (well or over-sampled),
 *   large near undersampling.
 *
 * Exact predicates, inexact constructions; the points are translated to their centroid
 * before insertion, so large coordinates (UTM) keep their precision. Exact duplicates
 * are inserted once; every input point keeps an entry and reads the values of its
 * representative (the smallest index among identical points). Per-sample work runs in
 * parallel (TBB).
 *
 * Index space: every SampleIndex is a position in the array given to compute().
 */
class PCL_COCONE_EXPORT VoronoiCocone
{
public:
  VoronoiCocone();
  ~VoronoiCocone();
  VoronoiCocone(VoronoiCocone&&) noexcept;
  VoronoiCocone&
  operator=(VoronoiCocone&&) noexcept;
  VoronoiCocone(const VoronoiCocone&) = delete;
  VoronoiCocone&
  operator=(const VoronoiCocone&) = delete;

  /** \brief Cocone angle theta in radians. Default pi/8; valid range (0, pi/2). */
  Status
  setCoconeAngle(double theta);
  double
  getCoconeAngle() const;

  /** \brief Number of worker threads; 0 (default) lets TBB use every core. */
  void
  setNumberOfThreads(unsigned threads);
  unsigned
  getNumberOfThreads() const;

  /** \brief Builds the Delaunay triangulation of \a points and the per-sample geometry.
   * \param[in] points the samples (any coordinates; no NaN or infinity)
   * \return Status::ok, or the reason nothing was built (see errorMessage()). */
  Status
  compute(const std::vector<Eigen::Vector3d>& points);

  /** \brief Wall-clock seconds of the stages of the last compute(). */
  struct Timings
  {
    double delaunay = 0; ///< triangulation, duplicates included
    double geometry = 0; ///< circumcenters, poles, radii, marks, incidence lists
  };
  const Timings&
  timings() const;

  /** \brief Status of the last compute() (decimate() returns its own). */
  Status
  status() const;

  /** \brief One-line explanation of the last failure; empty after success. */
  const std::string&
  errorMessage() const;

  /** \brief Number of samples given to compute(), duplicates included. */
  std::size_t
  size() const;

  /** \brief Number of distinct samples (Delaunay vertices). */
  std::size_t
  numUniqueSamples() const;

  /** \brief The smallest index whose point is identical to sample i (i itself unless i
   * duplicates an earlier point). */
  SampleIndex
  representative(SampleIndex i) const;

  /** \brief The samples translated to their centroid (the frame CGAL works in). */
  const std::vector<Eigen::Vector3d>&
  centeredPoints() const;

  /** \brief The translation applied: sample = centered point + offset(). */
  const Eigen::Vector3d&
  offset() const;

  /** \brief Unit pole vector v_p of sample i (oriented towards the positive pole). */
  const Eigen::Vector3d&
  poleVector(SampleIndex i) const;

  /** \brief True when V_p is unbounded (p lies on the convex hull), so p+ is at
   * infinity. */
  bool
  positivePoleAtInfinity(SampleIndex i) const;

  /** \brief Positive pole in input coordinates; all components +infinity when it lies
   * at infinity. */
  Eigen::Vector3d
  positivePole(SampleIndex i) const;

  /** \brief Negative pole in input coordinates; NaN when V_p has no Voronoi vertex on
   * the negative side of v_p. */
  Eigen::Vector3d
  negativePole(SampleIndex i) const;

  /** \brief Height h_p = |p- - p| in input units; NaN when there is no negative pole. */
  double
  height(SampleIndex i) const;

  /** \brief Cocone radius r_p in input units; +infinity for an unbounded cocone. */
  double
  coconeRadius(SampleIndex i) const;

  /** \brief r_p / h_p; +infinity when h_p is undefined or r_p infinite. */
  double
  ratio(SampleIndex i) const;

  /** \brief The Delaunay triangles marked by the cocone of at least one vertex. */
  const std::vector<MarkedTriangle>&
  markedTriangles() const;

  /** \brief Indices into markedTriangles() of the triangles incident to sample i
   * (marked by i or by another vertex). Duplicates read their representative's. */
  IndexRange
  trianglesAround(SampleIndex i) const;

  /** \brief Cocone neighbours N_p of sample i: the samples whose Voronoi cell meets
   * C_p, i.e. the other vertices of the triangles that i marks. Sorted, without
   * duplicates, representatives only. */
  void
  coconeNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const;

  /** \brief The samples sharing a Delaunay edge with sample i (representatives only). */
  void
  delaunayNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const;

  /** \brief Every finite Delaunay triangle whose three vertices all lie in \a samples
   * (representative indices). Each triangle is reported once, vertices ascending. */
  void
  delaunayTrianglesAmong(const std::vector<SampleIndex>& samples,
                         std::vector<std::array<SampleIndex, 3>>& triangles) const;

  /** \brief Runs DECIMATE (paper section 4) up to the ratio bound \a rho.
   *
   * Heights and pole vectors stay those of the full sample; cocone radii are updated
   * only for the samples whose Voronoi cell a removal changed; the sample with the
   * smallest ratio goes first (ties by index), and the triangulation is updated in
   * place. The triangulation is consumed: afterwards only the per-sample values of the
   * full sample, and \a levels, remain meaningful (markedTriangles() is cleared).
   * \param[in] rho the largest ratio bound of interest, > 0
   * \param[out] levels per-sample removal levels (see DecimationLevels)
   * \param[in] progress optional callback, called with the share done in [0, 1];
   *            returning false cancels (Status::internal_error, "cancelled"). */
  Status
  decimate(double rho,
           DecimationLevels& levels,
           const std::function<bool(double)>& progress = nullptr);

  /** \brief Opaque implementation (CGAL lives there). */
  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
  double cocone_angle_;
  unsigned threads_ = 0;
};

} // namespace cocone
} // namespace pcl
