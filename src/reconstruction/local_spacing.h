// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the local sample spacing, the mesher's unit of length, and the size of a
// hole or patch in that unit (which decides what is a true boundary). Never installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** The local spacing of every sample (see the source): one value per sample, 0 for a
 * sample in no marked triangle. In parallel, with the threads of \a voronoi. */
std::vector<double> measureLocalSpacing(const VoronoiCocone& voronoi);

/** The median of the positive spacings of \a samples; 0 when none is positive. */
double typicalSpacing(const std::vector<double>& spacing,
                      const std::vector<SampleIndex>& samples);

/** Whether a hole or patch of \a area and \a perimeter is a true boundary: larger than
 * \a true_boundary_ratio local spacings of \a spacing (see the source). */
bool isTrueBoundary(double area, double perimeter, double spacing,
                    double true_boundary_ratio);

} // namespace detail
} // namespace cocone
} // namespace pcl
