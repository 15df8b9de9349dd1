// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * pcl::BoundarySampleEstimation: algorithm BOUNDARY as a pcl::Feature.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>
#include <pcl/features/feature.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pcl {

/** \brief Detects the samples near undersampling (boundaries, sharp features, thin or
 * sparsely sampled parts) from the geometry of their Voronoi cells: algorithm BOUNDARY
 * of Dey, Giesen, Goswami, Hudson, Wenger and Zhao, "Undersampling and Oversampling in
 * Sample Based Shape Modeling", IEEE Visualization 2001.
 *
 * A sample is *flat* when its Voronoi cell is long and thin (cocone radius r_p at most
 * rho times the height h_p) and its pole line agrees, within alpha, with those of the
 * samples whose cocone meets its cell. Flat samples are grown through cocone neighbours
 * that are thin and agree; every sample not reached is a boundary sample. On a smooth
 * open surface the flags mark the outermost row of samples along the rim (the rim
 * vertices of a correct reconstruction); they also mark samples along sharp edges and
 * in thin, undersampled parts. By default the rim row is completed beyond the paper
 * (see setRimRowCompletion): BOUNDARY alone flags a quarter to a half of it.
 *
 * Unlike pcl::BoundaryEstimation it needs no normals, no search radius and no k: the
 * one Delaunay triangulation of the cloud defines every neighbourhood. Output is
 * pcl::Boundary by default, so it drops into code written for BoundaryEstimation.
 *
 * Index spaces and special points:
 * - the Voronoi diagram is built from every finite point of the input cloud; the output
 *   has one row per index (setIndices) in that order, like every pcl::Feature;
 * - points with a NaN or infinite coordinate are skipped: their row says
 *   boundary_point = 0, isValid() is false, the per-point values are NaN and the
 *   output's is_dense is false; so are points far beyond the cloud's own scale
 *   (getFarIndices(), named by getWarningMessage()), which would change the cells of
 *   every sample on the convex hull;
 * - exact duplicates share one Voronoi cell and get the flag of the first of them;
 * - fewer than 4 distinct finite points, or all of them coplanar or collinear, have
 *   no 3D Voronoi cell: compute() reports it with PCL_ERROR and returns an empty
 *   output;
 * - setSearchSurface() is not supported (the cells are those of the input cloud).
 *
 * Besides the flags, the per-point Voronoi values are available after compute(): the
 * unit pole vector (a normal estimate oriented towards the positive pole, which lies on
 * the side where the cell extends farther), the height h_p (an estimate of the local
 * feature size), the cocone radius r_p and the ratio r_p / h_p.
 *
 * \tparam PointInT a point type with x, y, z
 * \tparam PointOutT a point type with a boundary_point field (default pcl::Boundary)
 * \ingroup features
 */
template <typename PointInT, typename PointOutT = pcl::Boundary>
class BoundarySampleEstimation : public Feature<PointInT, PointOutT>
{
public:
  /** \brief Shared pointer to a BoundarySampleEstimation. */
  using Ptr = shared_ptr<BoundarySampleEstimation<PointInT, PointOutT>>;
  /** \brief Shared pointer to a const BoundarySampleEstimation. */
  using ConstPtr = shared_ptr<const BoundarySampleEstimation<PointInT, PointOutT>>;
  /** \brief The output cloud type: a pcl::PointCloud of \a PointOutT. */
  using PointCloudOut = typename Feature<PointInT, PointOutT>::PointCloudOut;

  /** \brief Default parameters: rho 0.99, alpha pi/6, theta pi/8, rim row completed,
   * no band, automatic threads. */
  BoundarySampleEstimation()
  {
    Feature<PointInT, PointOutT>::feature_name_ = "BoundarySampleEstimation";
  }

  /** \brief Set rho, the ratio bound of the flatness test r_p / h_p <= rho.
   * Dimensionless; default 0.99 (the paper's value for all its data); valid range
   * (0, 10]. Smaller values flag more samples. Out of range: PCL_ERROR, unchanged.
   * \param[in] rho the ratio bound, dimensionless, in (0, 10] */
  void setRatioBound(double rho);
  /** \brief Get rho (see setRatioBound).
   * \return the ratio bound, dimensionless, in (0, 10]; default 0.99 */
  double
  getRatioBound() const
  {
    return parameters_.ratio_bound;
  }

  /** \brief Set alpha, the largest acute angle between pole lines of neighbouring flat
   * samples. Radians; default pi/6; valid range (0, pi/2]. Smaller values flag more
   * samples near curved or sharp regions. Out of range: PCL_ERROR, unchanged.
   * \param[in] alpha the normal agreement angle in radians, in (0, pi/2] */
  void setNormalAngle(double alpha);
  /** \brief Get alpha (see setNormalAngle).
   * \return the normal agreement angle in radians, in (0, pi/2]; default pi/6 */
  double
  getNormalAngle() const
  {
    return parameters_.normal_angle;
  }

  /** \brief Set theta, the cocone angle: the cocone of p is the part of its Voronoi
   * cell within theta of the plane orthogonal to the pole vector. Radians; default
   * pi/8; valid range (0, pi/2). Out of range: PCL_ERROR, unchanged.
   * \param[in] theta the cocone angle in radians, in (0, pi/2) */
  void setCoconeAngle(double theta);
  /** \brief Get theta (see setCoconeAngle).
   * \return the cocone angle in radians, in (0, pi/2); default pi/8 */
  double
  getCoconeAngle() const
  {
    return voronoi_parameters_.cocone_angle;
  }

  /** \brief Beyond the paper: also flag \a rings rings of cocone neighbours around the
   * boundary samples, giving a band along boundaries like pcl::BoundaryEstimation's.
   * In rings; default 0 (BOUNDARY as published); valid range 0 to 64. Out of range:
   * PCL_ERROR, unchanged.
   * \param[in] rings the number of rings, 0 to 64 */
  void setBoundaryBandRings(unsigned rings);
  /** \brief Get the number of band rings (see setBoundaryBandRings).
   * \return the number of rings, 0 to 64; default 0 */
  unsigned
  getBoundaryBandRings() const
  {
    return parameters_.band_rings;
  }

  /** \brief Beyond the paper: complete the outermost row of samples along each rim.
   * BOUNDARY as published flags only 27-54% of that row: a rim sample whose Voronoi
   * cell is closed off just beyond the rim by its neighbours' cells passes the flatness
   * test. With completion on, every sample reached from a flag along cocone neighbours
   * whose nearby cocone neighbours leave a gap wider than 2 pi / 3 in its tangent plane
   * is flagged too (and the walk goes on from it). Default true; false gives BOUNDARY
   * exactly as published.
   * \param[in] complete true to complete the rim row */
  void
  setRimRowCompletion(bool complete)
  {
    parameters_.complete_rim_row = complete;
  }
  /** \brief Get whether the rim row is completed (see setRimRowCompletion).
   * \return true (default) when the rim row is completed */
  bool
  getRimRowCompletion() const
  {
    return parameters_.complete_rim_row;
  }

  /** \brief Set a callback for the progress of compute(): it is called from the
   * thread that called compute() with the share of the run done (0 to 1), a few times
   * per stage; returning false cancels the run, which then fails with the message
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

  /** \name Per-point results of the last compute()
   * One entry per output row, i.e. per index of the selection (setIndices) in its
   * order; row r describes input cloud point indices[r]. Empty after a run without a
   * Voronoi diagram; a run that initCompute() refuses (e.g. no input) leaves
   * them as they were. */
  /** \{ */
  /** \brief Which output rows have Voronoi values.
   * \return per row: 1 where the input point was finite and took part, 0 where it was
   *         skipped */
  const std::vector<std::uint8_t>&
  getValidity() const
  {
    return valid_;
  }
  /** \brief Pole vectors v_p, a normal estimate.
   * \return per row: the unit pole vector (oriented towards the positive pole), in the
   *         input frame; NaN where invalid */
  const std::vector<Eigen::Vector3f>&
  getPoleVectors() const
  {
    return pole_vectors_;
  }
  /** \brief Heights h_p = |p- - p|, an estimate of the local feature size.
   * \return per row: the height in input units; NaN where invalid or where the cell
   *         has no negative pole */
  const std::vector<float>&
  getHeights() const
  {
    return heights_;
  }
  /** \brief Cocone radii r_p.
   * \return per row: the radius in input units; +infinity for an unbounded cocone; NaN
   *         where invalid */
  const std::vector<float>&
  getCoconeRadii() const
  {
    return radii_;
  }
  /** \brief Ratios r_p / h_p, compared with rho by the flatness test.
   * \return per row: the ratio, dimensionless; +infinity where h_p is undefined or r_p
   *         infinite; NaN where invalid */
  const std::vector<float>&
  getRatios() const
  {
    return ratios_;
  }
  /** \brief Why the last run produced no result. The same text went to PCL_ERROR.
   * \return one line, e.g. "all points are coplanar: no 3D Voronoi cell to measure";
   *         empty after a successful run */
  const std::string&
  getErrorMessage() const
  {
    return error_message_;
  }
  /** \brief The input points left out of the diagram because they lie far beyond the
   * cloud's own scale (more than cocone::kFarPointFactor times its median radius from
   * its median point); their rows are invalid, like those of non-finite points.
   * \return input cloud indices, ascending */
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
  /** \brief Number of boundary samples among the output rows.
   * \return the number of rows with boundary_point = 1 (a repeated index counts each
   *         time) */
  std::size_t
  getNumberOfBoundarySamples() const
  {
    return boundary_count_;
  }
  /** \} */

protected:
  using Feature<PointInT, PointOutT>::feature_name_;
  using Feature<PointInT, PointOutT>::getClassName;
  using Feature<PointInT, PointOutT>::input_;
  using Feature<PointInT, PointOutT>::indices_;
  using Feature<PointInT, PointOutT>::surface_;
  using Feature<PointInT, PointOutT>::fake_surface_;

  /** \brief Checks the input without asking for a search radius or k, and builds no
   * search tree: the Delaunay triangulation replaces both.
   * \return false (with PCL_ERROR and getErrorMessage()) without an input cloud, with
   *         invalid indices, an empty cloud, or a search surface other than the input;
   *         true otherwise */
  bool initCompute() override;

  /** \brief Runs BOUNDARY on every finite input point and fills one row per index.
   * \param[out] output the boundary flags, one row per index (already sized by
   *             pcl::Feature::compute); emptied when no Voronoi diagram exists */
  void computeFeature(PointCloudOut& output) override;

private:
  void clearResults(std::size_t rows);

  /** computeFeature without its guard against running out of memory. */
  void estimate(PointCloudOut& output);

  /** Fails the run: the message to getErrorMessage() and PCL_ERROR, empty output. */
  void fail(const std::string& message, PointCloudOut& output);

  cocone::VoronoiParameters voronoi_parameters_;
  cocone::BoundaryParameters parameters_;

  std::vector<std::uint8_t> valid_;
  std::vector<Eigen::Vector3f> pole_vectors_;
  std::vector<float> heights_;
  std::vector<float> radii_;
  std::vector<float> ratios_;
  std::size_t boundary_count_ = 0;
  pcl::Indices far_indices_;
  std::function<bool(double)> progress_;
  std::string error_message_;
  std::string warning_message_;
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl/cocone/impl/boundary_sample_estimation.hpp>
#endif
