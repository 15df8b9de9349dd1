// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the state behind VoronoiCocone, and the door through which the core's own
// algorithms reach it (decimation consumes it). Free of CGAL. Never installed.
#pragma once

#include "voronoi/delaunay_stars.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** The state behind VoronoiCocone; shared with decimation. Per-sample arrays are
 * indexed by input index and filled for representatives only. */
struct VoronoiCocone::Impl
{
  Status status = Status::not_computed;
  VoronoiCocone::Timings timings;
  std::string message;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centered; // the diagram's points: smoothed when denoised
  // The samples as given, centered, when the diagram was built on a smoothed copy;
  // empty otherwise (then they are #centered).
  std::vector<Eigen::Vector3d> input_centered;
  NoiseEstimate noise;
  unsigned smoothing_rounds = 0;
  std::vector<SampleIndex> representative;
  detail::DelaunayStars stars; // after compute(); cleared by decimate()
  std::size_t unique_count = 0;

  std::vector<Eigen::Vector3d> pole_vector;
  std::vector<Eigen::Vector3d> positive_pole; // centered frame
  std::vector<Eigen::Vector3d> negative_pole; // centered frame
  std::vector<double> height;                 // NaN: no negative pole
  std::vector<double> radius;                 // +inf: unbounded cocone
  std::vector<std::uint8_t> unbounded;

  std::vector<MarkedTriangle> triangles;
  std::vector<std::uint32_t> triangle_offsets; // CSR by sample, size n + 1
  std::vector<std::uint32_t> triangle_ids;

  double
  ratio(SampleIndex i) const
  {
    const double h = height[i];
    const double r = radius[i];
    if (!(h > 0) || !std::isfinite(r))
      return std::numeric_limits<double>::infinity();
    return r / h;
  }
};

namespace detail {

/** The core's own access to a VoronoiCocone's state. */
struct VoronoiCoconeAccess
{
  using State = VoronoiCocone::Impl;

  static State&
  state(VoronoiCocone& voronoi)
  {
    return *voronoi.impl_;
  }
  static const State&
  state(const VoronoiCocone& voronoi)
  {
    return *voronoi.impl_;
  }
};

/** The state behind a VoronoiCocone, as the core's algorithms name it. */
using DiagramState = VoronoiCoconeAccess::State;

} // namespace detail
} // namespace cocone
} // namespace pcl
