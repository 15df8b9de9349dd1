// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The one place where the PCL-facing templates turn a cloud into core samples.
 */
#pragma once

#include <pcl/common/point_tests.h>
#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <Eigen/Core>

#include <vector>

namespace pcl {
namespace cocone {

/** \brief Collects the finite points of \a cloud at \a indices as double-precision
 * samples.
 * \tparam PointT a point type with x, y, z
 * \param[in] cloud the input cloud
 * \param[in] indices the input cloud indices to consider, in order (each must be a
 *            valid index of \a cloud; not checked)
 * \param[out] samples one entry per finite point, in the order of \a indices, in input
 *             units; its positions are the sample indices given to
 *             VoronoiCocone::compute (cleared first)
 * \param[out] cloud_index for each sample (same size as \a samples), its input cloud
 *             index: maps sample indices back to input cloud indices (cleared first)
 * \param[out] skipped_indices if given, the input cloud indices of the skipped points,
 *             in the order of \a indices (appended to)
 * \return the number of points skipped because a coordinate is NaN or infinite */
template <typename PointT>
std::size_t
gatherFiniteSamples(const pcl::PointCloud<PointT>& cloud,
                    const pcl::Indices& indices,
                    std::vector<Eigen::Vector3d>& samples,
                    pcl::Indices& cloud_index,
                    pcl::Indices* skipped_indices = nullptr)
{
  samples.clear();
  cloud_index.clear();
  samples.reserve(indices.size());
  cloud_index.reserve(indices.size());
  std::size_t skipped = 0;
  for (const pcl::index_t i : indices) {
    const PointT& point = cloud[i];
    if (!pcl::isXYZFinite(point)) {
      ++skipped;
      if (skipped_indices)
        skipped_indices->push_back(i);
      continue;
    }
    samples.emplace_back(point.x, point.y, point.z);
    cloud_index.push_back(i);
  }
  return skipped;
}

} // namespace cocone
} // namespace pcl
