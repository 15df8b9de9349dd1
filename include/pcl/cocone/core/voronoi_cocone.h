// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API: the Voronoi/cocone core shared by BoundarySampleEstimation,
 * CoconeReconstruction and VoronoiDecimation, and by every other front end. Most users
 * want the three classes (pcl/cocone/boundary_sample_estimation.h,
 * cocone_reconstruction.h, voronoi_decimation.h); the headers under pcl/cocone/core/
 * are for those who work on samples without a PCL cloud, or build on the diagram
 * itself. Every index here is a sample index (a position in the array given to
 * compute()), never a cloud index. The core is compiled once into the library; CGAL
 * stays behind its private implementation, so these headers need only Eigen and the
 * standard library.
 *
 * Stages, one header each: the diagram (this header), BOUNDARY (boundary_samples.h),
 * the reconstruction (reconstruction.h), DECIMATE (decimation.h); mesh checks
 * (mesh_topology.h, mesh_geometry.h); the outcome of every entry (status.h).
 */
#pragma once

#include <pcl/cocone/core/denoise.h>
#include <pcl/cocone/core/status.h>
#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>

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
/** \brief The non-template core of pcl_cocone (Voronoi geometry, BOUNDARY, COCONE
 * meshing, DECIMATE) and its helpers (parameters, mesh checks, file formats). */
namespace cocone {

namespace detail {
struct VoronoiCoconeAccess;
} // namespace detail

/** \brief Index of a sample: its position in the point array given to
 * VoronoiCocone::compute. */
using SampleIndex = std::uint32_t;

/** \brief Marks "no sample" wherever a SampleIndex is expected. */
constexpr SampleIndex kNoSample = std::numeric_limits<SampleIndex>::max();

/** \brief A Delaunay triangle whose dual Voronoi edge meets the cocone of at least one
 * of its vertices.
 *
 * Bit k of \a marked_by is set when the cocone of vertex[k] meets the Voronoi edge dual
 * to the triangle (paper: the triangle is among CANDIDATETRIANGLES(vertex[k])). The
 * vertices are representative sample indices, in no particular order. */
struct MarkedTriangle
{
  std::array<SampleIndex, 3> vertex; ///< the three vertices (representative samples)
  std::uint8_t marked_by;            ///< bit k set: vertex[k]'s cocone marks it

  /** \brief Whether the cocone of vertex[k] marks the triangle.
   * \param[in] k position in #vertex, 0 to 2 (not a sample index)
   * \return true when bit \a k of #marked_by is set */
  bool
  isMarkedBy(int k) const
  {
    return (marked_by >> k) & 1u;
  }
};

/** \brief A read-only view of a contiguous run of indices, usable in a range-based
 * for loop. The index space is the producer's (VoronoiCocone::trianglesAround:
 * positions in VoronoiCocone::markedTriangles()). The view points into the
 * VoronoiCocone: it is valid until the next compute(), until decimate() consumes the
 * object, or until the object's destruction. */
struct IndexRange
{
  const std::uint32_t* first = nullptr; ///< the first index; null for an empty default
  const std::uint32_t* last = nullptr;  ///< one past the last index
  /** \brief Start of the run.
   * \return #first */
  const std::uint32_t*
  begin() const
  {
    return first;
  }
  /** \brief End of the run.
   * \return #last (one past the last index) */
  const std::uint32_t*
  end() const
  {
    return last;
  }
  /** \brief Length of the run.
   * \return the number of indices, last - first */
  std::size_t
  size() const
  {
    return static_cast<std::size_t>(last - first);
  }
  /** \brief Whether the run is empty.
   * \return true when there is no index */
  bool
  empty() const
  {
    return first == last;
  }
};

/** \brief Voronoi cell geometry of a point sample: one 3D Delaunay triangulation, and
 * per sample its poles, pole vector, height, cocone radius and the Delaunay triangles
 * its cocone marks.
 *
 * Definitions (Dey et al. 2001, section 2; Amenta, Choi, Dey, Leekha 2000):
 * - positive pole p+: the Voronoi vertex of the cell V_p farthest from p; at infinity
 *   when V_p is unbounded (p on the convex hull);
 * - pole vector v_p: unit vector along p+ - p; for an unbounded cell, the average of
 * the outward normals of the convex-hull triangles at p;
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
 * Memory: once the per-sample geometry is computed, the object keeps the triangulation
 * as flat arrays (the samples of each cell, the cells of each sample: 32 bytes per
 * cell) for delaunayNeighbours(), delaunayTrianglesAmong() and decimate()
 * (decimation.h), and frees
 * CGAL's own, which takes about 80 bytes per cell. Surface samples have 5 to 9 cells
 * per point (the benchmark's shapes and scans); samples lying almost exactly on an
 * analytic surface, up to 20.
 *
 * Index space: every SampleIndex is a position in the array given to compute().
 */
class PCL_COCONE_EXPORT VoronoiCocone
{
public:
  /** \brief An empty object: status() is Status::not_computed and size() is 0.
   * \param[in] parameters the cocone angle and the number of threads (defaults: pi/8,
   *            automatic); compute() refuses an out-of-range cocone angle with
   *            Status::invalid_parameter */
  explicit VoronoiCocone(const VoronoiParameters& parameters = VoronoiParameters());
  /** \brief Releases the triangulation. */
  ~VoronoiCocone();
  /** \brief Takes over the triangulation and results of the moved-from object, which
   * may afterwards only be assigned to or destroyed. */
  VoronoiCocone(VoronoiCocone&&) noexcept;
  /** \brief Takes over the triangulation and results of the moved-from object, which
   * may afterwards only be assigned to or destroyed.
   * \return *this */
  VoronoiCocone& operator=(VoronoiCocone&&) noexcept;
  /** \brief Not copyable (the object owns a triangulation); move it instead. */
  VoronoiCocone(const VoronoiCocone&) = delete;
  /** \brief Not copyable (the object owns a triangulation); move it instead. */
  VoronoiCocone& operator=(const VoronoiCocone&) = delete;

  /** \brief Set theta, the cocone angle: the cocone of p is the part of its Voronoi
   * cell within theta of the plane orthogonal to the pole vector. Radians; default
   * pi/8; valid range (0, pi/2) (kCoconeAngleRange). Used by the next compute() and by
   * decimate().
   * \param[in] theta the cocone angle in radians
   * \return Status::ok, or Status::invalid_parameter (and the angle is unchanged) when
   *         \a theta is outside (0, pi/2); no message is printed */
  Status setCoconeAngle(double theta);
  /** \brief Get theta, the cocone angle (see setCoconeAngle).
   * \return the cocone angle in radians, in (0, pi/2) */
  double getCoconeAngle() const;

  /** \brief Set the number of worker threads of compute(), and of decimate() on this
   * object.
   * \param[in] threads number of threads; 0 (default) lets TBB use every core; any
   *            value is accepted */
  void setNumberOfThreads(unsigned threads);
  /** \brief Get the number of worker threads (see setNumberOfThreads).
   * \return the number of threads; 0 means automatic (every core) */
  unsigned getNumberOfThreads() const;

  /** \brief Builds the Delaunay triangulation of \a points and the per-sample geometry.
   * Replaces the results of any earlier compute() (also when it fails).
   * \param[in] points the samples (any coordinates, in input units; no NaN or
   *            infinity); the position of a point in this array is its SampleIndex
   * \param[in] progress optional: called from this thread with the share done, every
   *            65536 insertions and at the end; returning false cancels
   *            (Status::internal_error, errorMessage() "cancelled")
   * \return Status::ok, or the reason nothing was built (see errorMessage()):
   *         Status::invalid_parameter (the cocone angle, or a tile exchange whose rank
   *         is not below its size), Status::too_many_points,
   *         Status::non_finite_input, Status::too_few_points,
   *         Status::degenerate_dimension or Status::internal_error (also when
   *         another process of a tile exchange failed, with its reason). With a tile
   *         exchange (VoronoiParameters::exchange), a process other than the root
   *         returns Status::not_computed once it has sent its tiles; timings() of the
   *         root then count only the tiles it built itself. */
  Status compute(const std::vector<Eigen::Vector3d>& points,
                 const ProgressCallback& progress = nullptr);

  /** \brief Wall-clock seconds of the stages of the last compute(). */
  struct Timings
  {
    double denoise = 0;  ///< noise estimate and smoothing (0 when denoising is off)
    double delaunay = 0; ///< triangulation, duplicates included
    double geometry = 0; ///< circumcenters, poles, radii, marks, incidence lists
    /** Tiles the diagram was built in (VoronoiParameters::tiles): 1 when untiled,
     * also when a tiled build fell back to one tile. With tiles, #delaunay and
     * #geometry share the wall time of the tile phase in proportion to the time each
     * took summed over the tiles; the join of the tiles counts to #geometry. */
    unsigned tiles = 0;
    /** Samples triangulated summed over the tiles, over the distinct samples: 1
     * untiled; the share of halo samples on top of it. */
    double triangulated_share = 0;
  };
  /** \brief Durations of the last compute().
   * \return the stages' wall-clock times in seconds; all 0 before compute() or after a
   *         failed one */
  const Timings& timings() const;

  /** \brief Whether the diagram can be used.
   * \return Status::ok after a successful compute(); Status::not_computed before any,
   *         and after decimate() consumed the object (whether it succeeded, failed or
   *         was cancelled); otherwise the reason the last compute() failed */
  Status status() const;

  /** \brief Explanation of the last failure of compute().
   * \return one line, e.g. "all points are coplanar: no 3D Voronoi cell to measure";
   *         empty after success */
  const std::string& errorMessage() const;

  /** \brief Number of samples given to compute(), duplicates included.
   * \return the size of the array given to the last successful compute(): the valid
   *         sample indices are 0 to size() - 1; 0 before compute() or after a
   *         failure */
  std::size_t size() const;

  /** \brief Number of distinct samples (Delaunay vertices).
   * \return the number of distinct points, at most size(); 0 before compute() or after
   *         a failure */
  std::size_t numUniqueSamples() const;

  /** \brief The representative of a sample: the smallest index whose point is
   * identical to sample \a i.
   * \param[in] i a sample index, < size()
   * \return a sample index: \a i itself unless \a i duplicates an earlier point */
  SampleIndex representative(SampleIndex i) const;

  /** \brief The typical sample spacing: the median distance from a sample to its
   * nearest other sample (through the Delaunay edges), over up to 1024 distinct samples
   * spread evenly over the index range. Deterministic.
   * \return the spacing in input units; 0 before compute() */
  double typicalSpacing() const;

  /** \brief The samples translated to their centroid (the frame CGAL works in).
   * \return one point per sample (indexed by SampleIndex, duplicates included), in
   *         input units: sample i = centeredPoints()[i] + offset(), or its smoothed
   *         copy when denoised() (then see centeredInputPoints()) */
  const std::vector<Eigen::Vector3d>& centeredPoints() const;

  /** \brief The samples as given to compute(), translated by offset(): the same as
   * centeredPoints() unless the diagram was built on a smoothed copy (denoised()).
   * \return one point per sample (indexed by SampleIndex, duplicates included), in
   *         input units */
  const std::vector<Eigen::Vector3d>& centeredInputPoints() const;

  /** \brief Whether the last compute() built the diagram on a smoothed copy of the
   * samples (VoronoiParameters::denoise, core/denoise.h): then centeredPoints(), the
   * poles and every other position it hands out are those of the copy, and
   * centeredInputPoints() holds the samples as given.
   * \return true when the diagram is that of the smoothed copy */
  bool denoised() const;

  /** \brief The noise the last compute() measured (estimateNoise).
   * \return the estimate; relative_noise 0 when denoising is off or nothing could be
   *         measured */
  const NoiseEstimate& noiseEstimate() const;

  /** \brief The smoothing rounds the last compute() ran (SmoothedSamples::rounds).
   * \return 0 unless denoised() */
  unsigned smoothingRounds() const;

  /** \brief Set whether the next compute() builds the diagram on a smoothed copy of
   * the samples (see VoronoiParameters::denoise).
   * \param[in] mode DenoiseMode::automatic (default), on or off */
  void setDenoise(DenoiseMode mode);
  /** \brief Get the denoising mode (see setDenoise).
   * \return the mode */
  DenoiseMode getDenoise() const;

  /** \brief The translation applied: sample = centered point + offset().
   * \return the centroid of the samples (duplicates included), in input units; zero
   *         before compute() */
  const Eigen::Vector3d& offset() const;

  /** \brief Pole vector v_p of a sample.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the unit pole vector, oriented towards the positive pole (for an unbounded
   *         cell: the normalized sum of the outward normals of the convex-hull
   *         triangles at p) */
  const Eigen::Vector3d& poleVector(SampleIndex i) const;

  /** \brief Whether the positive pole of a sample lies at infinity.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return true when V_p is unbounded (p lies on the convex hull), so p+ is at
   *         infinity */
  bool positivePoleAtInfinity(SampleIndex i) const;

  /** \brief Positive pole p+ of a sample.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the pole in input coordinates; all components +infinity when it lies at
   *         infinity */
  Eigen::Vector3d positivePole(SampleIndex i) const;

  /** \brief Negative pole p- of a sample.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the pole in input coordinates; all components NaN when V_p has no Voronoi
   *         vertex on the negative side of v_p */
  Eigen::Vector3d negativePole(SampleIndex i) const;

  /** \brief Height h_p = |p- - p| of a sample, an estimate of the local feature size.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the height in input units, > 0; NaN when there is no negative pole */
  double height(SampleIndex i) const;

  /** \brief Cocone radius r_p of a sample, as computed by compute().
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the radius in input units, >= 0; +infinity for an unbounded cocone */
  double coconeRadius(SampleIndex i) const;

  /** \brief Ratio r_p / h_p of a sample (see coconeRadius and height).
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \return the ratio, dimensionless, >= 0; +infinity when h_p is undefined or r_p
   *         infinite */
  double ratio(SampleIndex i) const;

  /** \brief The Delaunay triangles marked by the cocone of at least one vertex.
   * \return the marked triangles (vertices are representative sample indices); empty
   *         before compute() */
  const std::vector<MarkedTriangle>& markedTriangles() const;

  /** \brief The marked triangles incident to a sample (marked by it or by another
   * vertex). Duplicates read their representative's.
   * \param[in] i a sample index, < size()
   * \return indices into markedTriangles() (not sample indices); empty before
   *         compute() */
  IndexRange trianglesAround(SampleIndex i) const;

  /** \brief Cocone neighbours N_p of sample i: the samples whose Voronoi cell meets
   * C_p, i.e. the other vertices of the triangles that i marks.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \param[out] neighbours representative sample indices, sorted, without repeats
   *             (cleared first) */
  void coconeNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const;

  /** \brief The samples sharing a finite Delaunay edge with sample i. Safe to call
   * from several threads at once.
   * \param[in] i a sample index, < size() (a duplicate reads its representative's)
   * \param[out] neighbours representative sample indices, sorted (cleared first); empty
   *             before compute() */
  void delaunayNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const;

  /** \brief Every finite Delaunay triangle whose three vertices all lie in \a samples.
   * \param[in] samples sample indices, each < size(), in any order; duplicates stand
   *            for their representatives
   * \param[out] triangles the triangles as representative sample indices, ascending
   *             within each triangle, each triangle reported once, sorted (cleared
   *             first); empty before compute() */
  void delaunayTrianglesAmong(const std::vector<SampleIndex>& samples,
                              std::vector<std::array<SampleIndex, 3>>& triangles) const;

private:
  // The state lives behind the pointer, with CGAL's types in the library only. The
  // core's own algorithms (decimation, which consumes the diagram) reach it through
  // detail::VoronoiCoconeAccess, defined under src/.
  struct Impl;
  friend struct detail::VoronoiCoconeAccess;
  std::unique_ptr<Impl> impl_;
  VoronoiParameters parameters_;
};

/** \brief An order of \a points along a Z-order (Morton) curve over their bounding box.
 *
 * Every per-sample array of the core is indexed by SampleIndex, and the Delaunay cells
 * are stored roughly in space order; samples given in random order (blue noise, merged
 * or shuffled clouds) make every stage jump through memory. Giving
 * VoronoiCocone::compute the points in this order took the reconstruction of a 1M-point
 * blue-noise hemisphere from 15.2 to 12.0 s (docs/performance.md); inputs already in a
 * spatially coherent order (scans, parametric grids) neither gain nor lose. The PCL
 * classes do it (gatherFiniteSamples) and map every result back to the cloud's indices,
 * so their results depend on the points, not on their order in the cloud.
 *
 * Deterministic, and stable: points in the same cell of the 2^21-per-axis grid keep
 * their relative order, so of identical points the first stays first (and stays the
 * representative of its group). Non-finite points go last, in their order.
 * \param[in] points the points, in any order
 * \param[in] threads worker threads (0: every core)
 * \return a permutation of 0 to points.size() - 1: entry k is the position in \a points
 *         of the k-th point along the curve; empty when there are kNoSample points or
 *         more (more than a SampleIndex addresses: compute() refuses them too) */
PCL_COCONE_EXPORT std::vector<SampleIndex>
spatialOrder(const std::vector<Eigen::Vector3d>& points, unsigned threads = 0);

} // namespace cocone
} // namespace pcl
