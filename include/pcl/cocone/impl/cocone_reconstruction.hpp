// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/cloud_samples.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/console/print.h>

namespace pcl {

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setCoconeAngle(double theta)
{
  if (!(theta > 0 && theta < M_PI / 2)) {
    PCL_ERROR("[pcl::%s::setCoconeAngle] theta = %g rad is outside (0, pi/2); keeping "
              "%g.\n",
              getClassName().c_str(), theta, cocone_angle_);
    return;
  }
  cocone_angle_ = theta;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setRatioBound(double rho)
{
  if (!(rho > 0 && rho <= 10)) {
    PCL_ERROR("[pcl::%s::setRatioBound] rho = %g is outside (0, 10]; keeping %g.\n",
              getClassName().c_str(), rho, parameters_.boundary.ratio_bound);
    return;
  }
  parameters_.boundary.ratio_bound = rho;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setNormalAngle(double alpha)
{
  if (!(alpha > 0 && alpha <= M_PI / 2)) {
    PCL_ERROR("[pcl::%s::setNormalAngle] alpha = %g rad is outside (0, pi/2]; keeping "
              "%g.\n",
              getClassName().c_str(), alpha, parameters_.boundary.normal_angle);
    return;
  }
  parameters_.boundary.normal_angle = alpha;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setTrueBoundaryRatio(double ratio)
{
  if (!(ratio >= 0.5 && ratio <= 1000)) {
    PCL_ERROR("[pcl::%s::setTrueBoundaryRatio] %g is outside [0.5, 1000]; keeping %g.\n",
              getClassName().c_str(), ratio, parameters_.true_boundary_ratio);
    return;
  }
  parameters_.true_boundary_ratio = ratio;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::performReconstruction(pcl::PolygonMesh& output)
{
  performReconstruction(output.polygons);
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::performReconstruction(std::vector<pcl::Vertices>& polygons)
{
  polygons.clear();
  error_message_.clear();
  report_ = cocone::ReconstructionReport();
  boundary_samples_.assign(input_->size(), 0);
  boundary_loops_.clear();
  unused_indices_.clear();

  std::vector<Eigen::Vector3d> samples;
  pcl::Indices cloud_index;
  cocone::gatherFiniteSamples(*input_, *indices_, samples, cloud_index);
  for (const pcl::index_t i : *indices_)
    if (!pcl::isXYZFinite((*input_)[i]))
      unused_indices_.push_back(i);

  cocone::VoronoiCocone voronoi;
  voronoi.setCoconeAngle(cocone_angle_);
  voronoi.setNumberOfThreads(threads_);
  if (voronoi.compute(samples) != cocone::Status::ok) {
    error_message_ = voronoi.errorMessage();
    PCL_ERROR("[pcl::%s::reconstruct] %s.\n", getClassName().c_str(),
              error_message_.c_str());
    unused_indices_ = *indices_;
    return;
  }
  std::vector<cocone::TriangleIndices> triangles;
  cocone::reconstructSurface(voronoi, parameters_, triangles, report_);

  polygons.reserve(triangles.size());
  for (const cocone::TriangleIndices& t : triangles) {
    polygons.emplace_back();
    polygons.back().vertices.resize(3);
    for (int k = 0; k < 3; ++k)
      polygons.back().vertices[k] = cloud_index[t[k]];
  }
  for (std::size_t s = 0; s < samples.size(); ++s)
    boundary_samples_[cloud_index[s]] = report_.boundary_samples[s];
  for (const std::vector<cocone::SampleIndex>& loop : report_.open_loops) {
    pcl::Vertices cycle;
    cycle.vertices.reserve(loop.size());
    for (const cocone::SampleIndex s : loop)
      cycle.vertices.push_back(cloud_index[s]);
    boundary_loops_.push_back(std::move(cycle));
  }
  for (const cocone::SampleIndex s : report_.unused_samples)
    unused_indices_.push_back(cloud_index[s]);
  std::sort(unused_indices_.begin(), unused_indices_.end());
  PCL_DEBUG("[pcl::%s::reconstruct] %zu triangles, %zu candidates, %zu pruned, %zu "
            "stitched in %zu holes, %zu open loops, %zu unused points.\n",
            getClassName().c_str(), polygons.size(), report_.candidate_triangles,
            report_.pruned_triangles, report_.stitched_triangles, report_.stitched_holes,
            boundary_loops_.size(), unused_indices_.size());
}

} // namespace pcl

#define PCL_INSTANTIATE_CoconeReconstruction(T)                                        \
  template class PCL_COCONE_EXPORT pcl::CoconeReconstruction<T>;
