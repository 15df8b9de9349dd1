// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's first stage: the cocone candidates (the pool's group 0), less
// the lids that cover holes. Never installed.
#pragma once

#include "reconstruction/mesh_state.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Adds the candidates among the marked triangles of \a voronoi to the empty pool of
 * \a mesh, as group kCoconeGroup (closed), and builds the incidence lists: a triangle
 * is a candidate when every vertex not flagged in \a boundary marks it, and it has one
 * such vertex. Returns the number of candidates. */
std::size_t
collectCandidates(const VoronoiCocone& voronoi,
                  const std::vector<std::uint8_t>& boundary, MeshState& mesh);

/** Rejects the candidates of \a mesh that form lids over holes (see the source), with
 * the local spacings \a spacing of the samples and BOUNDARY's flags \a boundary. In
 * parallel on \a threads threads (0: all). Returns the number of triangles rejected. */
std::size_t removeLids(MeshState& mesh, const std::vector<double>& spacing,
                       const std::vector<std::uint8_t>& boundary,
                       double true_boundary_ratio, unsigned threads);

} // namespace detail
} // namespace cocone
} // namespace pcl
