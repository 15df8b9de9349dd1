// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the Delaunay triangulation as the diagram keeps it once CGAL's is freed
// (the stars of the samples, in flat arrays), and the per-thread sample marks its
// queries use. Free of CGAL. Never installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Marks on samples that clear() forgets in O(1) (a round number per sample), so that
 * repeats and membership are decided without sorting or searching. Grows to the
 * largest sample marked; meant to be kept per thread and reused. */
class SampleMarks
{
public:
  /** Starts a new round, with nothing marked. */
  void
  clear()
  {
    if (++round_ == 0) { // wrapped: forget every earlier round
      std::fill(round_of_.begin(), round_of_.end(), 0);
      round_ = 1;
    }
  }

  /** Marks s; false if it was marked already in this round. */
  bool
  mark(SampleIndex s)
  {
    if (s >= round_of_.size())
      round_of_.resize(std::max<std::size_t>(s + 1, 2 * round_of_.size()), 0);
    return std::exchange(round_of_[s], round_) != round_;
  }

  bool
  isMarked(SampleIndex s) const
  {
    return s < round_of_.size() && round_of_[s] == round_;
  }

private:
  std::vector<std::uint32_t> round_of_;
  std::uint32_t round_ = 1;
};

/** The Delaunay triangulation as VoronoiCocone keeps it once the per-sample geometry is
 * done: the samples of every cell and the star of every sample, in flat arrays. It
 * answers the neighbour queries of stitching and decimation in 32 bytes per cell, where
 * CGAL's triangulation, which is freed, takes about 80 (a 72-byte cell, and a 48-byte
 * vertex per 6 or 7 cells). */
struct DelaunayStars
{
  /** Per cell, its four samples; kNoSample stands for the infinite vertex. */
  std::vector<std::array<SampleIndex, 4>> cell_samples;
  /** CSR by sample: the cells incident to sample s are cells[offsets[s]] to
   * cells[offsets[s + 1] - 1], ascending; empty for duplicates. */
  std::vector<std::uint32_t> offsets, cells;

  bool
  empty() const
  {
    return offsets.empty();
  }

  /** Appends the finite Delaunay neighbours of sample \a s (a representative) to
   * \a out, each once, unsorted; \a seen is scratch. */
  void
  appendNeighbours(SampleIndex s, SampleMarks& seen,
                   std::vector<SampleIndex>& out) const
  {
    seen.clear();
    for (std::uint32_t k = offsets[s]; k < offsets[s + 1]; ++k)
      for (const SampleIndex w : cell_samples[cells[k]])
        if (w != s && w != kNoSample && seen.mark(w))
          out.push_back(w);
  }

  void
  clear()
  {
    std::vector<std::array<SampleIndex, 4>>().swap(cell_samples);
    std::vector<std::uint32_t>().swap(offsets);
    std::vector<std::uint32_t>().swap(cells);
  }
};

} // namespace detail
} // namespace cocone
} // namespace pcl
