// SPDX-License-Identifier: GPL-3.0-or-later
// From the analytic samples (std::vector<Eigen::Vector3d>) to PCL clouds and back.
// Header-only and free of GTest: the benchmarks, which are built without the test
// support library, can include it.
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

/** An unorganized, dense cloud of \a points (narrowed to float); the fields other than
 * x, y, z keep their defaults. */
template <typename PointT = pcl::PointXYZ>
typename pcl::PointCloud<PointT>::Ptr
toCloud(const std::vector<Eigen::Vector3d>& points)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  cloud->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    (*cloud)[i].x = static_cast<float>(points[i].x());
    (*cloud)[i].y = static_cast<float>(points[i].y());
    (*cloud)[i].z = static_cast<float>(points[i].z());
  }
  cloud->width = static_cast<std::uint32_t>(points.size());
  cloud->height = 1;
  cloud->is_dense = true;
  return cloud;
}

/** The points as the algorithms see them (float coordinates, widened). */
template <typename PointT>
std::vector<Eigen::Vector3d>
toPoints(const pcl::PointCloud<PointT>& cloud)
{
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const PointT& p : cloud)
    points.emplace_back(p.x, p.y, p.z);
  return points;
}

/** \a cloud's points in a random order, the same for a given \a seed: point k of the
 * result is point order[k] of \a cloud. */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr
shuffledCloud(const pcl::PointCloud<PointT>& cloud, std::uint32_t seed,
              std::vector<std::size_t>& order)
{
  order.resize(cloud.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  auto shuffled = pcl::make_shared<pcl::PointCloud<PointT>>();
  for (const std::size_t i : order)
    shuffled->push_back(cloud[i]);
  return shuffled;
}

} // namespace test
} // namespace cocone
} // namespace pcl
