// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the per-sample geometry pass of VoronoiCocone::compute, tile by tile, and
// the join of the tiles' results. Never installed.
#pragma once

#include "voronoi/cgal_delaunay.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <array>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** What one tile hands to joinTiles. */
struct TileContribution
{
  /** The Delaunay cells whose smallest sample is the tile's: their samples in
   * ascending order, kNoSample (the infinite vertex) last. */
  std::vector<std::array<SampleIndex, 4>> cells;
  /** The marks of the tile's samples: each triangle under its ascending vertices, with
   * the bits of the tile's own vertices only. */
  std::vector<MarkedTriangle> marks;
};

/** Circumcenters, poles, heights, radii and cocone marks of the samples of \a dt (whose
 * vertices carry their sample index) that belong to tile \a tile (tile_of[s] == tile).
 * The stars of those samples must be complete in \a dt (tiled_delaunay.h). Writes their
 * entries of d.pole_vector, positive_pole, negative_pole, height, radius and
 * unbounded (sized by the caller), and the cells and marks they own to \a out. Every
 * value is computed from the vertices in ascending sample order and every tie broken
 * by sample indices, so it does not depend on the tile, its halo or the insertion
 * order. \a points are exactly the coordinates \a dt was built from: the circumcenters
 * are computed from them once \a dt is cleared. Clears \a dt.
 * \a sin_theta is the sine of the cocone angle. */
void computeTileGeometry(Delaunay& dt, const std::vector<Eigen::Vector3d>& points,
                         const std::vector<std::uint32_t>& tile_of, std::uint32_t tile,
                         double sin_theta, DiagramState& d, TileContribution& out);

/** The stars, marked triangles and incidence lists of the whole diagram, from every
 * tile's contribution (which it empties): the same arrays for any tiling. */
void joinTiles(std::vector<TileContribution>& tiles, DiagramState& d);

} // namespace detail
} // namespace cocone
} // namespace pcl
