// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The one place where the PCL-facing templates turn a cloud into core samples.
 */
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/common/point_tests.h>
#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <Eigen/Core>

#include <vector>

namespace pcl {
namespace cocone {

/** \brief Collects the finite points of \a cloud at \a indices as double-precision
 * samples, in spatial order.
 *
 * The samples are ordered along spatialOrder's curve, not as \a indices lists them:
 * the core then walks memory in order, whatever the order of the cloud (a fifth of a
 * 1M-point reconstruction on randomly ordered points), and the results depend on the
 * points, not on their order. The order is stable, so of identical points the one
 * listed first in \a indices represents the group.
 * \tparam PointT a point type with x, y, z
 * \param[in] cloud the input cloud
 * \param[in] indices the input cloud indices to consider (each must be a valid index
 *            of \a cloud; not checked)
 * \param[out] samples one entry per finite point, in input units; its positions are the
 *             sample indices given to VoronoiCocone::compute (cleared first)
 * \param[out] cloud_index for each sample (same size as \a samples), its input cloud
 *             index: maps sample indices back to input cloud indices (cleared first)
 * \param[out] skipped_indices if given, the input cloud indices of the skipped points,
 *             in the order of \a indices (appended to)
 * \param[in] threads worker threads of the ordering (0: every core)
 * \return the number of points skipped because a coordinate is NaN or infinite */
template <typename PointT>
std::size_t
gatherFiniteSamples(const pcl::PointCloud<PointT>& cloud, const pcl::Indices& indices,
                    std::vector<Eigen::Vector3d>& samples, pcl::Indices& cloud_index,
                    pcl::Indices* skipped_indices = nullptr, unsigned threads = 0)
{
  std::vector<Eigen::Vector3d> finite;
  pcl::Indices finite_index;
  finite.reserve(indices.size());
  finite_index.reserve(indices.size());
  std::size_t skipped = 0;
  for (const pcl::index_t i : indices) {
    const PointT& point = cloud[i];
    if (!pcl::isXYZFinite(point)) {
      ++skipped;
      if (skipped_indices)
        skipped_indices->push_back(i);
      continue;
    }
    finite.emplace_back(point.x, point.y, point.z);
    finite_index.push_back(i);
  }
  const std::vector<SampleIndex> order = spatialOrder(finite, threads);
  if (order.size() != finite.size()) { // too many for a SampleIndex: compute() says so
    samples = std::move(finite);
    cloud_index = std::move(finite_index);
    return skipped;
  }
  samples.resize(order.size());
  cloud_index.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    samples[k] = finite[order[k]];
    cloud_index[k] = finite_index[order[k]];
  }
  return skipped;
}

} // namespace cocone
} // namespace pcl
