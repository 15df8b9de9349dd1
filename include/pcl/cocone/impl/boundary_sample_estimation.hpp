// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/cloud_samples.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <limits>
#include <new>
#include <numeric>

namespace pcl {

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::setRatioBound(double rho)
{
  if (cocone::acceptParameter(getClassName(), "setRatioBound", "rho", rho,
                              cocone::kRatioBoundRange, parameters_.ratio_bound))
    parameters_.ratio_bound = rho;
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::setNormalAngle(double alpha)
{
  if (cocone::acceptParameter(getClassName(), "setNormalAngle", "alpha", alpha,
                              cocone::kNormalAngleRange, parameters_.normal_angle))
    parameters_.normal_angle = alpha;
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::setCoconeAngle(double theta)
{
  if (cocone::acceptParameter(getClassName(), "setCoconeAngle", "theta", theta,
                              cocone::kCoconeAngleRange,
                              voronoi_parameters_.cocone_angle))
    voronoi_parameters_.cocone_angle = theta;
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::setBoundaryBandRings(unsigned rings)
{
  if (cocone::acceptParameter(getClassName(), "setBoundaryBandRings", "rings", rings,
                              cocone::kBandRingsRange, parameters_.band_rings))
    parameters_.band_rings = rings;
}

template <typename PointInT, typename PointOutT>
bool
BoundarySampleEstimation<PointInT, PointOutT>::initCompute()
{
  error_message_.clear();
  if (!PCLBase<PointInT>::initCompute()) {
    error_message_ = "no input cloud or invalid indices";
    PCL_ERROR("[pcl::%s::compute] No input cloud or invalid indices.\n",
              getClassName().c_str());
    return false;
  }
  if (input_->empty()) {
    error_message_ = "the input cloud is empty";
    PCL_ERROR("[pcl::%s::compute] The input cloud is empty.\n", getClassName().c_str());
    return false;
  }
  if (surface_ && surface_ != input_) {
    error_message_ = "setSearchSurface is not supported";
    PCL_ERROR("[pcl::%s::compute] setSearchSurface is not supported: the Voronoi cells "
              "are those of the input cloud.\n",
              getClassName().c_str());
    return false;
  }
  if (!surface_) {
    fake_surface_ = true;
    surface_ = input_;
  }
  return true;
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::clearResults(std::size_t rows)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  valid_.assign(rows, 0);
  pole_vectors_.assign(rows, Eigen::Vector3f::Constant(nan));
  heights_.assign(rows, nan);
  radii_.assign(rows, nan);
  ratios_.assign(rows, nan);
  boundary_count_ = 0;
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::fail(const std::string& message,
                                                    PointCloudOut& output)
{
  error_message_ = message;
  PCL_ERROR("[pcl::%s::compute] %s.\n", getClassName().c_str(), error_message_.c_str());
  output.width = output.height = 0;
  output.clear();
  clearResults(0);
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::computeFeature(PointCloudOut& output)
{
  // The core reports its own failures; what remains is this template's copies.
  try {
    estimate(output);
  }
  catch (const std::bad_alloc&) {
    fail("out of memory during boundary detection", output); // allocates nothing
  }
}

template <typename PointInT, typename PointOutT>
void
BoundarySampleEstimation<PointInT, PointOutT>::estimate(PointCloudOut& output)
{
  const std::size_t rows = indices_->size();
  clearResults(rows);
  error_message_.clear();
  warning_message_.clear();

  // The diagram of every finite input point but the far ones; the rows are the indices.
  pcl::Indices all(input_->size());
  std::iota(all.begin(), all.end(), 0);
  const cocone::CloudSamples samples =
      cocone::gatherSamples(*input_, all, voronoi_parameters_.threads);
  far_indices_ = samples.far;
  std::vector<cocone::SampleIndex> sample_of(input_->size(), cocone::kNoSample);
  for (std::size_t s = 0; s < samples.cloud_index.size(); ++s)
    sample_of[samples.cloud_index[s]] = static_cast<cocone::SampleIndex>(s);

  cocone::VoronoiCocone voronoi(voronoi_parameters_);
  const cocone::Status status =
      voronoi.compute(samples.points, cocone::progressPart(progress_, 0, 0.9));
  warning_message_ = cocone::describeSampleProblems(
      *input_, samples, voronoi.typicalSpacing(), "their rows invalid");
  if (!warning_message_.empty())
    PCL_WARN("[pcl::%s::compute] %s.\n", getClassName().c_str(),
             warning_message_.c_str());
  if (status != cocone::Status::ok)
    return fail(voronoi.errorMessage(), output);
  std::vector<std::uint8_t> is_boundary;
  std::string message;
  if (cocone::detectBoundarySamples(voronoi, parameters_, is_boundary, &message) !=
      cocone::Status::ok)
    return fail(message, output);
  if (progress_ && !progress_(1))
    return fail("cancelled", output);

  for (std::size_t row = 0; row < rows; ++row) {
    const cocone::SampleIndex s = sample_of[(*indices_)[row]];
    if (s == cocone::kNoSample) {
      output[row].boundary_point = 0;
      output.is_dense = false;
      continue;
    }
    valid_[row] = 1;
    output[row].boundary_point = is_boundary[s];
    boundary_count_ += is_boundary[s];
    pole_vectors_[row] = voronoi.poleVector(s).cast<float>();
    heights_[row] = static_cast<float>(voronoi.height(s));
    radii_[row] = static_cast<float>(voronoi.coconeRadius(s));
    ratios_[row] = static_cast<float>(voronoi.ratio(s));
  }
}

} // namespace pcl

#define PCL_INSTANTIATE_BoundarySampleEstimation(T, OutT)                              \
  template class PCL_COCONE_EXPORT pcl::BoundarySampleEstimation<T, OutT>;
