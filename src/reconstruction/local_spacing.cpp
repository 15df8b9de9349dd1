// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/local_spacing.h"

#include "common/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace pcl {
namespace cocone {
namespace detail {

// Local spacing: the distance from a sample to its third nearest neighbour among the
// samples it shares a marked triangle with. On an evenly spread sample it is about
// 1.1 sqrt(area / n); unlike the cocone radius it does not grow at the rim of a hole.
std::vector<double>
measureLocalSpacing(const VoronoiCocone& voronoi)
{
  const std::vector<Eigen::Vector3d>& points = voronoi.centeredPoints();
  const std::vector<MarkedTriangle>& marked = voronoi.markedTriangles();
  const std::size_t n = voronoi.size();
  std::vector<double> spacing(n, 0);
  runInArena(voronoi.getNumberOfThreads(), [&] {
    tbb::parallel_for(
        tbb::blocked_range<SampleIndex>(0, static_cast<SampleIndex>(n), 1024),
        [&](const tbb::blocked_range<SampleIndex>& range) {
          std::vector<double> distances;
          for (SampleIndex p = range.begin(); p != range.end(); ++p) {
            distances.clear();
            for (const std::uint32_t t : voronoi.trianglesAround(p))
              for (const SampleIndex v : marked[t].vertex)
                if (v != p)
                  distances.push_back((points[v] - points[p]).squaredNorm());
            std::sort(distances.begin(), distances.end());
            distances.erase(std::unique(distances.begin(), distances.end()),
                            distances.end());
            if (!distances.empty())
              spacing[p] =
                  std::sqrt(distances[std::min<std::size_t>(distances.size(), 3) - 1]);
          }
        });
  });
  return spacing;
}

double
typicalSpacing(const std::vector<double>& spacing,
               const std::vector<SampleIndex>& samples)
{
  std::vector<double> values;
  values.reserve(samples.size());
  for (const SampleIndex v : samples)
    if (spacing[v] > 0)
      values.push_back(spacing[v]);
  if (values.empty())
    return 0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The size of a hole or of a patch: twice its area over its perimeter, which is the
// radius for a disc and half the width for a long strip. A hole is a true boundary
// when this radius exceeds true_boundary_ratio local spacings (paper 3.4.2 compares the
// circumradii of the triangles that would fill it with those of its neighbours, but on
// scans the fills of true holes are fans of long, thin triangles whose circumradii are
// no larger than those of many fills of small gaps; this measure separates them).
bool
isTrueBoundary(double area, double perimeter, double spacing,
               double true_boundary_ratio)
{
  return perimeter > 0 && 2 * area / perimeter > true_boundary_ratio * spacing;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
