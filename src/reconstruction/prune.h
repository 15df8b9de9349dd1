// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's pruning of candidate triangles at sharp edges, for the cocone
// candidates and again for the Delaunay triangles offered to each hole. Never
// installed.
#pragma once

#include "reconstruction/mesh_state.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Prunes the candidates of a group of the pool (see the source for the rule). */
class Pruner
{
public:
  /** Prunes the candidates of \a mesh; the triangles of the cocone group incident to a
   * sample flagged in \a boundary are never pruned. In parallel on \a threads threads
   * (0: all) when a group is large. */
  Pruner(MeshState& mesh, const std::vector<std::uint8_t>& boundary, unsigned threads)
    : mesh_(mesh), boundary_(boundary), threads_(threads)
  {}

  /** Rejects the candidates of \a group that must go, until none is left to; returns
   * their number. */
  std::size_t prune(std::uint32_t group);

private:
  bool mustPrune(std::uint32_t t, std::vector<SampleIndex>& apexes,
                 std::vector<double>& angles) const;

  MeshState& mesh_;
  const std::vector<std::uint8_t>& boundary_;
  const unsigned threads_;
  // Scratch of mustPrune in the cascade, reused to keep it free of allocations.
  std::vector<SampleIndex> apexes_;
  std::vector<double> angles_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
