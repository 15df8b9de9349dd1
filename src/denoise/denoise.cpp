// SPDX-License-Identifier: GPL-3.0-or-later
// Noise estimation and scale-space smoothing (core/denoise.h): local quadric fits over
// k-nearest-neighbour sets.
#include "common/parallel.h"

#include <pcl/cocone/core/denoise.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace pcl {
namespace cocone {

namespace {

/** The \a k nearest samples of each query (the query among them), nearest first, as
 * \a k indices per query in one flat array. */
std::vector<std::uint32_t>
nearestNeighbours(const std::vector<Eigen::Vector3d>& points,
                  const std::vector<std::uint32_t>& queries, unsigned k,
                  unsigned threads)
{
  // FLANN works in floats: centre the samples first, so that large coordinates (UTM)
  // keep the precision that tells neighbours apart.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    centre += p;
  centre /= static_cast<double>(points.size());
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = points[i] - centre;
    (*cloud)[i] = pcl::PointXYZ(static_cast<float>(c.x()), static_cast<float>(c.y()),
                                static_cast<float>(c.z()));
  }
  pcl::KdTreeFLANN<pcl::PointXYZ> tree(true);
  tree.setInputCloud(cloud);
  std::vector<std::uint32_t> neighbours(queries.size() * k);
  detail::runInArena(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        pcl::Indices found;
                        std::vector<float> distances;
                        for (std::size_t q = range.begin(); q != range.end(); ++q) {
                          tree.nearestKSearch((*cloud)[queries[q]], static_cast<int>(k),
                                              found, distances);
                          // FLANN returns them in the order its search met them, which
                          // depends on the query alone: identical queries get identical
                          // lists.
                          for (unsigned j = 0; j < k; ++j)
                            neighbours[q * k + j] = static_cast<std::uint32_t>(
                                j < found.size() ? found[j] : queries[q]);
                        }
                      });
  });
  return neighbours;
}

/** The most neighbours a fit takes. */
constexpr unsigned kMaxFitPoints = 2 * kNoiseNeighbours;

/** A quadric height field fitted to a neighbourhood. */
struct LocalQuadric
{
  unsigned points = 0;
  bool valid = false;
  Eigen::Vector3d origin;  // the neighbourhood's centroid
  Eigen::Vector3d u, v, n; // its principal axes, n the normal
  double scale = 0;        // radius of the neighbourhood in the (u, v) plane
  Eigen::Matrix<double, 6, 1>
      coefficients;    // h = c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2
  double residual = 0; // RMS distance from the quadric (10 degrees of freedom)
  /** The smallest over the middle eigenvalue of the neighbourhood's covariance: near 0
   * for a patch of a surface, near 1 for samples that fill a volume. */
  double thickness = 0;

  double
  height(double s, double t) const
  {
    return coefficients[0] + coefficients[1] * s + coefficients[2] * t +
           coefficients[3] * s * s + coefficients[4] * s * t + coefficients[5] * t * t;
  }

  /** The local spacing: that of evenly spread samples filling the disc. */
  double
  spacing() const
  {
    return scale * std::sqrt(M_PI / points);
  }
};

/** Fits a quadric height field over the principal plane of the \a k neighbours \a ids
 * (7 to kMaxFitPoints of them) of \a positions. */
LocalQuadric
fitQuadric(const std::vector<Eigen::Vector3d>& positions, const std::uint32_t* ids,
           unsigned k)
{
  LocalQuadric fit;
  fit.points = k;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (unsigned j = 0; j < k; ++j)
    centroid += positions[ids[j]];
  centroid /= k;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (unsigned j = 0; j < k; ++j) {
    const Eigen::Vector3d d = positions[ids[j]] - centroid;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  if (eigen.info() != Eigen::Success)
    return fit;
  if (!(eigen.eigenvalues()[1] > 0))
    return fit; // the samples lie along a line
  fit.thickness = eigen.eigenvalues()[0] / eigen.eigenvalues()[1];
  fit.origin = centroid;
  fit.n = eigen.eigenvectors().col(0);
  fit.v = eigen.eigenvectors().col(1);
  fit.u = eigen.eigenvectors().col(2);
  // Fixed largest sizes: no allocation per fit.
  using Design = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, kMaxFitPoints, 6>;
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxFitPoints, 1>;
  Design design(k, 6);
  Column heights(k);
  Eigen::Matrix<double, Eigen::Dynamic, 2, 0, kMaxFitPoints, 2> plane(k, 2);
  double radius = 0;
  for (unsigned j = 0; j < k; ++j) {
    const Eigen::Vector3d d = positions[ids[j]] - centroid;
    plane(j, 0) = d.dot(fit.u);
    plane(j, 1) = d.dot(fit.v);
    heights[j] = d.dot(fit.n);
    radius = std::max(radius, plane.row(j).norm());
  }
  if (!(radius > 0))
    return fit;
  fit.scale = radius;
  for (unsigned j = 0; j < k; ++j) {
    const double s = plane(j, 0) / radius, t = plane(j, 1) / radius;
    design.row(j) << 1, s, t, s * s, s * t, t * t;
  }
  // The normal equations, over (s, t) scaled to the unit disc: well conditioned unless
  // the samples lie along a line (one scan row), which leaves the quadric undetermined;
  // such a neighbourhood measures nothing.
  const Eigen::Matrix<double, 6, 6> normal = design.transpose() * design;
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(normal);
  const Eigen::Matrix<double, 6, 1> pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > 1e-9 * pivots.maxCoeff()))
    return fit;
  fit.coefficients = ldlt.solve(design.transpose() * heights);
  fit.residual =
      std::sqrt((design * fit.coefficients - heights).squaredNorm() / (k - 6));
  fit.valid = true;
  return fit;
}

/** Up to kNoiseProbes sample indices spread evenly over [0, n). */
std::vector<std::uint32_t>
probeSamples(std::size_t n)
{
  const std::size_t count = std::min(n, kNoiseProbes);
  std::vector<std::uint32_t> probes(count);
  for (std::size_t j = 0; j < count; ++j)
    probes[j] = static_cast<std::uint32_t>(j * n / count);
  return probes;
}

/** The noise at one probe, from the quadrics fitted to its nearest kNoiseNeighbours
 * and 2 kNoiseNeighbours samples (\a ids, nearest first), in local spacings; NaN when
 * either fit failed. An exact sample of a smooth surface leaves a residual that grows
 * with the cube of the neighbourhood's radius r (the terms beyond the quadric), noise
 * one that does not: with res^2 = sigma^2 + c r^6 at both radii, sigma^2 is what is
 * left at radius 0. On a coarse cloud (PCL's 397-point bunny, Power Crust's knot) the
 * residual at one radius alone is 0.14 to 0.7 spacings, as much as strong noise. */
double
probeNoise(const std::vector<Eigen::Vector3d>& positions, const std::uint32_t* ids)
{
  const LocalQuadric near = fitQuadric(positions, ids, kNoiseNeighbours);
  const LocalQuadric wide = fitQuadric(positions, ids, kMaxFitPoints);
  if (!near.valid || !wide.valid || !(wide.scale > near.scale) ||
      wide.thickness > kMaxPatchThickness)
    return std::numeric_limits<double>::quiet_NaN();
  const double near6 = std::pow(near.scale, 6), wide6 = std::pow(wide.scale, 6);
  const double variance =
      (near.residual * near.residual * wide6 - wide.residual * wide.residual * near6) /
      (wide6 - near6);
  return std::sqrt(std::max(variance, 0.0)) / near.spacing();
}

/** The lower quartile (kNoiseQuantile) of probeNoise over the probes whose neighbours
 * \a neighbours lists (kMaxFitPoints indices each, one probe after the other). */
NoiseEstimate
measureNoise(const std::vector<Eigen::Vector3d>& positions,
             const std::vector<std::uint32_t>& neighbours, unsigned threads)
{
  const std::size_t probe_count = neighbours.size() / kMaxFitPoints;
  std::vector<double> relative(probe_count);
  detail::runInArena(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, probe_count, 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t j = range.begin(); j != range.end(); ++j)
                          relative[j] =
                              probeNoise(positions, &neighbours[j * kMaxFitPoints]);
                      });
  });
  relative.erase(std::remove_if(relative.begin(), relative.end(),
                                [](double r) { return !std::isfinite(r); }),
                 relative.end());
  NoiseEstimate estimate;
  estimate.measured = relative.size();
  // Most neighbourhoods are no patch of a surface: the cloud is too coarse for its
  // surface to be seen at this scale, and smoothing would only fold it further.
  if (relative.empty() || 2 * relative.size() < probe_count)
    return estimate;
  const auto middle =
      relative.begin() + static_cast<std::ptrdiff_t>(
                             static_cast<double>(relative.size()) * kNoiseQuantile);
  std::nth_element(relative.begin(), middle, relative.end());
  estimate.relative_noise = *middle;
  return estimate;
}

} // namespace

NoiseEstimate
estimateNoise(const std::vector<Eigen::Vector3d>& points, unsigned threads)
{
  if (points.size() < kMaxFitPoints)
    return NoiseEstimate();
  const std::vector<std::uint32_t> probes = probeSamples(points.size());
  const std::vector<std::uint32_t> neighbours =
      nearestNeighbours(points, probes, kMaxFitPoints, threads);
  return measureNoise(points, neighbours, threads);
}

SmoothedSamples
smoothSamples(const std::vector<Eigen::Vector3d>& points, unsigned threads)
{
  SmoothedSamples result;
  result.points = points;
  const std::size_t n = points.size();
  if (n < kMaxFitPoints)
    return result;
  std::vector<std::uint32_t> everyone(n);
  for (std::size_t i = 0; i < n; ++i)
    everyone[i] = static_cast<std::uint32_t>(i);
  // The neighbourhoods are chosen once, on the input: the rounds move the samples
  // along the surface's normal only, so the nearest ones along the surface stay the
  // same, and a round costs the fits alone.
  constexpr unsigned k = kMaxFitPoints;
  const std::vector<std::uint32_t> neighbours =
      nearestNeighbours(points, everyone, k, threads);
  std::vector<std::uint32_t> probe_neighbours;
  for (const std::uint32_t p : probeSamples(n))
    probe_neighbours.insert(probe_neighbours.end(),
                            neighbours.begin() + std::size_t(p) * k,
                            neighbours.begin() + (std::size_t(p) + 1) * k);
  std::vector<Eigen::Vector3d> next(n);
  while (result.rounds < kMaxSmoothingRounds) {
    const std::vector<Eigen::Vector3d>& current = result.points;
    detail::runInArena(threads, [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            const LocalQuadric fit =
                                fitQuadric(current, &neighbours[i * k], k);
                            next[i] = current[i];
                            if (!fit.valid)
                              continue;
                            const Eigen::Vector3d d = current[i] - fit.origin;
                            const double s = d.dot(fit.u) / fit.scale;
                            const double t = d.dot(fit.v) / fit.scale;
                            next[i] += (fit.height(s, t) - d.dot(fit.n)) * fit.n;
                          }
                        });
    });
    result.points.swap(next);
    ++result.rounds;
    result.remaining_noise =
        measureNoise(result.points, probe_neighbours, threads).relative_noise;
    if (result.remaining_noise < kNoiseThreshold / 2)
      break;
  }
  return result;
}

} // namespace cocone
} // namespace pcl
