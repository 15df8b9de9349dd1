// SPDX-License-Identifier: GPL-3.0-or-later
//
// The body of pcl_cocone_reconstruction, shared with its MPI driver.
#pragma once

#include <pcl/cocone/core/tile_exchange.h>

#include <memory>

namespace pcl {
namespace cocone {
namespace tools {

/** Runs pcl_cocone_reconstruction on \a argv. With \a exchange, as one of the processes
 * that share the Voronoi diagram's tiles (-tiles defaults to one per process): rank 0
 * prints and writes the mesh, the others only compute their tiles. Returns the exit
 * code; failures exit through fail(). */
int runReconstructionTool(int argc, char** argv,
                          const std::shared_ptr<TileExchange>& exchange);

} // namespace tools
} // namespace cocone
} // namespace pcl
