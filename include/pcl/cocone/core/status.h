// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): the outcome of every core entry and
 * the progress callback of the long ones.
 */
#pragma once

#include <pcl/cocone/export.h>

#include <functional>

namespace pcl {
namespace cocone {

/** \brief Outcome of a core computation.
 *
 * Every exported core entry returns one, and every failure comes with a one-line
 * reason (VoronoiCocone::errorMessage, or the entry's \a message argument). No
 * exception crosses the core's boundary: running out of memory, a failure inside CGAL
 * or any other exception becomes Status::internal_error with a message that says
 * where it happened. */
enum class Status
{
  ok,                   ///< success (for compute(): the diagram was built)
  not_computed,         ///< no diagram: compute() not run or failed, or decimate() ran
  too_few_points,       ///< fewer than 4 distinct points
  non_finite_input,     ///< a coordinate is NaN or infinite
  degenerate_dimension, ///< all points are coplanar or collinear: there is no 3D cell
  too_many_points,      ///< 2^32 - 1 points or more: more than a SampleIndex addresses
  invalid_parameter, ///< a parameter or an input's size is outside its documented range
  internal_error     ///< CGAL failed, memory ran out, or the run was cancelled
};

/** \brief Human-readable name of a status.
 * \param[in] status the status to name
 * \return the enumerator's name, e.g. "degenerate_dimension"; "unknown" for a value
 *         outside the enumeration */
PCL_COCONE_EXPORT const char* toString(Status status);

/** \brief Progress of a long computation: called with the share done, in [0, 1];
 * returning false cancels it (the computation then returns Status::internal_error with
 * the message "cancelled"). An empty function is never called. */
using ProgressCallback = std::function<bool(double)>;

/** \brief The part [low, high] of \a whole: a callback that reports a stage's own
 * share s (0 to 1) to \a whole as low + (high - low) s, for computations made of
 * several core calls.
 * \param[in] whole the callback of the whole computation; may be empty
 * \param[in] low the share of the whole done when the stage starts, in [0, 1]
 * \param[in] high the share done when it ends, in [low, 1]
 * \return the stage's callback; empty when \a whole is */
inline ProgressCallback
progressPart(const ProgressCallback& whole, double low, double high)
{
  if (!whole)
    return nullptr;
  return [whole, low, high](double share) { return whole(low + (high - low) * share); };
}

} // namespace cocone
} // namespace pcl
