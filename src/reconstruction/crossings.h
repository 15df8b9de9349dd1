// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's repairs after stitching: samples left out are put back where
// they lie on the surface, and triangles that cross another one are removed. Never
// installed.
#pragma once

#include "reconstruction/mesh_state.h"
#include "reconstruction/walk.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Puts the samples of \a voronoi that no mesh triangle uses back into \a mesh where
 * they lie on it (see the source); \a spacing holds the local spacings of the samples.
 * The new triangles join the pool in group kPolygonGroup. Returns the number of
 * samples put back. */
std::size_t insertUnusedSamples(MeshState& mesh, const VoronoiCocone& voronoi,
                                const std::vector<double>& spacing);

/** What removeCrossings did. */
struct CrossingRemoval
{
  std::size_t removed = 0;       ///< triangles removed because they crossed another
  std::size_t pinch_removed = 0; ///< triangles removed after, to resolve pinches
};

/** Removes, of every pair of crossing mesh triangles of \a mesh with a suspect among
 * them (a triangle not of the cocone group, or at a sample flagged in \a boundary), the
 * one added last; then resolves the pinches this leaves through \a pinches. In
 * parallel on \a threads threads (0: all). */
CrossingRemoval
removeCrossings(MeshState& mesh, PinchResolver& pinches,
                const std::vector<std::uint8_t>& boundary, unsigned threads);

} // namespace detail
} // namespace cocone
} // namespace pcl
