// SPDX-License-Identifier: GPL-3.0-or-later
// Noise estimation and scale-space smoothing (core/denoise.h): local quadric fits over
// k-nearest-neighbour sets.
#include "common/parallel.h"

#include <pcl/cocone/core/denoise.h>

#include <Eigen/Dense>
#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
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
  std::vector<float> coordinates(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int axis = 0; axis < 3; ++axis)
      coordinates[3 * i + axis] = static_cast<float>(points[i][axis] - centre[axis]);
  // FLANN's own single kd-tree (findNeighbors is const: threads may search it at once),
  // searched one query at a time into a result set of the task's. PCL's KdTreeFLANN
  // wraps the same tree, but each of its searches opens an OpenMP region and converts
  // its lists, which took as long as the search itself.
  const flann::Matrix<float> dataset(coordinates.data(), points.size(), 3);
  flann::KDTreeSingleIndex<flann::L2_Simple<float>> tree(
      dataset, flann::KDTreeSingleIndexParams(15));
  tree.buildIndex();
  const flann::SearchParams exact(flann::FLANN_CHECKS_UNLIMITED, 0, true);
  std::vector<std::uint32_t> neighbours(queries.size() * k);
  detail::runInArena(threads, [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, queries.size(), 256),
        [&](const tbb::blocked_range<std::size_t>& range) {
          flann::KNNSimpleResultSet<float> found(k);
          std::vector<std::size_t> ids(k);
          std::vector<float> distances(k);
          for (std::size_t q = range.begin(); q != range.end(); ++q) {
            found.clear();
            tree.findNeighbors(found, &coordinates[3 * std::size_t(queries[q])], exact);
            const std::size_t count = std::min<std::size_t>(found.size(), k);
            found.copy(ids.data(), distances.data(), count, true);
            // Nearest first, equal distances in the order the search met them, which
            // depends on the query and the tree (built from the samples in the
            // classes' spatial order), not on the thread: identical queries get
            // identical lists.
            for (unsigned j = 0; j < k; ++j)
              neighbours[q * k + j] =
                  static_cast<std::uint32_t>(j < count ? ids[j] : queries[q]);
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
  double residual = 0; // RMS distance from the quadric, when Residual::measure
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

/** Whether fitQuadric measures the RMS residual (the noise estimate needs it; the
 * smoothing rounds only move samples onto the quadric). */
enum class Residual
{
  skip,
  measure,
};

/** Fits a quadric height field over the principal plane of the \a k neighbours \a ids
 * (7 to kMaxFitPoints of them) of \a positions. */
LocalQuadric
fitQuadric(const std::vector<Eigen::Vector3d>& positions, const std::uint32_t* ids,
           unsigned k, Residual residual)
{
  assert(k > 6 && k <= kMaxFitPoints); // 6 coefficients; fixed-size buffers below
  LocalQuadric fit;
  fit.points = k;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (unsigned j = 0; j < k; ++j)
    centroid += positions[ids[j]];
  centroid /= k;
  // Six scalar sums: Eigen's outer product d d^T goes through the stack in halves that
  // the next sum reads whole, a store-forwarding stall per sample (perf annotate).
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (unsigned j = 0; j < k; ++j) {
    const Eigen::Vector3d d = positions[ids[j]] - centroid;
    xx += d.x() * d.x();
    xy += d.x() * d.y();
    xz += d.x() * d.z();
    yy += d.y() * d.y();
    yz += d.y() * d.z();
    zz += d.z() * d.z();
  }
  Eigen::Matrix3d covariance;
  covariance << xx, xy, xz, xy, yy, yz, xz, yz, zz;
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
  // Plane coordinates and heights on the stack: no allocation per fit.
  double s[kMaxFitPoints], t[kMaxFitPoints], h[kMaxFitPoints];
  double radius_squared = 0;
  for (unsigned j = 0; j < k; ++j) {
    const Eigen::Vector3d d = positions[ids[j]] - centroid;
    s[j] = d.dot(fit.u);
    t[j] = d.dot(fit.v);
    h[j] = d.dot(fit.n);
    radius_squared = std::max(radius_squared, s[j] * s[j] + t[j] * t[j]);
  }
  if (!(radius_squared > 0))
    return fit;
  fit.scale = std::sqrt(radius_squared);
  // The least-squares system over the monomials 1, s, t, s^2, s t, t^2 with (s, t)
  // scaled to the unit disc. Its matrix holds only the 15 moments sum s^a t^b with
  // a + b <= 4, and its right-hand side the 6 sums h s^a t^b with a + b <= 2. Summing
  // them directly, in named scalars for the same reason as the covariance, replaced
  // the k x 6 design matrix and Eigen's product with it (which perf put at a fifth of
  // the smoothing).
  const double m00 = k; // the sum of s^0 t^0
  double m10 = 0, m01 = 0, m20 = 0, m11 = 0, m02 = 0, m30 = 0, m21 = 0, m12 = 0,
         m03 = 0, m40 = 0, m31 = 0, m22 = 0, m13 = 0, m04 = 0;
  double h00 = 0, h10 = 0, h01 = 0, h20 = 0, h11 = 0, h02 = 0;
  const double inverse_scale = 1 / fit.scale;
  for (unsigned j = 0; j < k; ++j) {
    const double a = s[j] * inverse_scale, b = t[j] * inverse_scale, z = h[j];
    s[j] = a;
    t[j] = b;
    const double aa = a * a, ab = a * b, bb = b * b;
    m10 += a;
    m01 += b;
    m20 += aa;
    m11 += ab;
    m02 += bb;
    m30 += aa * a;
    m21 += aa * b;
    m12 += a * bb;
    m03 += bb * b;
    m40 += aa * aa;
    m31 += aa * ab;
    m22 += aa * bb;
    m13 += ab * bb;
    m04 += bb * bb;
    h00 += z;
    h10 += z * a;
    h01 += z * b;
    h20 += z * aa;
    h11 += z * ab;
    h02 += z * bb;
  }
  const double moment[5][5] = {{m00, m01, m02, m03, m04},
                               {m10, m11, m12, m13, 0},
                               {m20, m21, m22, 0, 0},
                               {m30, m31, 0, 0, 0},
                               {m40, 0, 0, 0, 0}};
  const double height_moment[3][3] = {{h00, h01, h02}, {h10, h11, 0}, {h20, 0, 0}};
  static constexpr int kPowerOfS[6] = {0, 1, 0, 2, 1, 0};
  static constexpr int kPowerOfT[6] = {0, 0, 1, 0, 1, 2};
  Eigen::Matrix<double, 6, 6> normal;
  Eigen::Matrix<double, 6, 1> right;
  for (int row = 0; row < 6; ++row) {
    for (int column = 0; column < 6; ++column)
      normal(row, column) = moment[kPowerOfS[row] + kPowerOfS[column]]
                                  [kPowerOfT[row] + kPowerOfT[column]];
    right[row] = height_moment[kPowerOfS[row]][kPowerOfT[row]];
  }
  // Well conditioned unless the samples lie along a line (one scan row), which leaves
  // the quadric undetermined; such a neighbourhood measures nothing.
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(normal);
  const Eigen::Matrix<double, 6, 1> pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > 1e-9 * pivots.maxCoeff()))
    return fit;
  fit.coefficients = ldlt.solve(right);
  if (residual == Residual::measure) {
    double sum = 0;
    for (unsigned j = 0; j < k; ++j) {
      const double off = fit.height(s[j], t[j]) - h[j];
      sum += off * off;
    }
    fit.residual = std::sqrt(sum / (k - 6));
  }
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
  const LocalQuadric near =
      fitQuadric(positions, ids, kNoiseNeighbours, Residual::measure);
  const LocalQuadric wide =
      fitQuadric(positions, ids, kMaxFitPoints, Residual::measure);
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
                            const LocalQuadric fit = fitQuadric(
                                current, &neighbours[i * k], k, Residual::skip);
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
