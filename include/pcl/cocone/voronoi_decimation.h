// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/filters/filter_indices.h>

#include <cmath>
#include <string>
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
 * Levels of detail: the removals of a run up to rho contain those of every smaller
 * rho, in the same order, so one run gives nested subsets for several values
 * (computeLevelsOfDetail, getRemovalLevels).
 *
 * Index spaces and special points: indices (setIndices) select the points to decimate;
 * filter(Indices&) returns input cloud indices in the order of the selection. Points
 * with a NaN or infinite coordinate are never returned (in removed indices instead,
 * also with setNegative(true)). Exact duplicates: only the first is kept. Fewer than 4
 * distinct finite points, or all coplanar or collinear: PCL_ERROR and an empty result.
 *
 * \tparam PointT a point type with x, y, z
 * \ingroup filters
 */
template <typename PointT>
class VoronoiDecimation : public FilterIndices<PointT>
{
public:
  using Ptr = shared_ptr<VoronoiDecimation<PointT>>;
  using ConstPtr = shared_ptr<const VoronoiDecimation<PointT>>;

  /** \param[in] extract_removed_indices whether getRemovedIndices() is filled */
  explicit VoronoiDecimation(bool extract_removed_indices = false)
  : FilterIndices<PointT>(extract_removed_indices)
  {
    Filter<PointT>::filter_name_ = "VoronoiDecimation";
  }

  /** \brief Set rho: samples with r_p / h_p below it are removed, smallest first.
   * Dimensionless; default 0.3; valid range (0, 10], useful range 0.25 to 0.4 (the
   * paper removed 56% to 83% of its scans at 0.3 and 65% to 89% at 0.4). Out of range:
   * PCL_ERROR, unchanged. */
  void
  setRatioBound(double rho);
  /** \brief Get rho (see setRatioBound). */
  double
  getRatioBound() const
  {
    return ratio_bound_;
  }

  /** \brief Set theta, the cocone angle. Radians; default pi/8; valid range (0, pi/2).
   * Out of range: PCL_ERROR, unchanged. */
  void
  setCoconeAngle(double theta);
  /** \brief Get theta (see setCoconeAngle). */
  double
  getCoconeAngle() const
  {
    return cocone_angle_;
  }

  /** \brief Number of threads for the per-sample work; 0 (default) uses every core. */
  void
  setNumberOfThreads(unsigned threads)
  {
    threads_ = threads;
  }
  /** \brief Get the number of threads (0: automatic). */
  unsigned
  getNumberOfThreads() const
  {
    return threads_;
  }

  /** \brief Nested subsets for several ratio bounds from one run (up to the largest).
   * \param[in] ratio_bounds the values of rho, each in (0, 10]
   * \param[out] kept for each value, the kept input cloud indices (in selection order);
   *             a larger rho keeps a subset of what a smaller one keeps
   * \return false (with PCL_ERROR) on bad input or parameters */
  bool
  computeLevelsOfDetail(const std::vector<double>& ratio_bounds,
                        std::vector<pcl::Indices>& kept);

  /** \brief After filter() or computeLevelsOfDetail(): for each input cloud point, the
   * ratio bound from which on it is removed (kept at rho exactly when its level is >=
   * rho); +infinity for points no run removed, 0 for duplicates, NaN for points not
   * selected or not finite. */
  const std::vector<double>&
  getRemovalLevels() const
  {
    return removal_levels_;
  }

  /** \brief Why the last run produced no result (one line, e.g. "all points are
   * coplanar: no 3D Voronoi cell to measure"); empty after a successful run. The same
   * text went to PCL_ERROR. */
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

  void
  applyFilter(Indices& indices) override;

private:
  /** Runs DECIMATE up to rho on the selected points; fills removal_levels_. */
  bool
  decimate(double rho);

  double ratio_bound_ = 0.3;
  double cocone_angle_ = M_PI / 8;
  unsigned threads_ = 0;
  std::vector<double> removal_levels_;
  std::string error_message_;
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl/cocone/impl/voronoi_decimation.hpp>
#endif
