// SPDX-License-Identifier: GPL-3.0-or-later
#include "voronoi/cocone_edge.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl {
namespace cocone {

namespace detail {

// ---------------------------------------------------------------------------------
namespace {

ConeSide
classify(const Eigen::Vector3d& x, const Eigen::Vector3d& axis, double sin_theta)
{
  const double along = x.dot(axis);
  const double limit = sin_theta * x.norm();
  if (along > limit)
    return ConeSide::upper;
  if (along < -limit)
    return ConeSide::lower;
  return ConeSide::inside;
}

} // namespace

EdgeInCocone
clipVoronoiEdge(const Eigen::Vector3d& start, const Eigen::Vector3d& direction,
                bool is_ray, const Eigen::Vector3d& axis, double sin_theta)
{
  EdgeInCocone result;
  const ConeSide side_start = classify(start, axis, sin_theta);
  // A ray's far end is classified by its direction.
  const ConeSide side_end = classify(
      is_ray ? direction : Eigen::Vector3d(start + direction), axis, sin_theta);
  // Each nappe of the double cone is convex: a segment with both ends in the same nappe
  // stays in it; otherwise it crosses the cocone.
  result.meets = side_start == ConeSide::inside || side_end == ConeSide::inside ||
                 side_start != side_end;
  if (!result.meets)
    return result;
  if (is_ray && side_end == ConeSide::inside) {
    result.unbounded = true;
    return result;
  }
  // Points x(t) = start + t direction inside the cocone satisfy
  //   f(t) = (x.axis)^2 - sin^2 |x|^2 <= 0,
  // a quadratic a t^2 + 2 b t + c. |x(t)| is convex in t, so its maximum over the
  // feasible part sits at an end of a feasible interval: an end of the edge that is
  // inside, or a root of f.
  const double s2 = sin_theta * sin_theta;
  const double sv = start.dot(axis);
  const double dv = direction.dot(axis);
  const double a = dv * dv - s2 * direction.squaredNorm();
  const double b = sv * dv - s2 * start.dot(direction);
  const double c = sv * sv - s2 * start.squaredNorm();
  const double t_max = is_ray ? std::numeric_limits<double>::infinity() : 1.0;
  double best = 0;
  const auto consider = [&](double t) {
    if (t >= 0 && t <= t_max)
      best = std::max(best, (start + t * direction).squaredNorm());
  };
  if (side_start == ConeSide::inside)
    consider(0);
  if (!is_ray && side_end == ConeSide::inside)
    consider(1);
  const double scale = std::abs(a) + std::abs(b) + std::abs(c);
  if (std::abs(a) > 1e-14 * scale) {
    const double disc = b * b - a * c;
    if (disc >= 0) {
      // Numerically stable roots of a t^2 + 2 b t + c.
      const double q = -(b + std::copysign(std::sqrt(disc), b));
      consider(q / a);
      if (q != 0)
        consider(c / q);
    }
    else {
      consider(-b / a); // rounding hid a tangency: take the closest approach
    }
  }
  else if (b != 0) {
    consider(-c / (2 * b));
  }
  result.max_distance2 = best;
  return result;
}

} // namespace detail

} // namespace cocone
} // namespace pcl
