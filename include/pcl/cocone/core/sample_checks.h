// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): checks on the samples before any
 * geometry, for what would ruin a result without failing it: points far beyond the
 * cloud's own scale, and coordinates whose float rounding is coarse against the sample
 * spacing.
 */
#pragma once

#include <pcl/cocone/export.h>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief A point is far beyond the cloud's own scale when it lies more than this many
 * times the cloud's median radius from the cloud's median point (see CloudScale).
 *
 * Such a point can be no part of the sampled surface: the samples around it would
 * have to be a thousand times sparser than the cloud's. Kept, it changes the convex
 * hull, and with it the Voronoi cells of every hull sample, and once it is far enough
 * it also ruins the precision of everything else: on PCL's milk carton (0.3 across),
 * one point at 1e18 made decimation remove 84.7% of the points instead of 4.6% and
 * the mesh open along 8 loops instead of 2; at 1e20 every point was flagged. Writers
 * that mark invalid points with FLT_MAX produce such points. Legitimate distant parts
 * of a scan (a wall behind a table, the far end of a corridor) lie tens, not
 * thousands, of radii away. */
constexpr double kFarPointFactor = 1000;

/** \brief The cloud's own scale, robust to a minority of arbitrary points (not the
 * bounding box, not the mean, which one point can move anywhere). */
struct CloudScale
{
  /** The median point: the median of each coordinate, in input units. */
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  /** The median distance of the points from #centre, in input units; where half the
   * points or more coincide with it, the median distance of the other points. */
  double radius = 0;
};

/** \brief The cloud's own scale (see CloudScale).
 * \param[in] points the points, each finite
 * \return the median point and radius; zero for an empty array */
PCL_COCONE_EXPORT CloudScale cloudScale(const std::vector<Eigen::Vector3d>& points);

/** \brief Which points lie far beyond the cloud's own scale: farther than
 * kFarPointFactor times cloudScale().radius from cloudScale().centre.
 * \param[in] points the points, each finite
 * \return one flag per point, 1 for a far point; all 0 when the radius is 0 (every
 *         point at one place) */
PCL_COCONE_EXPORT std::vector<std::uint8_t>
findFarPoints(const std::vector<Eigen::Vector3d>& points);

/** \brief The rounding step of single-precision floats at the largest coordinate of
 * \a points: how coarsely a cloud of float coordinates (as in every PCL point type)
 * can place them. 0.5 for coordinates around 5.4e6 (UTM northings).
 * \param[in] points the points, each finite
 * \return the distance between the float nearest to the largest absolute coordinate
 *         and the next float away from zero, in input units; 0 for an empty array */
PCL_COCONE_EXPORT double floatRoundingStep(const std::vector<Eigen::Vector3d>& points);

} // namespace cocone
} // namespace pcl
