// SPDX-License-Identifier: GPL-3.0-or-later
// Checks on the samples before any geometry (core/sample_checks.h).
#include <pcl/cocone/core/sample_checks.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl {
namespace cocone {

namespace {

/** The median of \a values (the upper one of an even count); reorders them. */
double
median(std::vector<double>& values)
{
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

} // namespace

CloudScale
cloudScale(const std::vector<Eigen::Vector3d>& points)
{
  CloudScale scale;
  if (points.empty())
    return scale;
  std::vector<double> values(points.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < points.size(); ++i)
      values[i] = points[i][axis];
    scale.centre[axis] = median(values);
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    values[i] = (points[i] - scale.centre).norm();
  scale.radius = median(values);
  if (scale.radius == 0) { // half the points or more at the centre: the others decide
    values.erase(std::remove(values.begin(), values.end(), 0.0), values.end());
    scale.radius = values.empty() ? 0 : median(values);
  }
  return scale;
}

std::vector<std::uint8_t>
findFarPoints(const std::vector<Eigen::Vector3d>& points)
{
  std::vector<std::uint8_t> far(points.size(), 0);
  const CloudScale scale = cloudScale(points);
  if (!(scale.radius > 0))
    return far;
  const double limit = kFarPointFactor * scale.radius;
  for (std::size_t i = 0; i < points.size(); ++i)
    far[i] = (points[i] - scale.centre).norm() > limit;
  return far;
}

double
floatRoundingStep(const std::vector<Eigen::Vector3d>& points)
{
  double largest = 0;
  for (const Eigen::Vector3d& p : points)
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (largest == 0)
    return 0;
  const float nearest = static_cast<float>(largest);
  if (!std::isfinite(nearest))
    return std::numeric_limits<double>::infinity(); // beyond what a float holds
  return static_cast<double>(
             std::nextafter(nearest, std::numeric_limits<float>::max())) -
         static_cast<double>(nearest);
}

} // namespace cocone
} // namespace pcl
