// SPDX-License-Identifier: GPL-3.0-or-later
// Private: how a Voronoi edge meets a cocone, the one test behind the cocone radius,
// the cocone marks and the clipped cells of decimation. Free of CGAL. Never installed.
#pragma once

#include <Eigen/Core>

namespace pcl {
namespace cocone {
namespace detail {

/** Classification of a point relative to the double cone of a cocone. */
enum class ConeSide
{
  upper,  // cos(angle(x, v)) > sin(theta)
  inside, // |cos| <= sin(theta): in the cocone
  lower   // cos < -sin(theta)
};

/** How a Voronoi edge (segment or ray, relative to the sample) meets a cocone. */
struct EdgeInCocone
{
  bool meets = false;       // some point of the edge lies in the cocone
  bool unbounded = false;   // the ray's direction lies in the cocone: r_p is infinite
  double max_distance2 = 0; // largest squared distance from p of a point inside
};

/** Clips the Voronoi edge start + t * direction (t in [0, 1] for a segment, t >= 0 for
 * a ray), given relative to the sample, against the cocone of axis \a axis (unit) and
 * angle theta (sin_theta = sin(theta)). */
EdgeInCocone
clipVoronoiEdge(const Eigen::Vector3d& start, const Eigen::Vector3d& direction,
                bool is_ray, const Eigen::Vector3d& axis, double sin_theta);

} // namespace detail
} // namespace cocone
} // namespace pcl
