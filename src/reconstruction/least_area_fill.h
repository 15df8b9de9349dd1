// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the triangulation of least area of a polygon loop in space that uses no
// forbidden diagonal and crosses no obstacle triangle: how the mesher closes a small
// hole that its Delaunay triangles cannot close. Never installed.
#pragma once

#include <pcl/cocone/core/mesh_topology.h>

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Tables reused from one fill to the next (m^3 entries for a loop of m vertices), so
 * that a sequence of fills does not allocate them each time. */
struct LeastAreaFillScratch
{
  std::vector<std::uint8_t> verdicts; ///< per candidate triangle (i, j, k)
  std::vector<double> areas;          ///< per candidate triangle (i, j, k)
};

/** The triangulation of the polygon \a loop of least total area (dynamic programming
 * over its diagonals, O(m^3) for m vertices) that uses no diagonal \a is_edge names and
 * no triangle intersecting an obstacle (trianglesIntersect: sharing vertices is not
 * crossing). No two of its triangles intersect each other either: where the least-area
 * one folds through itself, the larger triangle of a crossing pair is excluded and the
 * search goes on, so the fill returned may then be larger than the least clear one
 * (see the source).
 * \param[in] points vertex positions
 * \param[in] loop the polygon: indices into \a points, the last joined to the first; it
 *            runs a -> b as the surface's triangles traverse its edges
 * \param[in] is_edge is_edge(a, b) for two loop vertices that are not neighbours on
 *            the loop: true when the segment a b is an edge already (of the surface),
 *            which a fill must not use twice
 * \param[in] obstacles triangles that no fill triangle may intersect (the surface
 *            around the hole: at least every one whose box meets the loop's box)
 * \param[out] fill the triangles, each running a loop edge b -> a, so that they
 *             continue the surface across the loop; cleared first
 * \param[out] blockers when the fill is not found quickly (within a few rounds, see
 *             the source), the positions in \a obstacles of the triangles crossed by
 *             the candidates smaller than the one chosen (or than none): what stands
 *             between the loop and a smaller fill; sorted, without repeats; cleared
 *             first, and empty when the fill was found quickly
 * \param[in,out] scratch tables reused between calls
 * \return whether a fill was found (false also for fewer than 3 vertices); after a
 *         fold, false does not prove that no clear fill exists */
bool fillLoopByLeastArea(
    const std::vector<Eigen::Vector3d>& points, const std::vector<std::uint32_t>& loop,
    const std::function<bool(std::uint32_t, std::uint32_t)>& is_edge,
    const std::vector<TriangleIndices>& obstacles, std::vector<TriangleIndices>& fill,
    std::vector<std::uint32_t>& blockers, LeastAreaFillScratch& scratch);

} // namespace detail
} // namespace cocone
} // namespace pcl
