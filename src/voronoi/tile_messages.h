// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the message a process sends to the root when several build one diagram
// (core/tile_exchange.h): the per-sample geometry of its tiles' own samples and their
// TileContributions. Never installed.
#pragma once

#include "voronoi/cell_geometry.h"
#include "voronoi/tiling.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** A hash of what every process must agree on before its tiles mean anything to the
 * root: the cloud's size, its distinct samples, the tiling and the coordinates the
 * diagram is built from (smoothed when denoised). */
std::uint64_t diagramFingerprint(const DiagramState& d, const KdTiling& tiling);

/** The message of a process that built tiles \a tiles of \a tiling: whether every one
 * of them was \a complete (if not, nothing else is sent: the root builds the diagram
 * as one tile), \a fingerprint (diagramFingerprint), then for each tile its samples'
 * entries of \a d and its contribution (which is emptied). */
std::vector<std::uint8_t>
packTiles(const KdTiling& tiling, const std::vector<unsigned>& tiles, bool complete,
          std::uint64_t fingerprint, const DiagramState& d,
          std::vector<TileContribution>& contributions);

/** The message of a process that failed before its tiles were built or packed: its
 * one-line \a reason. Allocates little, so that it can be sent after running out of
 * memory. */
std::vector<std::uint8_t> packFailure(const std::string& reason);

/** Writes the tiles of \a message, from process \a sender of \a processes, into \a d
 * and \a contributions. Returns false when the sender's tiles were not complete.
 * Throws StageFailure (internal_error) when the sender failed (with its reason), and
 * on a message that is truncated, made from another fingerprint, or names other tiles
 * than those dealt to the sender (tile t to process t mod processes, ascending) or
 * samples outside the cloud. */
bool unpackTiles(const std::vector<std::uint8_t>& message, unsigned sender,
                 unsigned processes, const KdTiling& tiling, std::uint64_t fingerprint,
                 DiagramState& d, std::vector<TileContribution>& contributions);

} // namespace detail
} // namespace cocone
} // namespace pcl
