// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the Delaunay triangulation of one tile, with a halo grown until the stars of
// the tile's own samples are exactly those of the whole cloud. Never installed.
#pragma once

#include "voronoi/cgal_delaunay.h"
#include "voronoi/tiling.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** How a tile's triangulation went. */
struct TileTriangulationStats
{
  std::size_t owned = 0; ///< the tile's own samples
  std::size_t local = 0; ///< samples triangulated: own plus halo
  unsigned rounds = 0;   ///< insertion rounds (1: the first halo was enough)
  bool complete = false; ///< false: the halo outgrew its budget, nothing is exact
};

/** Triangulates tile \a tile of \a tiling (samples at \a points) with a halo of whole
 * leaves, grown until the star of every sample of the tile is final: every Delaunay
 * cell incident to one has a circumball (for a cell on the convex hull: the open
 * half-space beyond its hull facet) that holds no sample outside tile and halo. Such a
 * cell is a cell of the triangulation of all the samples, and a star made of such
 * cells is that sample's star in the whole triangulation: the tile's geometry equals
 * the untiled one. Which leaves to test is decided on bounds that hold whatever the
 * rounding: the circumcenter in interval arithmetic, the side of a hull facet with
 * CGAL's exact orientation (a needle facet, or a cell too flat for intervals, has every
 * leaf tested); each sample of a chosen leaf is then tested with CGAL's exact
 * predicate and symbolic perturbation. The halo may grow more than needed, never less.
 *
 * Stops, with complete == false, once tile and halo would exceed \a halo_factor times
 * the tile's own samples plus 2048, or the leaves it tests 16 per sample of that budget
 * (a leaf counted once per cell whose conflicts it is tested for, whatever the order),
 * or when \a give_up returns true (checked between rounds and every 4096 cells tested).
 * \a on_inserted is called on the thread that runs the tile, with counts of samples
 * inserted: about every 65536, and the rest at the end of each round. */
TileTriangulationStats
triangulateTile(const KdTiling& tiling, unsigned tile,
                const std::vector<Eigen::Vector3d>& points,
                const std::vector<std::uint32_t>& tile_of, unsigned halo_factor,
                Delaunay& dt, const std::function<void(std::size_t)>& on_inserted,
                const std::function<bool()>& give_up);

} // namespace detail
} // namespace cocone
} // namespace pcl
