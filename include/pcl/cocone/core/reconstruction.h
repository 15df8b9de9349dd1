// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * COCONE reconstruction with boundaries (Dey et al. 2001, section 3.4) on the geometry
 * of a VoronoiCocone: the non-template algorithm behind CoconeReconstruction.
 */
#pragma once

#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/export.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Parameters of the reconstruction (the cocone angle is the VoronoiCocone's).
 * Defaults are those of CoconeReconstruction. */
struct ReconstructionParameters
{
  /** BOUNDARY's parameters (rho, alpha; see BoundaryParameters for units, defaults
   * and ranges); band_rings and complete_rim_row are ignored here: the samples that
   * cast no vote are BOUNDARY's as published. */
  BoundaryParameters boundary;
  /** Detect boundary samples and let them cast no vote. Default true; false gives the
   * original COCONE candidate rule (a triangle needs the marks of all its vertices).
   * Either value is valid. */
  bool detect_boundary = true;
  /** Close the holes that are not true boundaries. Default true; either value is
   * valid. */
  bool stitch_holes = true;
  /** A hole is a true boundary, and stays open, when its size (twice its area over its
   * perimeter: the radius of a round hole, half the width of a long one) exceeds this
   * many local sample spacings; smaller holes are stitched. The same test removes
   * candidate triangles that cover such a hole. In local spacings (about 1.1 times
   * sqrt(area / n) on evenly spread samples); default 2; valid range [0.5, 1000]
   * (kTrueBoundaryRatioRange). */
  double true_boundary_ratio = 2;
};

/** \brief Checks the reconstruction's parameters against their ranges (parameters.h);
 * boundary.band_rings is checked too, although the reconstruction ignores it.
 * \param[in] parameters the values to check
 * \return true when every value of \a parameters lies in its documented range */
PCL_COCONE_EXPORT bool
isValid(const ReconstructionParameters& parameters);

/** \brief What a reconstruction did, stage by stage. Sample indices (SampleIndex) are
 * those of the VoronoiCocone, i.e. positions in the array given to
 * VoronoiCocone::compute. */
struct ReconstructionReport
{
  /** BOUNDARY's flags, one per sample (indexed by SampleIndex): 1 for a boundary
   * sample, 0 otherwise; all 0 when detection is off. */
  std::vector<std::uint8_t> boundary_samples;
  /** Boundary samples among the distinct samples (duplicates not counted). */
  std::size_t distinct_boundary_samples = 0;
  std::size_t distinct_samples = 0; ///< distinct samples (VoronoiCocone::numUniqueSamples)
  /** \brief Whether most distinct samples are boundary samples. Those cast no vote, so
   * the cocones then choose too few triangles to cover the surface: the cloud is too
   * sparse for boundary detection at this rho (a larger rho, or no detection, fits it
   * better). The reconstruction warns when this holds.
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
  std::size_t pruned_triangles = 0;    ///< candidates removed at sharp edges
  std::size_t walked_triangles = 0;    ///< triangles the walk took
  /** Walked triangles removed again because a vertex ended with several fans. */
  std::size_t pinch_removed_triangles = 0;
  std::size_t stitched_holes = 0;      ///< holes closed by stitching
  std::size_t stitched_triangles = 0;  ///< triangles added to close them
  /** Samples left out by the extraction and put back by splitting the triangle they
   * lie over in three, or the edge they lie next to in two (within one local spacing
   * of the surface there). */
  std::size_t inserted_samples = 0;
  /** Triangles removed because they crossed another one (undersampled or noisy parts);
   * their holes are stitched. */
  std::size_t crossing_triangles = 0;
  /** The boundary loops left open (true boundaries and holes that could not be closed),
   * as cycles of representative sample indices oriented with the surface (the edge from
   * the last back to the first closes a cycle). */
  std::vector<std::vector<SampleIndex>> open_loops;
  /** \brief Wall-clock seconds of each stage. */
  struct Timings
  {
    double boundary = 0;   ///< BOUNDARY
    double candidates = 0; ///< candidates, local spacing and lids
    double pruning = 0;    ///< pruning at sharp edges
    double walk = 0;       ///< walk and pinch resolution
    double stitching = 0;  ///< stitching, sample insertion, crossing removal
    double finishing = 0;  ///< orientation, loops, unused samples
  } timings;               ///< wall-clock seconds of each stage
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
 * \param[in] voronoi a VoronoiCocone on which compute() succeeded and decimate() has
 *            not run (decimate() consumes the triangulation)
 * \param[in] parameters see ReconstructionParameters (assumed valid: see isValid)
 * \param[out] triangles oriented triangles of representative sample indices (cleared
 *             first)
 * \param[out] report the stages' numbers, open loops and unused samples (reset first)
 * \return Status::ok, or Status::not_computed when voronoi.status() is not ok (then
 *         \a triangles and \a report stay empty) */
PCL_COCONE_EXPORT Status
reconstructSurface(const VoronoiCocone& voronoi,
                   const ReconstructionParameters& parameters,
                   std::vector<TriangleIndices>& triangles,
                   ReconstructionReport& report);

} // namespace cocone
} // namespace pcl
