// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): the one place where the PCL-facing
 * templates turn a cloud into core samples, and map the results back.
 */
#pragma once

#include <pcl/cocone/core/sample_checks.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/common/point_tests.h>
#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <Eigen/Core>

#include <cstdio>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief The samples of a cloud, and the points left out of them. */
struct CloudSamples
{
  /** One entry per sample, in input units, in spatial order; its positions are the
   * sample indices given to VoronoiCocone::compute. */
  std::vector<Eigen::Vector3d> points;
  /** For each sample (same size as #points), its input cloud index. */
  pcl::Indices cloud_index;
  /** The input cloud indices of points with a NaN or infinite coordinate, in the order
   * of the selection. */
  pcl::Indices non_finite;
  /** The input cloud indices of finite points far beyond the cloud's own scale
   * (findFarPoints), in the order of the selection. */
  pcl::Indices far;
};

/** \brief Collects the finite points of \a cloud at \a indices as double-precision
 * samples, leaves out those far beyond the cloud's own scale, and puts the rest in
 * spatial order.
 *
 * The samples are ordered along spatialOrder's curve, not as \a indices lists them:
 * the core then walks memory in order, whatever the order of the cloud (a fifth of a
 * 1M-point reconstruction on randomly ordered points), and the results depend on the
 * points, not on their order. The order is stable, so of identical points the one
 * listed first in \a indices represents the group. Far points are found before the
 * curve is laid over the samples' bounding box, so that a far point changes nothing
 * else.
 * \tparam PointT a point type with x, y, z
 * \param[in] cloud the input cloud
 * \param[in] indices the input cloud indices to consider (each must be a valid index
 *            of \a cloud; not checked)
 * \param[in] threads worker threads of the ordering (0: every core)
 * \return the samples and the points left out */
template <typename PointT>
CloudSamples
gatherSamples(const pcl::PointCloud<PointT>& cloud, const pcl::Indices& indices,
              unsigned threads = 0)
{
  CloudSamples result;
  std::vector<Eigen::Vector3d> finite;
  pcl::Indices finite_index;
  finite.reserve(indices.size());
  finite_index.reserve(indices.size());
  for (const pcl::index_t i : indices) {
    const PointT& point = cloud[i];
    if (!pcl::isXYZFinite(point)) {
      result.non_finite.push_back(i);
      continue;
    }
    finite.emplace_back(point.x, point.y, point.z);
    finite_index.push_back(i);
  }
  const std::vector<std::uint8_t> far = findFarPoints(finite);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < finite.size(); ++k) {
    if (far[k]) {
      result.far.push_back(finite_index[k]);
      continue;
    }
    finite[kept] = finite[k];
    finite_index[kept] = finite_index[k];
    ++kept;
  }
  finite.resize(kept);
  finite_index.resize(kept);
  const std::vector<SampleIndex> order = spatialOrder(finite, threads);
  if (order.size() != finite.size()) { // too many for a SampleIndex: compute() says so
    result.points = std::move(finite);
    result.cloud_index = std::move(finite_index);
    return result;
  }
  result.points.resize(order.size());
  result.cloud_index.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    result.points[k] = finite[order[k]];
    result.cloud_index[k] = finite_index[order[k]];
  }
  return result;
}

/** \brief A float rounding step this large against the typical sample spacing gets a
 * warning: the rounding moves the samples by a noticeable share of the distances the
 * geometry measures (PCL's LiDAR terrain, UTM northings near 5.4e6: a step of 0.5 m
 * against a spacing of about 1.5 m). */
constexpr double kCoarseRoundingShare = 0.05;

/** \brief What a class warns about the samples, one sentence each, or empty: far points
 * left out, and coordinates that float rounding makes coarse against the spacing.
 * \param[in] cloud the input cloud (to name a far point)
 * \param[in] samples what gatherSamples returned
 * \param[in] spacing the typical sample spacing (VoronoiCocone::typicalSpacing), 0 if
 *            unknown
 * \param[in] where_far_points_go how the class reports far points, e.g. "listed as
 *            unused"
 * \return the warning text, without a final newline; empty when there is nothing to say
 */
template <typename PointT>
std::string
describeSampleProblems(const pcl::PointCloud<PointT>& cloud,
                       const CloudSamples& samples, double spacing,
                       const char* where_far_points_go)
{
  std::string text;
  char buffer[512];
  if (!samples.far.empty()) {
    const PointT& example = cloud[samples.far.front()];
    std::snprintf(buffer, sizeof buffer,
                  "%zu point%s lie%s more than %g times the cloud's median radius from "
                  "its median point (e.g. point %d at (%g, %g, %g)): left out, %s",
                  samples.far.size(), samples.far.size() == 1 ? "" : "s",
                  samples.far.size() == 1 ? "s" : "", kFarPointFactor,
                  static_cast<int>(samples.far.front()), example.x, example.y,
                  example.z, where_far_points_go);
    text += buffer;
  }
  const double step = floatRoundingStep(samples.points);
  if (spacing > 0 && step > kCoarseRoundingShare * spacing) {
    std::snprintf(
        buffer, sizeof buffer,
        "%scoordinates as large as these are rounded to steps of %g as floats, "
        "%.0f%% of the typical sample spacing %g: shift the cloud towards the "
        "origin before it is stored as float (e.g. subtract a corner of its "
        "bounding box), or read it from a double-precision source",
        text.empty() ? "" : "; ", step, 100 * step / spacing, spacing);
    text += buffer;
  }
  return text;
}

} // namespace cocone
} // namespace pcl
