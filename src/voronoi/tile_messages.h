// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the message a process sends to the root when several build one diagram
// (core/tile_exchange.h): the per-sample geometry of its tiles' own samples and their
// TileContributions. Never installed.
#pragma once

#include "voronoi/cell_geometry.h"
#include "voronoi/tiling.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** The message of a process that built tiles \a tiles of \a tiling: whether every one
 * of them was \a complete (if not, nothing else is sent: the root builds the diagram
 * as one tile), then for each tile its samples' entries of \a d and its contribution
 * (which is emptied). */
std::vector<std::uint8_t>
packTiles(const KdTiling& tiling, const std::vector<unsigned>& tiles, bool complete,
          const DiagramState& d, std::vector<TileContribution>& contributions);

/** Writes the tiles of \a message (from packTiles, on the same tiling) into \a d and
 * \a contributions. Returns false when the sender's tiles were not complete. Throws
 * StageFailure (internal_error) on a message that is truncated or names a tile or
 * sample outside the tiling. */
bool unpackTiles(const std::vector<std::uint8_t>& message, const KdTiling& tiling,
                 DiagramState& d, std::vector<TileContribution>& contributions);

} // namespace detail
} // namespace cocone
} // namespace pcl
