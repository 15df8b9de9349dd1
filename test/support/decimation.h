// SPDX-License-Identifier: GPL-3.0-or-later
// DECIMATE on a diagram as VoronoiDecimation::computeLevelsOfDetail runs it, for the
// tests of the core: BOUNDARY's flags with default parameters, rims thinned, no
// relaxation.
#pragma once

#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/decimation.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

/** Runs decimate() up to \a rho without relaxation, after BOUNDARY (when \a voronoi
 * holds a diagram); consumes \a voronoi as decimate() does. */
inline Status
decimateUpTo(VoronoiCocone&& voronoi, double rho, DecimationLevels& levels,
             const ProgressCallback& progress = nullptr, std::string* message = nullptr)
{
  std::vector<std::uint8_t> boundary;
  if (voronoi.status() == Status::ok)
    detectBoundarySamples(voronoi, BoundaryParameters(), boundary);
  DecimationParameters parameters;
  parameters.ratio_bound = rho;
  parameters.relaxation_iterations = 0;
  return decimate(std::move(voronoi), parameters, boundary, levels, progress, message);
}

} // namespace test
} // namespace cocone
} // namespace pcl
