// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit instantiations of the PCL-facing templates for PCL's usual point types. With
// PCL_NO_PRECOMPILE defined, the headers include their implementation instead, so
// custom point types work too (without CGAL: the templates only call the core).
#include <pcl/cocone/impl/boundary_sample_estimation.hpp>
#include <pcl/cocone/impl/cocone_reconstruction.hpp>
#include <pcl/cocone/impl/voronoi_decimation.hpp>
#include <pcl/impl/instantiate.hpp>
#include <pcl/point_types.h>

// Kept as written: clang-format would break the list inside the parentheses.
// clang-format off
#define PCL_COCONE_XYZ_POINT_TYPES                                                     \
  (pcl::PointXYZ)(pcl::PointXYZI)(pcl::PointXYZL)(pcl::PointXYZRGB)(pcl::PointXYZRGBA) \
  (pcl::PointXYZRGBL)(pcl::PointNormal)(pcl::PointXYZINormal)(pcl::PointXYZRGBNormal)  \
  (pcl::PointXYZLNormal)(pcl::PointWithViewpoint)
// clang-format on

PCL_INSTANTIATE_PRODUCT(BoundarySampleEstimation,
                        (PCL_COCONE_XYZ_POINT_TYPES)((pcl::Boundary)))
PCL_INSTANTIATE(CoconeReconstruction, PCL_COCONE_XYZ_POINT_TYPES)
PCL_INSTANTIATE(VoronoiDecimation, PCL_COCONE_XYZ_POINT_TYPES)
