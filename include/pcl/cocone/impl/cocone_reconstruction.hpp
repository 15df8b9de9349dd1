// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/cloud_samples.h>
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/tile_exchange.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <new>

namespace pcl {

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setCoconeAngle(double theta)
{
  if (cocone::acceptParameter(getClassName(), "setCoconeAngle", "theta", theta,
                              cocone::kCoconeAngleRange,
                              voronoi_parameters_.cocone_angle))
    voronoi_parameters_.cocone_angle = theta;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setRatioBound(double rho)
{
  if (cocone::acceptParameter(getClassName(), "setRatioBound", "rho", rho,
                              cocone::kRatioBoundRange,
                              parameters_.boundary.ratio_bound))
    parameters_.boundary.ratio_bound = rho;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setNormalAngle(double alpha)
{
  if (cocone::acceptParameter(getClassName(), "setNormalAngle", "alpha", alpha,
                              cocone::kNormalAngleRange,
                              parameters_.boundary.normal_angle))
    parameters_.boundary.normal_angle = alpha;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::setTrueBoundaryRatio(double ratio)
{
  if (cocone::acceptParameter(getClassName(), "setTrueBoundaryRatio", "ratio", ratio,
                              cocone::kTrueBoundaryRatioRange,
                              parameters_.true_boundary_ratio))
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
CoconeReconstruction<PointInT>::fail(const std::string& message)
{
  error_message_ = message;
  PCL_ERROR("[pcl::%s::reconstruct] %s.\n", getClassName().c_str(),
            error_message_.c_str());
  report_ = cocone::ReconstructionStatistics();
  std::fill(boundary_samples_.begin(), boundary_samples_.end(), 0);
  boundary_loops_.clear();
  unused_indices_ = *indices_;
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::performReconstruction(
    std::vector<pcl::Vertices>& polygons)
{
  // The core reports its own failures; what remains is this template's copies.
  try {
    reconstructSelection(polygons);
  }
  catch (const std::bad_alloc&) {
    // Nothing that allocates: every result is emptied, not refilled.
    std::vector<pcl::Vertices>().swap(polygons);
    report_ = cocone::ReconstructionStatistics();
    std::vector<std::uint8_t>().swap(boundary_samples_);
    std::vector<pcl::Vertices>().swap(boundary_loops_);
    pcl::Indices().swap(unused_indices_);
    pcl::Indices().swap(far_indices_);
    error_message_ = "out of memory during the reconstruction";
    PCL_ERROR("[pcl::%s::reconstruct] %s.\n", getClassName().c_str(),
              error_message_.c_str());
  }
}

template <typename PointInT>
void
CoconeReconstruction<PointInT>::reconstructSelection(
    std::vector<pcl::Vertices>& polygons)
{
  polygons.clear();
  error_message_.clear();
  report_ = cocone::ReconstructionStatistics();
  boundary_samples_.assign(input_->size(), 0);
  boundary_loops_.clear();
  unused_indices_.clear();
  warning_message_.clear();

  const cocone::CloudSamples samples =
      cocone::gatherSamples(*input_, *indices_, voronoi_parameters_.threads);
  far_indices_ = samples.far;
  unused_indices_ = samples.non_finite;
  unused_indices_.insert(unused_indices_.end(), samples.far.begin(), samples.far.end());
  const pcl::Indices& cloud_index = samples.cloud_index;

  cocone::VoronoiCocone voronoi(voronoi_parameters_);
  // The diagram takes about 60% of a run, the mesher the rest.
  const cocone::Status status =
      voronoi.compute(samples.points, cocone::progressPart(progress_, 0, 0.6));
  // A process other than the root of a shared diagram has sent its tiles: done.
  if (status == cocone::Status::not_computed && voronoi_parameters_.exchange &&
      voronoi_parameters_.exchange->rank() != 0)
    return;
  warning_message_ = cocone::describeSampleProblems(
      *input_, samples, voronoi.typicalSpacing(), "listed as unused");
  if (!warning_message_.empty())
    PCL_WARN("[pcl::%s::reconstruct] %s.\n", getClassName().c_str(),
             warning_message_.c_str());
  if (status != cocone::Status::ok)
    return fail(voronoi.errorMessage());
  std::vector<cocone::TriangleIndices> triangles;
  cocone::ReconstructionReport report;
  std::string message;
  if (cocone::reconstructSurface(voronoi, parameters_, triangles, report,
                                 cocone::progressPart(progress_, 0.6, 1),
                                 &message) != cocone::Status::ok)
    return fail(message);

  // Every index handed out is a cloud index: sample s is cloud point cloud_index[s].
  report_ = report;
  polygons.reserve(triangles.size());
  for (const cocone::TriangleIndices& t : triangles) {
    polygons.emplace_back();
    polygons.back().vertices.resize(3);
    for (int k = 0; k < 3; ++k)
      polygons.back().vertices[k] = cloud_index[t[k]];
  }
  for (std::size_t s = 0; s < cloud_index.size(); ++s)
    boundary_samples_[cloud_index[s]] = report.boundary_samples[s];
  for (const std::vector<cocone::SampleIndex>& loop : report.open_loops) {
    pcl::Vertices cycle;
    cycle.vertices.reserve(loop.size());
    for (const cocone::SampleIndex s : loop)
      cycle.vertices.push_back(cloud_index[s]);
    boundary_loops_.push_back(std::move(cycle));
  }
  for (const cocone::SampleIndex s : report.unused_samples)
    unused_indices_.push_back(cloud_index[s]);
  std::sort(unused_indices_.begin(), unused_indices_.end());
  PCL_DEBUG("[pcl::%s::reconstruct] %zu triangles, %zu candidates, %zu pruned, %zu "
            "stitched in %zu holes, %zu open loops, %zu unused points.\n",
            getClassName().c_str(), polygons.size(), report_.candidate_triangles,
            report_.pruned_triangles, report_.stitched_triangles,
            report_.stitched_holes, boundary_loops_.size(), unused_indices_.size());
}

} // namespace pcl

#define PCL_INSTANTIATE_CoconeReconstruction(T)                                        \
  template class PCL_COCONE_EXPORT pcl::CoconeReconstruction<T>;
