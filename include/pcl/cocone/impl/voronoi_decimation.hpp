// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/cloud_samples.h>
#include <pcl/cocone/parameters.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace pcl {

template <typename PointT>
void
VoronoiDecimation<PointT>::setRatioBound(double rho)
{
  if (cocone::acceptParameter(getClassName(), "setRatioBound", "rho", rho,
                              cocone::kRatioBoundRange, ratio_bound_))
    ratio_bound_ = rho;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::setCoconeAngle(double theta)
{
  if (cocone::acceptParameter(getClassName(), "setCoconeAngle", "theta", theta,
                              cocone::kCoconeAngleRange, cocone_angle_))
    cocone_angle_ = theta;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::setRelaxationIterations(unsigned iterations)
{
  if (cocone::acceptParameter(getClassName(), "setRelaxationIterations", "iterations",
                              iterations, cocone::kRelaxationIterationsRange,
                              relaxation_iterations_))
    relaxation_iterations_ = iterations;
}

template <typename PointT>
bool
VoronoiDecimation<PointT>::decimate(double rho, bool relax)
{
  removal_levels_.assign(input_->size(), std::numeric_limits<double>::quiet_NaN());
  error_message_.clear();
  std::vector<Eigen::Vector3d> samples;
  pcl::Indices cloud_index;
  cocone::gatherFiniteSamples(*input_, *indices_, samples, cloud_index, nullptr,
                              threads_);

  cocone::VoronoiCocone voronoi;
  voronoi.setCoconeAngle(cocone_angle_);
  voronoi.setNumberOfThreads(threads_);
  cocone::DecimationLevels levels;
  const bool relaxing = relax && relaxation_iterations_ > 0;
  // What the relaxation holds: BOUNDARY's flags on the full sample. decimate() computes
  // them when it thins rims; otherwise they are needed before it changes the diagram.
  std::vector<std::uint8_t> fixed;
  const bool ok = voronoi.compute(samples) == cocone::Status::ok;
  if (ok && relaxing && !thin_rims_)
    cocone::detectBoundarySamples(voronoi, cocone::BoundaryParameters(), fixed);
  if (!ok || voronoi.decimate(rho, levels, nullptr, thin_rims_) != cocone::Status::ok) {
    error_message_ = voronoi.errorMessage();
    PCL_ERROR("[pcl::%s::filter] %s.\n", getClassName().c_str(), error_message_.c_str());
    return false;
  }
  if (relaxing) {
    if (thin_rims_)
      fixed = std::move(levels.boundary);
    std::vector<std::uint8_t> kept(samples.size(), 0);
    for (std::size_t s = 0; s < samples.size(); ++s)
      kept[s] = levels.level[s] >= rho;
    const auto start = std::chrono::steady_clock::now();
    const std::size_t moves = cocone::relaxDecimatedSample(
        voronoi, fixed, relaxation_iterations_, threads_, kept);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The levels stay true to the output: a sample moved to is kept at rho, one moved
    // from is removed just below it. Both stay kept at every smaller rho, so the sets
    // still nest (the smaller ones are DECIMATE's own).
    for (std::size_t s = 0; s < samples.size(); ++s) {
      if (kept[s] && !(levels.level[s] >= rho))
        levels.level[s] = rho;
      else if (!kept[s] && levels.level[s] >= rho)
        levels.level[s] = std::nextafter(rho, 0.0);
    }
    PCL_DEBUG("[pcl::%s::filter] relaxation: %zu moves, %.3f s.\n",
              getClassName().c_str(), moves, seconds);
  }
  for (std::size_t s = 0; s < samples.size(); ++s)
    removal_levels_[cloud_index[s]] = levels.level[s];
  PCL_DEBUG("[pcl::%s::filter] %zu of %zu finite points removed up to rho = %g.\n",
            getClassName().c_str(), levels.removals, samples.size(), rho);
  return true;
}

template <typename PointT>
void
VoronoiDecimation<PointT>::applyFilter(Indices& indices)
{
  indices.clear();
  removed_indices_->clear();
  if (!decimate(ratio_bound_, true))
    return;
  for (const pcl::index_t i : *indices_) {
    const double level = removal_levels_[i];
    const bool finite = !std::isnan(level);
    const bool kept = finite && level >= ratio_bound_;
    // Non-finite points are never output, with or without setNegative.
    if (finite && kept != negative_)
      indices.push_back(i);
    else if (extract_removed_indices_)
      removed_indices_->push_back(i);
  }
}

template <typename PointT>
bool
VoronoiDecimation<PointT>::computeLevelsOfDetail(const std::vector<double>& ratio_bounds,
                                                 std::vector<pcl::Indices>& kept)
{
  kept.clear();
  if (ratio_bounds.empty())
    return true;
  for (const double rho : ratio_bounds)
    if (!cocone::acceptParameter(getClassName(), "computeLevelsOfDetail", "rho", rho,
                                 cocone::kRatioBoundRange, ratio_bound_))
      return false;
  if (!this->initCompute())
    return false;
  const bool ok =
      decimate(*std::max_element(ratio_bounds.begin(), ratio_bounds.end()), false);
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
