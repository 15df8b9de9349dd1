// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): BOUNDARY (Dey et al. 2001, section
 * 3.3) on the geometry of a VoronoiCocone, the non-template algorithm behind
 * BoundarySampleEstimation, CoconeReconstruction and VoronoiDecimation.
 */
#pragma once

#include <pcl/cocone/core/status.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Runs BOUNDARY: the flat samples (ratio and normal conditions), grown through
 * cocone neighbours that satisfy the ratio condition and agree in pole line; every
 * other sample is a boundary sample. Then, as \a parameters ask, completes the rim
 * row and adds the band.
 * \param[in] voronoi a VoronoiCocone on which compute() succeeded
 * \param[in] parameters see BoundaryParameters
 * \param[out] is_boundary one entry per sample of \a voronoi (indexed by SampleIndex,
 *             size voronoi.size()): 1 for a boundary sample, 0 for an interior one; a
 *             duplicate gets its representative's flag. Cleared on failure
 * \param[out] message if given, the one-line reason of a failure (unchanged on
 *             success)
 * \return Status::ok; Status::not_computed when \a voronoi holds no diagram;
 *         Status::invalid_parameter when a value of \a parameters is outside its
 *         range (isValid); Status::internal_error when memory ran out */
PCL_COCONE_EXPORT Status detectBoundarySamples(const VoronoiCocone& voronoi,
                                               const BoundaryParameters& parameters,
                                               std::vector<std::uint8_t>& is_boundary,
                                               std::string* message = nullptr);

} // namespace cocone
} // namespace pcl
