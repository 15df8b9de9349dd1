// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * BOUNDARY (Dey et al. 2001, section 3.3) on the geometry of a VoronoiCocone: the
 * non-template algorithm behind BoundarySampleEstimation and CoconeReconstruction.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/voronoi_cocone.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Parameters of BOUNDARY. Defaults are the paper's practical values. */
struct BoundaryParameters
{
  /** rho: a sample is flat only if r_p / h_p <= rho. Dimensionless; default 0.99;
   * valid range (0, 10]. Theory asks for 1.3 epsilon on an epsilon-sample. */
  double ratio_bound = 0.99;
  /** alpha: the largest acute angle between the pole lines of a flat sample and of the
   * samples whose cocone it meets. Radians; default pi/6; valid range (0, pi/2]. */
  double normal_angle = M_PI / 6;
  /** Beyond the paper: grow the boundary flags by this many rings of cocone neighbours,
   * for users who want a band along the rim rather than its outermost row. Default 0
   * (BOUNDARY as published); valid range 0 to 64. */
  unsigned band_rings = 0;
};

/** \brief True when every value of \a parameters lies in its documented range. */
PCL_COCONE_EXPORT bool
isValid(const BoundaryParameters& parameters);

/** \brief Runs BOUNDARY: the flat samples (ratio and normal conditions), grown through
 * cocone neighbours that satisfy the ratio condition and agree in pole line; every
 * other sample is a boundary sample.
 * \param[in] voronoi a VoronoiCocone on which compute() succeeded
 * \param[in] parameters see BoundaryParameters (assumed valid)
 * \param[out] is_boundary one entry per sample of \a voronoi: 1 for a boundary sample,
 *             0 for an interior one; a duplicate gets its representative's flag
 * \return the number of boundary samples */
PCL_COCONE_EXPORT std::size_t
detectBoundarySamples(const VoronoiCocone& voronoi,
                      const BoundaryParameters& parameters,
                      std::vector<std::uint8_t>& is_boundary);

} // namespace cocone
} // namespace pcl
