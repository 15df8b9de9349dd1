// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tiles as independent jobs, without MPI: a TileExchange (core/tile_exchange.h) through
// files next to the output. Job R of N (R > 0) computes its share of the tiles and
// writes it to OUTPUT.job-R-of-N.tiles; job 0 reads them, joins, writes the mesh and
// removes the files. Job 0 runs after the others (a Slurm job array with a dependency,
// GNU parallel, a shell loop), or beside them with a wait: it builds its own tiles
// meanwhile and then waits for the files still missing.
#pragma once

#include <pcl/cocone/core/tile_exchange.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace tools {

class JobFiles : public TileExchange
{
public:
  /** Job \a job of \a jobs writing or reading next to \a output. \a fingerprint names
   * the input and the options that shape the diagram: job 0 refuses a file written
   * with another. Job 0 waits up to \a wait_seconds for a file that is missing once
   * its own tiles are built (0: the other jobs must have finished before it starts). */
  JobFiles(unsigned job, unsigned jobs, std::string output, std::string fingerprint,
           double wait_seconds = 0);

  unsigned
  rank() const override
  {
    return job_;
  }
  unsigned
  size() const override
  {
    return jobs_;
  }
  /** Job R > 0: writes \a message (atomically: a temporary file renamed). Job 0: when
   * \a message is not empty, job 0 has failed and nothing is read; otherwise reads
   * every other job's file, waiting for a missing one as set; throws
   * std::runtime_error naming the first file that is missing (after the wait),
   * unreadable or made from another input or other options. */
  std::vector<std::vector<std::uint8_t>>
  gatherToRoot(const std::vector<std::uint8_t>& message) override;

  /** Job 0, before its own tiles: throws std::runtime_error naming the first other
   * job's file that is missing (unless job 0 waits for it) or was made from another
   * input, options or version, so that a mistake is found before hours of work
   * rather than after. */
  void checkOthersReady() const;

  /** Job 0, once the mesh is written: removes the other jobs' files. */
  void removeFiles() const;

  /** The file of job \a job. */
  std::string fileOf(unsigned job) const;

private:
  unsigned job_, jobs_;
  std::string output_, fingerprint_;
  double wait_seconds_;
};

/** A 64-bit FNV-1a hash of \a bytes, continuing \a hash: the input's fingerprint. */
std::uint64_t fingerprintBytes(const void* bytes, std::size_t size,
                               std::uint64_t hash = 0xcbf29ce484222325ull);

} // namespace tools
} // namespace cocone
} // namespace pcl
