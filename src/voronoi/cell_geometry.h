// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the per-sample geometry pass of VoronoiCocone::compute. Never installed.
#pragma once

#include "voronoi/cgal_delaunay.h"
#include "voronoi/voronoi_cocone_impl.h"

namespace pcl {
namespace cocone {
namespace detail {

/** Circumcenters, poles, heights, radii and cocone marks of every sample of \a dt
 * (whose vertices carry their sample index), and the marked triangles with their
 * incidence lists, into \a d; the stars go to d.stars. Clears \a dt once its cells
 * are read. \a sin_theta is the sine of the cocone angle. */
void computeGeometry(Delaunay& dt, DiagramState& d, double sin_theta);

} // namespace detail
} // namespace cocone
} // namespace pcl
