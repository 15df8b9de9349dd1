// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * pcl::CoconeReconstruction: COCONE with boundary detection as a pcl::MeshConstruction.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>
#include <pcl/cocone/reconstruction_statistics.h>
#include <pcl/surface/reconstruction.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pcl {

/** \brief COCONE surface reconstruction with boundaries, after Dey, Giesen, Goswami,
 * Hudson, Wenger and Zhao, "Undersampling and Oversampling in Sample Based Shape
 * Modeling", IEEE Visualization 2001 (section 3.4), on the COCONE algorithm of Amenta,
 * Choi, Dey and Leekha (2000).
 *
 * The output is an oriented 2-manifold, possibly with boundary, whose vertices are the
 * input samples:
 * 1. BOUNDARY (see BoundarySampleEstimation) finds the samples near undersampling;
 * 2. each other sample chooses the Delaunay triangles whose dual Voronoi edge crosses
 *    its cocone; a triangle is a candidate when every non-boundary vertex chooses it;
 * 3. candidates covering a hole too large against the sample spacing are dropped, and
 *    triangles at sharp folds or dangling at bare edges are pruned (never those of a
 *    boundary sample, never those a flat sheet holds, so small gaps cannot cascade);
 * 4. a walk over the outer side of the candidates extracts the manifold, refusing a
 *    third triangle on an edge, a second fan at a vertex and any step that would turn
 *    the surface over (noisy scans otherwise come out partly upside down, with cracks
 *    where the two orientations meet); closed components face outward;
 * 5. the holes left are stitched with Delaunay triangles (or, for a few vertices, the
 *    least-area triangulation of the hole), unless a hole is a true boundary: larger
 *    than the true-boundary ratio in sample spacings;
 * 6. samples left out that lie on the surface are put back into the mesh, and
 *    triangles crossing another one are removed (their holes stitched again).
 *
 * No k-d tree and no normals are needed. Works for closed surfaces, surfaces with
 * boundaries (partial scans, terrain) and sharp features.
 *
 * Index spaces and special points:
 * - polygon vertex ids index the input cloud (also with setIndices, which selects the
 *   samples to reconstruct from); reconstruct(PolygonMesh&) copies the whole input
 *   cloud into the mesh, as every pcl::MeshConstruction does;
 * - points with a NaN or infinite coordinate, exact duplicates (the first of them is
 *   used) and isolated outliers end up in no triangle: getUnusedIndices() lists them;
 * - points far beyond the cloud's own scale (getFarIndices()) are left out before the
 *   diagram is built, so that they change nothing else; they are unused too, and
 *   getWarningMessage() names them;
 * - fewer than 4 distinct finite points, or all of them coplanar or collinear, have no
 *   3D Voronoi diagram: reconstruct() reports it with PCL_ERROR and returns no polygon;
 * - when memory runs out, reconstruct() returns no polygon, getErrorMessage() says so,
 *   and the diagnostics (boundary samples, loops, unused indices) are empty.
 *
 * \tparam PointInT a point type with x, y, z
 * \ingroup surface
 */
template <typename PointInT>
class CoconeReconstruction : public MeshConstruction<PointInT>
{
public:
  /** \brief Shared pointer to a CoconeReconstruction. */
  using Ptr = shared_ptr<CoconeReconstruction<PointInT>>;
  /** \brief Shared pointer to a const CoconeReconstruction. */
  using ConstPtr = shared_ptr<const CoconeReconstruction<PointInT>>;

  /** \brief Default parameters (theta pi/8, rho 0.99, alpha pi/6, true-boundary ratio
   * 2, boundary detection and hole stitching on, automatic threads); no search method
   * is needed (setSearchMethod may be skipped). */
  CoconeReconstruction() { check_tree_ = false; }

  /** \brief Set theta, the cocone angle: the cocone of p is the part of its Voronoi
   * cell within theta of the plane orthogonal to the pole vector. Radians; default pi/8
   * (the paper's value); valid range (0, pi/2). Out of range: PCL_ERROR, unchanged.
   * \param[in] theta the cocone angle in radians, in (0, pi/2) */
  void setCoconeAngle(double theta);
  /** \brief Get theta (see setCoconeAngle).
   * \return the cocone angle in radians, in (0, pi/2); default pi/8 */
  double
  getCoconeAngle() const
  {
    return voronoi_parameters_.cocone_angle;
  }

  /** \brief Set rho, BOUNDARY's ratio bound (r_p / h_p <= rho for flat samples).
   * Dimensionless; default 0.99; valid range (0, 10]. Smaller values flag more boundary
   * samples. Out of range: PCL_ERROR, unchanged.
   * \param[in] rho the ratio bound, dimensionless, in (0, 10] */
  void setRatioBound(double rho);
  /** \brief Get rho (see setRatioBound).
   * \return the ratio bound, dimensionless, in (0, 10]; default 0.99 */
  double
  getRatioBound() const
  {
    return parameters_.boundary.ratio_bound;
  }

  /** \brief Set alpha, BOUNDARY's normal agreement angle: the largest acute angle
   * between pole lines of neighbouring flat samples. Radians; default pi/6; valid range
   * (0, pi/2]. Out of range: PCL_ERROR, unchanged.
   * \param[in] alpha the normal agreement angle in radians, in (0, pi/2] */
  void setNormalAngle(double alpha);
  /** \brief Get alpha (see setNormalAngle).
   * \return the normal agreement angle in radians, in (0, pi/2]; default pi/6 */
  double
  getNormalAngle() const
  {
    return parameters_.boundary.normal_angle;
  }

  /** \brief Set the true-boundary size ratio: a hole whose size (twice its area over
   * its perimeter: the radius of a round hole) exceeds this many local sample
   * spacings is a true boundary and stays open; smaller holes are stitched. In local
   * spacings (about 1.1 sqrt(area / n) on an even sample); default 2; valid range
   * [0.5, 1000]. Raise it to close larger holes (e.g. a scan's cut), lower it to keep
   * smaller ones open. Out of range: PCL_ERROR, unchanged.
   * \param[in] ratio the size ratio, in local sample spacings, in [0.5, 1000] */
  void setTrueBoundaryRatio(double ratio);
  /** \brief Get the true-boundary size ratio (see setTrueBoundaryRatio).
   * \return the size ratio in local sample spacings, in [0.5, 1000]; default 2 */
  double
  getTrueBoundaryRatio() const
  {
    return parameters_.true_boundary_ratio;
  }

  /** \brief Detect boundary samples and let them cast no vote (default true). Off gives
   * the original COCONE, fine for densely sampled closed smooth surfaces only.
   * \param[in] enabled true to detect boundary samples (default), false for the
   *            original COCONE */
  void
  setBoundaryDetection(bool enabled)
  {
    parameters_.detect_boundary = enabled;
  }
  /** \brief Get whether boundary detection is on (see setBoundaryDetection).
   * \return true when boundary samples are detected; default true */
  bool
  getBoundaryDetection() const
  {
    return parameters_.detect_boundary;
  }

  /** \brief Close the holes that are not true boundaries (default true).
   * \param[in] enabled true to stitch holes smaller than the true-boundary ratio
   *            (default), false to leave every hole open */
  void
  setHoleStitching(bool enabled)
  {
    parameters_.stitch_holes = enabled;
  }
  /** \brief Get whether hole stitching is on (see setHoleStitching).
   * \return true when holes are stitched; default true */
  bool
  getHoleStitching() const
  {
    return parameters_.stitch_holes;
  }

  /** \brief Set a callback for the progress of reconstruct(): it is called from the
   * thread that called reconstruct() with the share of the run done (0 to 1), a few
   * times per stage; returning false cancels the run, which then fails with the message
   * "cancelled" (getErrorMessage()). The same type as cocone::ProgressCallback.
   * \param[in] callback the callback; an empty one (default) is never called */
  void
  setProgressCallback(std::function<bool(double)> callback)
  {
    progress_ = std::move(callback);
  }
  /** \brief Get the progress callback (see setProgressCallback).
   * \return the callback; empty by default */
  const std::function<bool(double)>&
  getProgressCallback() const
  {
    return progress_;
  }

  /** \brief Number of threads for the per-sample work; 0 (default) uses every core.
   * \param[in] threads the number of threads; 0 for automatic; any value is accepted */
  void
  setNumberOfThreads(unsigned threads)
  {
    voronoi_parameters_.threads = threads;
  }
  /** \brief Get the number of threads (see setNumberOfThreads).
   * \return the number of threads; 0 (default) means automatic (every core) */
  unsigned
  getNumberOfThreads() const
  {
    return voronoi_parameters_.threads;
  }

  /** \brief Whether the diagram is built on a smoothed copy of the samples, for
   * scanner noise (see cocone::VoronoiParameters::denoise and docs/noise.md): every
   * index handed out is still an input index, and every position the input's.
   * \param[in] mode cocone::DenoiseMode::automatic (default: smooth when the measured
   *            noise exceeds cocone::kNoiseThreshold), on or off; any value is valid */
  void
  setDenoise(cocone::DenoiseMode mode)
  {
    voronoi_parameters_.denoise = mode;
  }
  /** \brief Get the denoising mode (see setDenoise).
   * \return the mode; cocone::DenoiseMode::automatic by default */
  cocone::DenoiseMode
  getDenoise() const
  {
    return voronoi_parameters_.denoise;
  }

  /** \brief The number of tiles the Voronoi diagram is built in (see
   * cocone::VoronoiParameters::tiles and docs/scaling.md): the tiles run in parallel,
   * and the results are the same for any count.
   * \param[in] tiles 0 (default): automatic; 1: untiled; any value is valid */
  void
  setNumberOfTiles(unsigned tiles)
  {
    voronoi_parameters_.tiles = tiles;
  }
  /** \brief Get the number of tiles (see setNumberOfTiles).
   * \return the count; 0 means automatic */
  unsigned
  getNumberOfTiles() const
  {
    return voronoi_parameters_.tiles;
  }

  /** \brief Build the Voronoi diagram together with other processes (see
   * core/tile_exchange.h; pcl_cocone_reconstruction_mpi sets an MPI one). Every process
   * calls reconstruct() on the same cloud with the same parameters; the tiles
   * (setNumberOfTiles) are dealt out among them, so set as many tiles as processes at
   * least (the automatic count is one tile, which the root alone builds). On the root
   * (rank 0) reconstruct() gives the mesh a single process gives; on the others it
   * gives no polygon and no error (getErrorMessage() is empty unless something failed
   * there; a failure on another process fails the root's reconstruct() with its
   * reason).
   * \param[in] exchange the transport (pcl/cocone/core/tile_exchange.h); empty
   *            (default): this process alone */
  void
  setTileExchange(std::shared_ptr<cocone::TileExchange> exchange)
  {
    voronoi_parameters_.exchange = std::move(exchange);
  }
  /** \brief Get the tile exchange (see setTileExchange).
   * \return the transport; empty when this process works alone */
  const std::shared_ptr<cocone::TileExchange>&
  getTileExchange() const
  {
    return voronoi_parameters_.exchange;
  }

  /** \name Diagnostics of the last reconstruct()
   * A reconstruct() that initCompute() refuses (e.g. no input) leaves them as
   * they were. */
  /** \{ */
  /** \brief Boundary-sample flags of BOUNDARY as published: the samples that cast no
   * vote (BoundarySampleEstimation completes the rim row by default, so it may flag
   * more).
   * \return one flag per input cloud point (indexed by input cloud index, size of the
   *         input cloud): 1 for a boundary sample, 0 otherwise and for points that did
   *         not take part (not selected, not finite, or no Voronoi diagram); all 0 when
   *         boundary detection is off */
  const std::vector<std::uint8_t>&
  getBoundarySamples() const
  {
    return boundary_samples_;
  }
  /** \brief Number of candidate triangles chosen by the cocones.
   * \return the number of candidates (ReconstructionReport::candidate_triangles) */
  std::size_t
  getNumberOfCandidateTriangles() const
  {
    return report_.candidate_triangles;
  }
  /** \brief Number of candidates dropped because they covered a true boundary.
   * \return the number of lid triangles (ReconstructionReport::lid_triangles) */
  std::size_t
  getNumberOfLidTriangles() const
  {
    return report_.lid_triangles;
  }
  /** \brief Number of candidates pruned at sharp edges.
   * \return the number of pruned triangles (ReconstructionReport::pruned_triangles) */
  std::size_t
  getNumberOfPrunedTriangles() const
  {
    return report_.pruned_triangles;
  }
  /** \brief Number of holes closed by stitching.
   * \return the number of stitched holes (ReconstructionReport::stitched_holes) */
  std::size_t
  getNumberOfStitchedHoles() const
  {
    return report_.stitched_holes;
  }
  /** \brief Number of triangles added by stitching.
   * \return the number of stitched triangles
   *         (ReconstructionReport::stitched_triangles) */
  std::size_t
  getNumberOfStitchedTriangles() const
  {
    return report_.stitched_triangles;
  }
  /** \brief The boundary loops left open (true boundaries and holes that could not be
   * closed).
   * \return one pcl::Vertices per loop: a cycle of input cloud indices oriented with
   *         the surface (the edge from the last back to the first closes it) */
  const std::vector<pcl::Vertices>&
  getBoundaryLoops() const
  {
    return boundary_loops_;
  }
  /** \brief The selected points left out because they lie far beyond the cloud's own
   * scale (more than cocone::kFarPointFactor times its median radius from its median
   * point: invalid-point markers such as FLT_MAX, corrupt values). They are among
   * getUnusedIndices() too, and getWarningMessage() names them.
   * \return input cloud indices, in selection order */
  const pcl::Indices&
  getFarIndices() const
  {
    return far_indices_;
  }
  /** \brief What the last run warns about, besides its result: far points left out,
   * coordinates whose float rounding is coarse against the sample spacing (with what to
   * do about it). The same text went to PCL_WARN.
   * \return one line; empty when there is nothing to warn about */
  const std::string&
  getWarningMessage() const
  {
    return warning_message_;
  }
  /** \brief The selected points that are in no triangle: non-finite points,
   * far points, duplicates, outliers, samples the extraction left out.
   * \return input cloud indices (among those selected), ascending; after a run without
   *         a Voronoi diagram, every selected index in selection order */
  const pcl::Indices&
  getUnusedIndices() const
  {
    return unused_indices_;
  }
  /** \brief Why the last run produced no result. The same text went to PCL_ERROR.
   * \return one line, e.g. "all points are coplanar: no 3D Voronoi cell to measure";
   *         empty after a successful run */
  const std::string&
  getErrorMessage() const
  {
    return error_message_;
  }
  /** \brief What the last run did, stage by stage, in numbers (counts and timings).
   * The per-point results are getBoundarySamples(), getBoundaryLoops() and
   * getUnusedIndices(), all in input cloud indices.
   * \return the statistics; all 0 after a run without a Voronoi diagram */
  const cocone::ReconstructionStatistics&
  getReport() const
  {
    return report_;
  }
  /** \} */

protected:
  using MeshConstruction<PointInT>::check_tree_;
  using MeshConstruction<PointInT>::input_;
  using MeshConstruction<PointInT>::indices_;

  /** \brief Name used in messages.
   * \return "CoconeReconstruction" */
  std::string
  getClassName() const override
  {
    return "CoconeReconstruction";
  }

  /** \brief Reconstructs into output.polygons (pcl::MeshConstruction::reconstruct has
   * already copied the input cloud into output.cloud).
   * \param[out] output the mesh; its polygons' vertex ids are input cloud indices */
  void performReconstruction(pcl::PolygonMesh& output) override;

  /** \brief Reconstructs the surface through the selected finite points.
   * \param[out] polygons oriented triangles as input cloud indices (cleared first);
   *             empty when no Voronoi diagram exists */
  void performReconstruction(std::vector<pcl::Vertices>& polygons) override;

private:
  /** performReconstruction without its guard against running out of memory. */
  void reconstructSelection(std::vector<pcl::Vertices>& polygons);

  /** Fails the run: the message to getErrorMessage() and PCL_ERROR, every result
   * empty, every selected index unused. */
  void fail(const std::string& message);

  cocone::VoronoiParameters voronoi_parameters_;
  cocone::ReconstructionParameters parameters_;

  cocone::ReconstructionStatistics report_;
  std::vector<std::uint8_t> boundary_samples_;
  std::vector<pcl::Vertices> boundary_loops_;
  pcl::Indices unused_indices_;
  pcl::Indices far_indices_;
  std::function<bool(double)> progress_;
  std::string error_message_;
  std::string warning_message_;
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl/cocone/impl/cocone_reconstruction.hpp>
#endif
