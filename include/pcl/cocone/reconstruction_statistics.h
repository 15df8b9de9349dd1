// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * What a reconstruction did, stage by stage, in numbers: the part of the core's report
 * that CoconeReconstruction hands out as it is (getReport()). It holds no index, so
 * nothing in it can be mistaken for a cloud index.
 */
#pragma once

#include <cstddef>

namespace pcl {
namespace cocone {

/** \brief The counts and timings of a reconstruction. */
struct ReconstructionStatistics
{
  /** Boundary samples among the distinct samples (duplicates not counted). */
  std::size_t distinct_boundary_samples = 0;
  std::size_t distinct_samples = 0; ///< distinct samples (points of the diagram)
  /** \brief Whether most distinct samples are boundary samples: the cloud is too
   * sparse for boundary detection at this rho. Boundary samples cast no vote, so the
   * cocones would choose too few triangles to cover the surface (Power Crust's
   * 1281-point knot: 11% of its samples used). The reconstruction then falls back to
   * no boundary detection: every sample votes, no hole is a true boundary, and
   * candidates with a circumradius above 0.9 local spacings are left out
   * (docs/topology.md). It warns when this holds.
   * \return true when more than half of the distinct samples are boundary samples */
  bool
  tooSparseForBoundaryDetection() const
  {
    return 2 * distinct_boundary_samples > distinct_samples;
  }
  std::size_t candidate_triangles = 0; ///< Delaunay triangles chosen by the cocones
  /** Candidates removed because they covered a true boundary (a hole too small against
   * the local feature size for BOUNDARY to flag its rim, but too large against the
   * sample spacing to be a sampling gap). */
  std::size_t lid_triangles = 0;
  std::size_t pruned_triangles = 0; ///< candidates removed at sharp edges
  std::size_t walked_triangles = 0; ///< triangles the walk took
  /** Walked triangles removed again because a vertex ended with several fans. */
  std::size_t pinch_removed_triangles = 0;
  std::size_t stitched_holes = 0;     ///< holes closed by stitching
  std::size_t stitched_triangles = 0; ///< triangles added to close them
  /** Samples left out by the extraction and put back by splitting the triangle they
   * lie over in three, or the edge they lie next to in two (within one local spacing
   * of the surface there). */
  std::size_t inserted_samples = 0;
  /** Triangles removed because they crossed another one (undersampled or noisy parts);
   * their holes are stitched. */
  std::size_t crossing_triangles = 0;
  /** When the diagram was built on a smoothed copy of the samples (denoising, see
   * docs/noise.md): triangles removed because they cross another one at the input
   * positions (with the fans this pinches and the small pieces it cuts off), and
   * triangles added to fill their holes again. 0 otherwise. */
  std::size_t restore_removed_triangles = 0;
  std::size_t restore_filled_triangles = 0; ///< see restore_removed_triangles
  /** \brief Wall-clock seconds of each stage. */
  struct Timings
  {
    double boundary = 0;   ///< BOUNDARY
    double candidates = 0; ///< candidates, local spacing and lids
    double pruning = 0;    ///< pruning at sharp edges
    double walk = 0;       ///< walk and pinch resolution
    double stitching = 0;  ///< stitching, sample insertion, crossing removal
    double finishing = 0;  ///< orientation, loops, unused samples
    /** Denoised diagrams only: back at the input positions, crossing triangles found
     * (exact predicates), removed and their holes filled. */
    double restore = 0;
  } timings; ///< wall-clock seconds of each stage
};

} // namespace cocone
} // namespace pcl
