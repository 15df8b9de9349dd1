// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * BOUNDARY (Dey et al. 2001, section 3.3) on the geometry of a VoronoiCocone: the
 * non-template algorithm behind BoundarySampleEstimation and CoconeReconstruction.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Parameters of BOUNDARY. rho and alpha default to the paper's practical
 * values; of the two extensions beyond the paper, the rim-row completion is on and the
 * band is off by default. */
struct BoundaryParameters
{
  /** \brief rho: a sample is flat only if r_p / h_p <= rho. Dimensionless; default
   * 0.99; valid range (0, 10] (kRatioBoundRange). Theory asks for 1.3 epsilon on an
   * epsilon-sample. */
  double ratio_bound = 0.99;
  /** \brief alpha: the largest acute angle between the pole lines of a flat sample and
   * of the samples whose cocone meets its Voronoi cell. Radians; default pi/6; valid
   * range (0, pi/2] (kNormalAngleRange). */
  double normal_angle = M_PI / 6;
  /** \brief Beyond the paper: grow the boundary flags by this many rings of cocone
   * neighbours, for users who want a band along the rim rather than its outermost row.
   * In rings; default 0 (BOUNDARY as published); valid range 0 to 64
   * (kBandRingsRange). */
  unsigned band_rings = 0;
  /** \brief Beyond the paper: complete the outermost row along a rim. BOUNDARY as
   * published flags 27-54% of that row (a rim sample whose cell is closed off just
   * beyond the rim by its neighbours' cells passes the ratio test). With this on,
   * starting from BOUNDARY's flags and walking along cocone neighbours, every sample
   * whose nearby cocone neighbours leave a gap wider than 2 pi / 3 in its tangent
   * plane is flagged as well. Grown only from flags, it adds no flag to a shape that
   * has none. Default true; false gives BOUNDARY as published. Either value is
   * valid. */
  bool complete_rim_row = true;
};

/** \brief Checks BOUNDARY's parameters against their ranges (parameters.h).
 * \param[in] parameters the values to check
 * \return true when every value of \a parameters lies in its documented range */
PCL_COCONE_EXPORT bool
isValid(const BoundaryParameters& parameters);

/** \brief Runs BOUNDARY: the flat samples (ratio and normal conditions), grown through
 * cocone neighbours that satisfy the ratio condition and agree in pole line; every
 * other sample is a boundary sample. Then, as \a parameters ask, completes the rim
 * row and adds the band.
 * \param[in] voronoi a VoronoiCocone on which compute() succeeded and decimate() has
 *            not run (decimate() clears the marked triangles BOUNDARY needs)
 * \param[in] parameters see BoundaryParameters (assumed valid: see isValid)
 * \param[out] is_boundary one entry per sample of \a voronoi (indexed by SampleIndex,
 *             size voronoi.size()): 1 for a boundary sample, 0 for an interior one; a
 *             duplicate gets its representative's flag. All 0 when \a voronoi holds no
 *             diagram
 * \return the number of entries of \a is_boundary that are 1 (duplicates included); 0
 *         when \a voronoi holds no diagram */
PCL_COCONE_EXPORT std::size_t
detectBoundarySamples(const VoronoiCocone& voronoi,
                      const BoundaryParameters& parameters,
                      std::vector<std::uint8_t>& is_boundary);

} // namespace cocone
} // namespace pcl
