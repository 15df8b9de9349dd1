// SPDX-License-Identifier: GPL-3.0-or-later
// Private: walking the cocone-neighbour graph of a VoronoiCocone through its marked
// triangles, and the rim test on it. Shared by BOUNDARY (rim-row completion) and
// DECIMATE (rim samples measured on the side where the surface is). Never installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Calls visit(q, p_marks, q_marks) for each other vertex q of every marked triangle
 * at p (with repeats), saying whether p's cocone and q's cocone mark that triangle. */
template <typename Visit>
void
forEachTriangleNeighbour(const VoronoiCocone& voronoi, SampleIndex p, Visit&& visit)
{
  const std::vector<MarkedTriangle>& triangles = voronoi.markedTriangles();
  for (const std::uint32_t t : voronoi.trianglesAround(p)) {
    const MarkedTriangle& triangle = triangles[t];
    int self = 0;
    while (triangle.vertex[self] != p)
      ++self;
    for (int k = 0; k < 3; ++k)
      if (k != self)
        visit(triangle.vertex[k], triangle.isMarkedBy(self), triangle.isMarkedBy(k));
  }
}

/** The cocone-neighbour graph made symmetric: p and q are linked when one's cocone
 * meets the other's cell. Calls visit(q) for each such q of p (with repeats). */
template <typename Visit>
void
forEachCoconeLink(const VoronoiCocone& voronoi, SampleIndex p, Visit&& visit)
{
  forEachTriangleNeighbour(voronoi, p, [&](SampleIndex q, bool p_marks, bool q_marks) {
    if (p_marks || q_marks)
      visit(q);
  });
}

/** A sample is on the rim when its nearby links leave a gap wider than this in its
 * tangent plane. Around an interior sample the links are the vertices of its umbrella,
 * whose angles at the sample stay below 2 pi / 3 on a good sample; a rim sample sees
 * a gap of about pi. Measured on the benchmark's open surfaces: pi/2 flags the second
 * row too (precision in the row 0.54-0.59), 2.3 misses a tenth of the row (recall
 * 0.87-0.92), 2 pi / 3 finds 0.94-0.96 of it at precision 0.99-1.0. */
constexpr double kRimGapAngle = 2 * M_PI / 3;

/** The widest angular gap between p's nearby cocone links in its tangent plane. */
struct TangentGap
{
  double angle = 2 * M_PI;     ///< radians; 2 pi when fewer than two links remain
  Eigen::Vector3d normal{};    ///< unit normal of the tangent plane used
  double thickness = 0;        ///< fitted plane only: the mean squared distance of the
                               ///< links to it over their mean squared distance along
                               ///< its second axis (0 on a plane; 1 or more across a
                               ///< crease)
  Eigen::Vector3d direction{}; ///< unit vector in the tangent plane through the gap's
                               ///< middle, pointing away from the links; zero when
                               ///< angle is 2 pi
};

/** How widestTangentGap chooses the tangent plane of p. */
enum class TangentPlane
{
  pole_vector, ///< normal to p's pole vector
  fitted       ///< the least-squares plane through p of its nearby links: on a rim
               ///< the pole vector can run along the surface, out through the gap
};

/** The widest gap between the directions from p to its nearby cocone links (links
 * longer than kFarLink times the median are across a hole, not nearby), measured in
 * p's tangent plane. \a links and \a scratch are reused buffers. */
TangentGap
widestTangentGap(const VoronoiCocone& voronoi, SampleIndex p, TangentPlane plane,
                 std::vector<SampleIndex>& links, std::vector<double>& scratch);

} // namespace detail
} // namespace cocone
} // namespace pcl
