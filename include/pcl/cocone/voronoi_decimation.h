// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * pcl::VoronoiDecimation: algorithm DECIMATE as a pcl::FilterIndices.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>
#include <pcl/filters/filter_indices.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pcl {

/** \brief Removes oversampling while keeping every feature: algorithm DECIMATE of Dey,
 * Giesen, Goswami, Hudson, Wenger and Zhao, "Undersampling and Oversampling in Sample
 * Based Shape Modeling", IEEE Visualization 2001 (section 4).
 *
 * A sample whose Voronoi cell is long and skinny (cocone radius r_p small against the
 * height h_p, an estimate of the local feature size) is redundant. While some sample
 * has r_p / h_p < rho, the one with the smallest ratio is removed and the radii of the
 * samples whose cells grew are measured again; heights and pole vectors stay those of
 * the full sample. What remains is still dense relative to the local feature size, so
 * flat regions are thinned much more than curved ones and small features keep their
 * samples, unlike VoxelGrid (which moves points) or UniformSampling (which ignores
 * shape). The kept points are original points, never moved; the result is the same on
 * every run.
 *
 * Rims (beyond the paper, on by default, setThinRims): the cocone of a sample on the
 * rim of an open surface runs on past the last samples, so DECIMATE as published never
 * thins the outermost row (on a 10k monkey saddle at rho 0.4 it kept 252 of its 270
 * samples, and they were 252 of the 381 kept). Rim samples are therefore measured only
 * on the side where the surface is, and the rim is thinned like the rest.
 *
 * Relaxation (beyond the paper, on by default, setRelaxationIterations): DECIMATE stops
 * where every kept sample borders a gap wider than rho h_p, which leaves kept samples
 * bunched beside the gaps. filter() then evens the kept set out at the same size, by a
 * few rounds of Lloyd's iteration over the input: each kept sample starts a generator
 * that moves to the centroid of the input samples nearest to it, and in the end keeps
 * the input sample nearest to it. Samples flagged by BOUNDARY (rims, sharp features),
 * and kept samples next to them, stay. At equal point counts this lowers the
 * reconstruction error on smooth shapes (docs/benchmarks.md: sphere 10k at rho 0.3,
 * Hausdorff distance 1.7 spacings without it, 1.0 with it).
 *
 * Levels of detail: the removals of a run up to rho contain those of every smaller
 * rho, in the same order, so one run gives nested subsets for several values
 * (computeLevelsOfDetail, getRemovalLevels). computeLevelsOfDetail returns DECIMATE's
 * own sets, without relaxation.
 *
 * Index spaces and special points: indices (setIndices) select the points to decimate;
 * filter(Indices&) returns input cloud indices in the order of the selection. Points
 * with a NaN or infinite coordinate, and points far beyond the cloud's own scale
 * (getFarIndices()), are never returned (in removed indices instead, also with
 * setNegative(true)). Exact duplicates: only the first is kept. Fewer than 4
 * distinct finite points, or all coplanar or collinear: PCL_ERROR and an empty result.
 *
 * \tparam PointT a point type with x, y, z
 * \ingroup filters
 */
template <typename PointT>
class VoronoiDecimation : public FilterIndices<PointT>
{
public:
  /** \brief Shared pointer to a VoronoiDecimation. */
  using Ptr = shared_ptr<VoronoiDecimation<PointT>>;
  /** \brief Shared pointer to a const VoronoiDecimation. */
  using ConstPtr = shared_ptr<const VoronoiDecimation<PointT>>;

  /** \brief Default parameters: rho 0.3, theta pi/8, automatic threads.
   * \param[in] extract_removed_indices whether getRemovedIndices() is filled (default
   *            false) */
  explicit VoronoiDecimation(bool extract_removed_indices = false)
    : FilterIndices<PointT>(extract_removed_indices)
  {
    Filter<PointT>::filter_name_ = "VoronoiDecimation";
  }

  /** \brief Set rho: samples with r_p / h_p below it are removed, smallest first.
   * Dimensionless; default 0.3; valid range (0, 10], useful range 0.25 to 0.4 (the
   * paper removed 56% to 83% of its scans at 0.3 and 65% to 89% at 0.4). Out of range:
   * PCL_ERROR, unchanged.
   * \param[in] rho the ratio bound, dimensionless, in (0, 10] */
  void setRatioBound(double rho);
  /** \brief Get rho (see setRatioBound).
   * \return the ratio bound, dimensionless, in (0, 10]; default 0.3 */
  double
  getRatioBound() const
  {
    return parameters_.ratio_bound;
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

  /** \brief Beyond the paper: measure each sample on the rim of an open surface
   * (flagged by BOUNDARY, with its cocone neighbours on one side in its tangent plane)
   * on the side of its Voronoi cell where the surface is, so that rims are thinned like
   * the rest of the surface. False gives DECIMATE as published, which keeps the
   * outermost row of an open surface at its input density. Closed surfaces have no
   * rim: their result does not depend on it.
   * \param[in] thin whether rims are thinned; default true; either value is valid */
  void
  setThinRims(bool thin)
  {
    parameters_.thin_rims = thin;
  }
  /** \brief Get whether rims are thinned (see setThinRims).
   * \return true (default) when rim samples are measured on the surface side only */
  bool
  getThinRims() const
  {
    return parameters_.thin_rims;
  }

  /** \brief Beyond the paper: rounds of relaxation after DECIMATE in filter() (see the
   * class description); 0 gives DECIMATE's own sample. The point count never changes;
   * the rounds stop early once fewer than 1% of the kept samples would change (5 on
   * the bunny at rho 0.3).
   * \param[in] iterations the number of rounds, in [0, 1000]; default 10; other values
   *            are refused with PCL_ERROR and the current value is kept */
  void setRelaxationIterations(unsigned iterations);
  /** \brief Get the number of relaxation rounds (see setRelaxationIterations).
   * \return the number of rounds; 10 by default */
  unsigned
  getRelaxationIterations() const
  {
    return parameters_.relaxation_iterations;
  }

  /** \brief Set a callback for the progress of filter(): it is called from the
   * thread that called filter() with the share of the run done (0 to 1), a few times
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

  /** \brief Nested subsets for several ratio bounds from one run (up to the largest).
   * Does not change the ratio bound of setRatioBound; ignores setNegative. Fills
   * getRemovalLevels() like filter() does.
   * \param[in] ratio_bounds the values of rho, dimensionless, each in (0, 10], in any
   *            order
   * \param[out] kept for each value (same order as \a ratio_bounds), the kept input
   *             cloud indices (in selection order); a larger rho keeps a subset of what
   *             a smaller one keeps. Cleared first; empty on failure
   * \return true on success, also for an empty \a ratio_bounds (then nothing is
   *         computed); false (with PCL_ERROR) on bad input or parameters */
  bool computeLevelsOfDetail(const std::vector<double>& ratio_bounds,
                             std::vector<pcl::Indices>& kept);

  /** \brief After filter() or computeLevelsOfDetail(): for each input cloud point, the
   * ratio bound from which on it is removed (kept at rho exactly when its level is >=
   * rho, for rho up to the bound the run went to). After a relaxed filter() the
   * levels describe its output: a point the relaxation moved to has level rho, one it
   * moved from a level just below rho; the sets kept at smaller rho still contain it.
   * \return one level per input cloud point (indexed by input cloud index, size of the
   *         input cloud), dimensionless: +infinity for points the run did not remove, 0
   *         for duplicates, NaN for points not selected, not finite or far (see
   *         getFarIndices()), and for every
   *         point after a run without a Voronoi diagram; empty after a run that ran
   *         out of memory */
  const std::vector<double>&
  getRemovalLevels() const
  {
    return removal_levels_;
  }

  /** \brief The selected points left out because they lie far beyond the cloud's own
   * scale (more than cocone::kFarPointFactor times its median radius from its median
   * point); they are never kept, like non-finite points.
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

  /** \brief Why the last run produced no result. The same text went to PCL_ERROR.
   * \return one line, e.g. "all points are coplanar: no 3D Voronoi cell to measure";
   *         empty after a successful run */
  const std::string&
  getErrorMessage() const
  {
    return error_message_;
  }

protected:
  using FilterIndices<PointT>::negative_;
  using FilterIndices<PointT>::extract_removed_indices_;
  using FilterIndices<PointT>::removed_indices_;
  using PCLBase<PointT>::input_;
  using PCLBase<PointT>::indices_;
  using Filter<PointT>::getClassName;

  /** \brief Runs DECIMATE up to the ratio bound on the selected points.
   * \param[out] indices the kept input cloud indices in selection order (with
   *             setNegative(true): the removed finite ones); never a non-finite point;
   *             empty when no Voronoi diagram exists */
  void applyFilter(Indices& indices) override;

private:
  /** Runs DECIMATE on the selected points with \a parameters; fills removal_levels_.
   * False (with PCL_ERROR and getErrorMessage()) when it fails. */
  bool decimate(const cocone::DecimationParameters& parameters);
  /** decimate() without its guard against running out of memory. */
  bool decimateSelection(const cocone::DecimationParameters& parameters);

  cocone::VoronoiParameters voronoi_parameters_;
  cocone::DecimationParameters parameters_;
  std::vector<double> removal_levels_;
  pcl::Indices far_indices_;
  std::function<bool(double)> progress_;
  std::string error_message_;
  std::string warning_message_;
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl/cocone/impl/voronoi_decimation.hpp>
#endif
