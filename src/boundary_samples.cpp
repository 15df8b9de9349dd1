// SPDX-License-Identifier: GPL-3.0-or-later
#include <pcl/cocone/boundary_samples.h>
#include <pcl/cocone/parameters.h>

#include <algorithm>
#include <cmath>

namespace pcl {
namespace cocone {

bool
isValid(const BoundaryParameters& parameters)
{
  return kRatioBoundRange.contains(parameters.ratio_bound) &&
         kNormalAngleRange.contains(parameters.normal_angle) &&
         kBandRingsRange.contains(parameters.band_rings);
}

namespace {

/** The cocone-neighbour graph made symmetric: p and q are linked when one's cocone
 * meets the other's cell. Calls visit(q) for each such q of p (with repeats). */
template <typename Visit>
void
forEachCoconeLink(const VoronoiCocone& voronoi, SampleIndex p, Visit&& visit)
{
  const std::vector<MarkedTriangle>& triangles = voronoi.markedTriangles();
  for (const std::uint32_t t : voronoi.trianglesAround(p)) {
    const MarkedTriangle& triangle = triangles[t];
    int self = 0;
    while (triangle.vertex[self] != p)
      ++self;
    for (int k = 0; k < 3; ++k) {
      if (k == self)
        continue;
      if (triangle.isMarkedBy(self) || triangle.isMarkedBy(k))
        visit(triangle.vertex[k]);
    }
  }
}

} // namespace

std::size_t
detectBoundarySamples(const VoronoiCocone& voronoi,
                      const BoundaryParameters& parameters,
                      std::vector<std::uint8_t>& is_boundary)
{
  const std::size_t n = voronoi.size();
  is_boundary.assign(n, 0);
  if (voronoi.status() != Status::ok)
    return 0;
  const double cos_alpha = std::cos(parameters.normal_angle);
  // Both conditions compare pole *lines*: orientation is ignored.
  const auto agree = [&](SampleIndex p, SampleIndex q) {
    return std::abs(voronoi.poleVector(p).dot(voronoi.poleVector(q))) >= cos_alpha;
  };

  std::vector<std::uint8_t> thin(n, 0); // ratio condition
  for (std::size_t i = 0; i < n; ++i)
    thin[i] = voronoi.representative(static_cast<SampleIndex>(i)) == i &&
              voronoi.ratio(static_cast<SampleIndex>(i)) <= parameters.ratio_bound;

  // Normal condition: every q whose cocone meets V_p (p in N_q) agrees with p.
  std::vector<std::uint8_t> disagrees(n, 0);
  for (const MarkedTriangle& triangle : voronoi.markedTriangles())
    for (int k = 0; k < 3; ++k) {
      if (!triangle.isMarkedBy(k))
        continue;
      const SampleIndex q = triangle.vertex[k];
      for (int m = 0; m < 3; ++m)
        if (m != k && !agree(triangle.vertex[m], q))
          disagrees[triangle.vertex[m]] = 1;
    }

  // R: the flat samples, grown through cocone neighbours (p in N_q, q in R) that are
  // thin and agree with q. A reachability closure: the traversal order does not matter.
  std::vector<std::uint8_t> interior(n, 0);
  std::vector<SampleIndex> queue;
  for (std::size_t i = 0; i < n; ++i)
    if (thin[i] && !disagrees[i]) {
      interior[i] = 1;
      queue.push_back(static_cast<SampleIndex>(i));
    }
  std::vector<SampleIndex> neighbours;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const SampleIndex q = queue[head];
    voronoi.coconeNeighbours(q, neighbours);
    for (const SampleIndex p : neighbours) {
      if (interior[p] || !thin[p] || !agree(p, q))
        continue;
      interior[p] = 1;
      queue.push_back(p);
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const SampleIndex r = voronoi.representative(static_cast<SampleIndex>(i));
    is_boundary[i] = r == i && !interior[i];
  }

  // Optional band: rings of cocone neighbours around the flags.
  std::vector<SampleIndex> frontier;
  for (std::size_t i = 0; i < n; ++i)
    if (is_boundary[i])
      frontier.push_back(static_cast<SampleIndex>(i));
  std::vector<SampleIndex> next;
  for (unsigned ring = 0; ring < parameters.band_rings && !frontier.empty(); ++ring) {
    next.clear();
    for (const SampleIndex p : frontier)
      forEachCoconeLink(voronoi, p, [&](SampleIndex q) {
        if (!is_boundary[q]) {
          is_boundary[q] = 1;
          next.push_back(q);
        }
      });
    frontier.swap(next);
  }

  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    is_boundary[i] = is_boundary[voronoi.representative(static_cast<SampleIndex>(i))];
    count += is_boundary[i];
  }
  return count;
}

} // namespace cocone
} // namespace pcl
