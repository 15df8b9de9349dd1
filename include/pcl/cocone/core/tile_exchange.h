// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API, beyond the paper: a Voronoi diagram built by several processes.
 *
 * Every process runs the same computation, on the same points with the same
 * parameters. The tiles (VoronoiParameters::tiles) are dealt out, tile t to process
 * t mod size(); each process triangulates its tiles with their halos and computes
 * their samples' poles, heights, radii and cocone marks; the root (rank 0) gathers
 * the results and joins them into the diagram, which is the same, bit for bit, as the
 * one a single process builds. The rest (BOUNDARY, the mesher) runs on the root. When
 * a tile's halo outgrows its budget, the root builds the diagram as one tile itself,
 * with the same result.
 *
 * The library has no MPI dependency: the MPI driver (pcl_cocone_reconstruction_mpi)
 * implements this interface with MPI, and any other transport can. The processes must
 * run the same build of the library (the messages are its in-memory layout).
 */
#pragma once

#include <pcl/cocone/export.h>

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief The transport between the processes that build one diagram together (see
 * the file's description). */
class PCL_COCONE_EXPORT TileExchange
{
public:
  virtual ~TileExchange() = default;

  /** \brief This process's number.
   * \return the rank, in [0, size()); 0 is the root, which joins */
  virtual unsigned rank() const = 0;

  /** \brief The number of processes.
   * \return at least 1 */
  virtual unsigned size() const = 0;

  /** \brief Hands each process's tiles to the root: called exactly once per diagram by
   * every process. May throw; the diagram then fails with Status::internal_error, or
   * with this process's own failure when it had failed before the call.
   * \param[in] message this process's tiles; it can exceed 2 GiB. On the root it is
   *            empty, unless the root has failed: then it holds the failure, the root
   *            will not read the others' messages, and an exchange that would wait for
   *            them (job files) need not; one that must let the senders finish (MPI)
   *            still receives them
   * \return on the root, the message of every process indexed by rank (entry 0 left
   *         empty); elsewhere, after sending \a message to the root, an empty vector */
  virtual std::vector<std::vector<std::uint8_t>>
  gatherToRoot(const std::vector<std::uint8_t>& message) = 0;
};

} // namespace cocone
} // namespace pcl
