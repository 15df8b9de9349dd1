// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): DECIMATE (Dey et al. 2001, section 4)
 * and the relaxation that may follow it, the non-template algorithms behind
 * VoronoiDecimation. DECIMATE consumes the diagram it runs on, so it takes it by
 * rvalue reference.
 */
#pragma once

#include <pcl/cocone/core/status.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/export.h>
#include <pcl/cocone/parameters.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Result of DECIMATE: for every sample, the ratio bound from which on it is
 * removed.
 *
 * For any rho in (0, largest_ratio_bound], sample i is kept by DECIMATE(P, rho)
 * exactly when `level[i] >= rho` (removed for every larger rho). Duplicates get level
 * 0 (never kept). The levels nest: the set kept at a larger rho is a subset of the set
 * kept at a smaller one, and each is what a separate run at that rho returns (the
 * removal order is the same prefix; the neighbour lists a run keeps depend on its rho,
 * see src/decimation/decimation.cpp, and the tests find the sets identical). Samples
 * not removed up to largest_ratio_bound get +infinity. After a relaxation, the levels
 * describe its output: a sample it moved to has level largest_ratio_bound, one it
 * moved from a level just below it; the sets kept at smaller rho still contain both.
 */
struct DecimationLevels
{
  /** One entry per sample, indexed by SampleIndex (size VoronoiCocone::size());
   * dimensionless like rho. */
  std::vector<double> level;
  double largest_ratio_bound = 0;   ///< the rho the run went up to (dimensionless)
  std::size_t removals = 0;         ///< samples removed (duplicates not counted)
  std::size_t relaxation_moves = 0; ///< kept samples the relaxation replaced
};

/** \brief Runs DECIMATE (paper section 4) up to the ratio bound, then, when
 * parameters.relaxation_iterations > 0, relaxDecimatedSample on the kept samples.
 *
 * Heights and pole vectors stay those of the full sample; cocone radii are measured
 * again only for the samples whose Voronoi cell a removal changed; the sample with the
 * smallest ratio goes first (ties by the smaller sample index), and the run stops when
 * no remaining sample has a ratio below rho or only 4 distinct samples are left. The
 * cells are kept up to date from Delaunay neighbour lists, not from a triangulation:
 * the diagram is consumed, and \a voronoi is left empty (status()
 * Status::not_computed, size() 0; its cocone angle and threads stay) however the run
 * ends. The cocone angle and the threads are \a voronoi's.
 * \param[in,out] voronoi a diagram on which compute() succeeded; consumed
 * \param[in] parameters see DecimationParameters
 * \param[in] boundary BOUNDARY's flags on \a voronoi (detectBoundarySamples with
 *            default BoundaryParameters), one per sample: the rims measured on one
 *            side when parameters.thin_rims, the samples the relaxation holds when it
 *            runs. May be empty when neither is asked for
 * \param[out] levels per-sample removal levels, indexed by SampleIndex (see
 *             DecimationLevels); reset first. A cancelled run leaves the removals made
 *             so far
 * \param[in] progress optional, called from this thread with the share done every
 *            1024 removals and with 1 at the end; returning false cancels
 *            (Status::internal_error, message "cancelled")
 * \param[out] message if given, the one-line reason of a failure (unchanged on
 *             success)
 * \return Status::ok; Status::not_computed when \a voronoi holds no diagram;
 *         Status::invalid_parameter for a value outside its range (isValid) or
 *         \a boundary of the wrong size; Status::internal_error when cancelled or out
 *         of memory */
PCL_COCONE_EXPORT Status decimate(VoronoiCocone&& voronoi,
                                  const DecimationParameters& parameters,
                                  const std::vector<std::uint8_t>& boundary,
                                  DecimationLevels& levels,
                                  const ProgressCallback& progress = nullptr,
                                  std::string* message = nullptr);

/** \brief Beyond the paper: evens out a decimated sample, keeping its size.
 *
 * Lloyd's iteration over the input samples: each kept sample starts a generator; every
 * round, each generator moves to the centroid of the samples nearest to it (weighted by
 * the share of the surface each stands for, its squared cocone radius on the full
 * sample), and the sample of its cluster nearest to it is the one it would keep. The
 * rounds stop when fewer than 1% of those choices change, or after \a iterations. The
 * generators move freely between rounds; only the choices are samples. A generator
 * stays on its kept sample when it, or a sample of its cluster, is \a fixed.
 * Deterministic. decimate() runs it when asked; it is exported for other front ends.
 * \param[in] voronoi the diagram of the full sample, from compute() (only positions
 *            and cocone radii are read)
 * \param[in] fixed per sample (size voronoi.size()): 1 for samples that must not move
 *            and hold the kept sample nearest them (BOUNDARY's flags: rims, sharp
 *            features)
 * \param[in] iterations at most this many rounds (0: nothing changes)
 * \param[in] threads worker threads (0: every core)
 * \param[in,out] kept per sample (size voronoi.size()): 1 for a kept sample; the count
 *            never changes, duplicates are never chosen
 * \param[out] moves the number of kept samples replaced
 * \param[out] message if given, the one-line reason of a failure (unchanged on
 *             success)
 * \return Status::ok; Status::invalid_parameter when a size does not match (then
 *         nothing changes and \a moves is 0); Status::internal_error when memory ran
 *         out (then \a kept is as given) */
PCL_COCONE_EXPORT Status relaxDecimatedSample(const VoronoiCocone& voronoi,
                                              const std::vector<std::uint8_t>& fixed,
                                              unsigned iterations, unsigned threads,
                                              std::vector<std::uint8_t>& kept,
                                              std::size_t& moves,
                                              std::string* message = nullptr);

} // namespace cocone
} // namespace pcl
