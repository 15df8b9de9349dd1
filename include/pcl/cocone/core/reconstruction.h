// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): COCONE reconstruction with boundaries
 * (Dey et al. 2001, section 3.4) on the geometry of a VoronoiCocone, the non-template
 * algorithm behind CoconeReconstruction.
 */
#pragma once

#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/core/status.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>
#include <pcl/cocone/reconstruction_statistics.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief What a reconstruction did: its counts and timings, and per-sample results.
 * Sample indices (SampleIndex) are those of the VoronoiCocone, i.e. positions in the
 * array given to VoronoiCocone::compute (CoconeReconstruction maps them to cloud
 * indices and hands out only the statistics as they are). */
struct ReconstructionReport : ReconstructionStatistics
{
  /** BOUNDARY's flags, one per sample (indexed by SampleIndex): 1 for a boundary
   * sample, 0 otherwise; all 0 when detection is off. */
  std::vector<std::uint8_t> boundary_samples;
  /** The boundary loops left open (true boundaries and holes that could not be closed),
   * as cycles of representative sample indices oriented with the surface (the edge from
   * the last back to the first closes a cycle). */
  std::vector<std::vector<SampleIndex>> open_loops;
  /** Samples in no output triangle, as sample indices in ascending order: duplicates
   * (their representative is used instead), isolated outliers, and samples the
   * manifold extraction had to leave out. */
  std::vector<SampleIndex> unused_samples;
};

/** \brief Reconstructs an oriented 2-manifold (with boundary) through the samples.
 *
 * Stages: BOUNDARY; candidate triangles (a Delaunay triangle is a candidate when every
 * non-boundary vertex's cocone marks it and it has at least one such vertex); pruning
 * of triangles at sharp edges (never of triangles incident to a boundary sample, nor of
 * triangles that a flat sheet holds on an edge, so that small gaps cannot cascade);
 * manifold extraction by walking the outer side of the candidates, refusing any third
 * triangle on an edge, any second fan at a vertex and any step that would turn the
 * surface over (a fold, or a triangle facing away from the mesh at the edge's ends);
 * stitching of the holes that are not true boundaries with Delaunay triangles on the
 * hole, by the same prune and walk;
 * putting back samples left out that lie on the surface; removal of triangles crossing
 * another one (their holes stitched again); orientation outward on closed components.
 * \param[in] voronoi a VoronoiCocone on which compute() succeeded
 * \param[in] parameters see ReconstructionParameters
 * \param[out] triangles oriented triangles of representative sample indices (cleared
 *             first; empty on failure)
 * \param[out] report the stages' numbers, open loops and unused samples (reset first)
 * \param[in] progress optional: called from this thread with the share done at the
 *            end of each stage; returning false cancels (Status::internal_error,
 *            message "cancelled")
 * \param[out] message if given, the one-line reason of a failure (unchanged on
 *             success)
 * \return Status::ok; Status::not_computed when voronoi.status() is not ok;
 *         Status::invalid_parameter when a value of \a parameters is outside its
 *         range (isValid); Status::internal_error when memory ran out or a stage
 *         failed (then \a triangles and \a report are empty) */
PCL_COCONE_EXPORT Status reconstructSurface(const VoronoiCocone& voronoi,
                                            const ReconstructionParameters& parameters,
                                            std::vector<TriangleIndices>& triangles,
                                            ReconstructionReport& report,
                                            const ProgressCallback& progress = nullptr,
                                            std::string* message = nullptr);

} // namespace cocone
} // namespace pcl
