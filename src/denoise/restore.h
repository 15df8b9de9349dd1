// SPDX-License-Identifier: GPL-3.0-or-later
// Private: what the reconstruction does when the diagram was built on a smoothed copy
// (core/denoise.h) and the mesh returns to the samples as given: the triangles that
// now cross another one are removed and their holes filled again. Never installed.
#pragma once

#include <pcl/cocone/core/mesh_topology.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** The largest hole restoreInputPositions fills (vertices of its loop): a fill is
 * O(m^3) in time and memory, and the holes left by a few crossing triangles have a
 * dozen vertices. */
constexpr std::size_t kMaxRestoreLoop = 64;

/** The largest piece restoreInputPositions removes when the repair has cut it off from
 * the rest (triangles): the scraps seen are single triangles, whose samples then count
 * as unused. */
constexpr std::size_t kMaxRestoreScrap = 4;

/** What restoreInputPositions did. */
struct RestoreRepair
{
  /// triangles that crossed another, pinched, or were cut off by the repair
  std::size_t removed_triangles = 0;
  std::size_t filled_triangles = 0; ///< triangles added in their holes
};

/** Makes \a triangles, a mesh chosen on smoothed positions, free of self-intersection
 * at the positions \a points of its vertices as given: every triangle of an
 * intersecting pair (findSelfIntersections) is removed, and so is every fan but the
 * largest at a vertex this pinches; each hole this opens (a
 * boundary loop through a vertex of a removed triangle, of at most kMaxRestoreLoop
 * vertices) is filled with the triangulation of least area that crosses no triangle of
 * the mesh (the mesher's fill). Two rounds remove and fill; a third removes what still
 * crosses and leaves its hole open, so that no crossing is left. In each round, before
 * the fills, pieces of at most kMaxRestoreScrap triangles whose boundary the repair
 * touched all round are removed: the repair cut them off. Deterministic: the same
 * for any \a threads, the most threads the crossing checks use (0: every core). */
RestoreRepair
restoreInputPositions(const std::vector<Eigen::Vector3d>& points,
                      std::vector<TriangleIndices>& triangles, unsigned threads);

} // namespace detail
} // namespace cocone
} // namespace pcl
