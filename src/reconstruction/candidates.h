// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's first stage: the cocone candidates (the pool's group 0), less
// the lids that cover holes. Never installed.
#pragma once

#include "reconstruction/local_spacing.h"
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
 * the local spacings \a spacing of the samples and the hole rule \a rule. In
 * parallel on \a threads threads (0: all). Returns the number of triangles rejected. */
std::size_t removeLids(MeshState& mesh, const std::vector<double>& spacing,
                       const HoleRule& rule, unsigned threads);

/** Circumradius bound of the candidates in the sparse fallback, in local spacings:
 * the triangles of a sampled surface stay below about 0.9 (see removeLids), those
 * that bridge a thin, sparse part lie above. Measured (docs/topology.md): knot_1281
 * is closed of genus 1 for bounds 0.7 to 0.9, genus 3 at 1.0, open without a bound;
 * random 800-point knots are genus 1 at 0.9 (3 seeds), genus 0 (tube cut) at 0.8.
 */
constexpr double kSparseCandidateRadius = 0.9;

/** Rejects the candidates of \a mesh whose circumradius exceeds \a ratio times the
 * largest local spacing \a spacing of their vertices (the sparse fallback, see
 * reconstruct_surface.cpp). Returns the number of triangles rejected. */
std::size_t rejectLargeCandidates(MeshState& mesh, const std::vector<double>& spacing,
                                  double ratio);

} // namespace detail
} // namespace cocone
} // namespace pcl
