// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_reconstruction_mpi: pcl_cocone_reconstruction across processes, e.g.
//   mpirun -np 4 pcl_cocone_reconstruction_mpi scan.pcd mesh.ply
// Every process reads the input and runs the same tool; the tiles of the Voronoi
// diagram (its Delaunay triangulations and per-sample geometry, the bulk of the work)
// are dealt out among them through an MPI TileExchange (core/tile_exchange.h), and
// rank 0 joins them, runs BOUNDARY and the mesher, and writes the mesh a single
// process writes.
#include "reconstruction_tool.h"

#include <fcntl.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

/** The TileExchange of MPI_COMM_WORLD: point-to-point messages to rank 0, each sent as
 * its length and then chunks (an MPI count is an int). */
class MpiTileExchange : public pcl::cocone::TileExchange
{
public:
  MpiTileExchange()
  {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    rank_ = static_cast<unsigned>(rank);
    size_ = static_cast<unsigned>(size);
  }

  unsigned
  rank() const override
  {
    return rank_;
  }
  unsigned
  size() const override
  {
    return size_;
  }

  std::vector<std::vector<std::uint8_t>>
  gatherToRoot(const std::vector<std::uint8_t>& message) override
  {
    if (rank_ != 0) {
      const std::uint64_t length = message.size();
      check(MPI_Send(&length, 1, MPI_UINT64_T, 0, kLengthTag, MPI_COMM_WORLD));
      for (std::size_t offset = 0; offset < message.size(); offset += kChunk)
        check(MPI_Send(message.data() + offset, chunkAt(offset, message.size()),
                       MPI_BYTE, 0, kDataTag, MPI_COMM_WORLD));
      return {};
    }
    std::vector<std::vector<std::uint8_t>> messages(size_);
    for (unsigned r = 1; r < size_; ++r) {
      std::uint64_t length = 0;
      check(MPI_Recv(&length, 1, MPI_UINT64_T, int(r), kLengthTag, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE));
      messages[r].resize(length);
      for (std::size_t offset = 0; offset < length; offset += kChunk)
        check(MPI_Recv(messages[r].data() + offset, chunkAt(offset, length), MPI_BYTE,
                       int(r), kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE));
    }
    return messages;
  }

private:
  static constexpr int kLengthTag = 1, kDataTag = 2;
  static constexpr std::size_t kChunk = std::size_t(1) << 30;

  static int
  chunkAt(std::size_t offset, std::size_t length)
  {
    return static_cast<int>(std::min(kChunk, length - offset));
  }
  static void
  check(int code)
  {
    if (code != MPI_SUCCESS)
      throw std::runtime_error("an MPI transfer failed");
  }

  unsigned rank_ = 0, size_ = 1;
};

bool mpi_finalized = false;
bool help_requested = false;

/** A process that exits without MPI_Finalize (the tool's fail() exits 1 with its
 * reason) takes the others down with it, so that none waits for its tiles. The help
 * (-h, which every process prints and exits 0 on) finalizes instead. */
void
atExit()
{
  if (mpi_finalized)
    return;
  if (help_requested)
    MPI_Finalize();
  else
    MPI_Abort(MPI_COMM_WORLD, EXIT_FAILURE);
}

} // namespace

int
main(int argc, char** argv)
{
  // The exchange may be called from a TBB thread, one thread at a time.
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  if (provided < MPI_THREAD_SERIALIZED) {
    std::fprintf(stderr, "pcl_cocone_reconstruction_mpi: the MPI library does not "
                         "support MPI_THREAD_SERIALIZED\n");
    MPI_Abort(MPI_COMM_WORLD, EXIT_FAILURE);
  }
  for (int i = 1; i < argc; ++i)
    help_requested = help_requested || std::strcmp(argv[i], "-h") == 0 ||
                     std::strcmp(argv[i], "--help") == 0;
  std::atexit(atExit);
  const auto exchange = std::make_shared<MpiTileExchange>();
  // Only rank 0 reports; errors still show from every rank.
  if (exchange->rank() != 0) {
    std::fflush(stdout);
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      ::dup2(null, STDOUT_FILENO);
      ::close(null);
    }
  }
  const int code = pcl::cocone::tools::runReconstructionTool(argc, argv, exchange);
  MPI_Finalize();
  mpi_finalized = true;
  return code;
}
