// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/cloud_samples.h>
#include <pcl/cocone/core/decimation.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/parameters.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

namespace pcl {

template <typename PointT>
void
VoronoiDecimation<PointT>::setRatioBound(double rho)
{
  if (cocone::acceptParameter(getClassName(), "setRatioBound", "rho", rho,
                              cocone::kRatioBoundRange, parameters_.ratio_bound))
    parameters_.ratio_bound = rho;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::setCoconeAngle(double theta)
{
  if (cocone::acceptParameter(getClassName(), "setCoconeAngle", "theta", theta,
                              cocone::kCoconeAngleRange,
                              voronoi_parameters_.cocone_angle))
    voronoi_parameters_.cocone_angle = theta;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::setRelaxationIterations(unsigned iterations)
{
  if (cocone::acceptParameter(getClassName(), "setRelaxationIterations", "iterations",
                              iterations, cocone::kRelaxationIterationsRange,
                              parameters_.relaxation_iterations))
    parameters_.relaxation_iterations = iterations;
}

template <typename PointT>
bool
VoronoiDecimation<PointT>::decimate(const cocone::DecimationParameters& parameters)
{
  // The core reports its own failures; what remains is this template's copies.
  try {
    return decimateSelection(parameters);
  }
  catch (const std::bad_alloc&) {
    std::vector<double>().swap(removal_levels_);
    pcl::Indices().swap(far_indices_);
    error_message_ = "out of memory during decimation";
    PCL_ERROR("[pcl::%s::filter] %s.\n", getClassName().c_str(),
              error_message_.c_str());
    return false;
  }
}

template <typename PointT>
bool
VoronoiDecimation<PointT>::decimateSelection(
    const cocone::DecimationParameters& parameters)
{
  removal_levels_.assign(input_->size(), std::numeric_limits<double>::quiet_NaN());
  error_message_.clear();
  warning_message_.clear();
  const cocone::CloudSamples samples =
      cocone::gatherSamples(*input_, *indices_, voronoi_parameters_.threads);
  far_indices_ = samples.far;

  const auto fail = [&](const std::string& message) {
    error_message_ = message;
    PCL_ERROR("[pcl::%s::filter] %s.\n", getClassName().c_str(),
              error_message_.c_str());
    return false;
  };
  cocone::VoronoiCocone voronoi(voronoi_parameters_);
  // The diagram takes about half of a run, DECIMATE and the relaxation the rest.
  const cocone::Status status =
      voronoi.compute(samples.points, cocone::progressPart(progress_, 0, 0.5));
  warning_message_ = cocone::describeSampleProblems(
      *input_, samples, voronoi.typicalSpacing(), "never kept");
  if (!warning_message_.empty())
    PCL_WARN("[pcl::%s::filter] %s.\n", getClassName().c_str(),
             warning_message_.c_str());
  if (status != cocone::Status::ok)
    return fail(voronoi.errorMessage());
  // BOUNDARY runs here, once, on the full sample: rims are thinned from its flags, and
  // the relaxation holds them (rims and sharp features).
  std::vector<std::uint8_t> boundary;
  std::string message;
  if ((parameters.thin_rims || parameters.relaxation_iterations > 0) &&
      cocone::detectBoundarySamples(voronoi, cocone::BoundaryParameters(), boundary,
                                    &message) != cocone::Status::ok)
    return fail(message);
  cocone::DecimationLevels levels;
  if (cocone::decimate(std::move(voronoi), parameters, boundary, levels,
                       cocone::progressPart(progress_, 0.5, 1),
                       &message) != cocone::Status::ok)
    return fail(message);
  for (std::size_t s = 0; s < samples.cloud_index.size(); ++s)
    removal_levels_[samples.cloud_index[s]] = levels.level[s];
  PCL_DEBUG("[pcl::%s::filter] %zu of %zu finite points removed up to rho = %g; the "
            "relaxation moved %zu.\n",
            getClassName().c_str(), levels.removals, samples.points.size(),
            parameters.ratio_bound, levels.relaxation_moves);
  return true;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::applyFilter(Indices& indices)
{
  indices.clear();
  removed_indices_->clear();
  if (!decimate(parameters_))
    return;
  for (const pcl::index_t i : *indices_) {
    const double level = removal_levels_[i];
    const bool finite = !std::isnan(level);
    const bool kept = finite && level >= parameters_.ratio_bound;
    // Non-finite points are never output, with or without setNegative.
    if (finite && kept != negative_)
      indices.push_back(i);
    else if (extract_removed_indices_)
      removed_indices_->push_back(i);
  }
}

template <typename PointT>
bool
VoronoiDecimation<PointT>::computeLevelsOfDetail(
    const std::vector<double>& ratio_bounds, std::vector<pcl::Indices>& kept)
{
  kept.clear();
  if (ratio_bounds.empty())
    return true;
  for (const double rho : ratio_bounds)
    if (!cocone::acceptParameter(getClassName(), "computeLevelsOfDetail", "rho", rho,
                                 cocone::kRatioBoundRange, parameters_.ratio_bound))
      return false;
  if (!this->initCompute())
    return false;
  // DECIMATE's own nested sets: up to the largest rho, without relaxation.
  cocone::DecimationParameters parameters = parameters_;
  parameters.ratio_bound = *std::max_element(ratio_bounds.begin(), ratio_bounds.end());
  parameters.relaxation_iterations = 0;
  const bool ok = decimate(parameters);
  if (ok) {
    kept.resize(ratio_bounds.size());
    for (std::size_t k = 0; k < ratio_bounds.size(); ++k)
      for (const pcl::index_t i : *indices_)
        if (removal_levels_[i] >= ratio_bounds[k])
          kept[k].push_back(i);
  }
  this->deinitCompute();
  return ok;
}

} // namespace pcl

#define PCL_INSTANTIATE_VoronoiDecimation(T)                                           \
  template class PCL_COCONE_EXPORT pcl::VoronoiDecimation<T>;
