// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Second-level API (see core/voronoi_cocone.h): scanner noise. How much a cloud's
 * samples scatter about a smooth surface, measured against their own spacing, and the
 * smoothed copy (scale space) on which VoronoiCocone::compute builds the diagram when
 * the scatter is too large for the cocone geometry. The samples themselves are never
 * moved: every result stays indexed by the input samples, and a mesh keeps the input
 * coordinates as its vertices.
 */
#pragma once

#include <pcl/cocone/export.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Neighbours of a sample in the smaller local fit: the sample and its 15
 * nearest others; the larger fit and the smoothing take twice as many. A quadric height
 * field has 6 coefficients; 16 points leave 10 degrees of freedom for the residual, and
 * keep the neighbourhood small against the curvature of coarse clouds (the residual of
 * an exact sample grows with the neighbourhood's radius cubed). */
constexpr unsigned kNoiseNeighbours = 16;

/** \brief The share of the measured neighbourhoods whose noise lies below the cloud's
 * (NoiseEstimate::relative_noise): its lower quartile. Noise is everywhere, whereas the
 * neighbourhoods that meet a crease, a thin part or an undersampled bend measure high
 * for other reasons; on coarse clouds they are many (more than half of them on a
 * 1000-point cube), and the quartile still sees past them. */
constexpr double kNoiseQuantile = 0.25;

/** \brief The noise level above which the diagram is built on a smoothed copy (see
 * NoiseEstimate::relative_noise: about sigma / spacing for Gaussian noise).
 *
 * Evidence (docs/noise.md, measured with estimateNoise): exact samples of the test
 * shapes (torus, hemisphere, genus 3, cube, open cylinder, sphere; 1000 to 100k, blue
 * noise and random) measure below 0.0001; the shared meshes and clean point sets 0 to
 * 0.017 (cactus, knot, fandisk, 3holes 0; mannequin 0.001, rocker arm 0.002, kitten
 * 0.005, foot 0.006, armadillo 0.012, dragon 0.017, zippered bunny 0.017). Gaussian
 * noise measures 0.014 to 0.025 at sigma = 0.03 spacings, 0.078 to 0.083 at 0.1, 0.22
 * to 0.25 at 0.3, and the shared scans 0.038 (PCL's 397-point bunny, a coarse subsample
 * of a scan) to 0.19 (LiDAR terrain 0.041, raw bunny scan 0.047, gargoyle 0.11, table
 * scene 0.12, milk carton 0.19). The threshold lies between the clean clouds (1.8 times
 * the largest) and the scans (0.8 times the smallest); noise of 0.03 spacings, which
 * costs a torus 2 spurious loops, stays below it. */
constexpr double kNoiseThreshold = 0.03;

/** \brief The thickest neighbourhood (the smallest over the middle eigenvalue of the
 * covariance of a sample's 2 kNoiseNeighbours nearest samples) that counts as a patch
 * of a surface, noisy or not. A thicker one measures no noise; when fewer than half of
 * the probes are patches, the cloud measures none (its surface is not sampled densely
 * enough to be seen at this scale, and smoothing would fold it further).
 *
 * Evidence (median over the probes, measured with numpy): clean sphere 0.001; a torus
 * with Gaussian noise of 0.3, 0.5 and 1.0 spacings 0.046, 0.115 and 0.34 (upper
 * quartile 0.43 at 1.0); the shared scans 0.006 (raw bunny) to 0.18 (LiDAR terrain,
 * upper quartile 0.35; PCL's 397-point bunny 0.075, milk 0.045, gargoyle 0.031, table
 * 0.02). Samples that are no surface at this scale: Power Crust's 1281-point knot 0.65,
 * random 600- and 1000-point knots 0.67 and 0.56 (lower quartiles 0.56 and 0.43), a
 * random ball 0.65. Before this bound, the 600-point knot measured as noise of 0.74
 * spacings and was smoothed into an open tube. */
constexpr double kMaxPatchThickness = 0.4;

/** \brief How noisy a cloud is. */
struct NoiseEstimate
{
  /** The noise in local spacings: the lower quartile (kNoiseQuantile), over the
   * measured samples, of the noise at each. There, quadrics are fitted (least squares
   * over the plane of the principal axes) to the sample's kNoiseNeighbours and
   * 2 kNoiseNeighbours nearest samples; each leaves an RMS residual (sum of squares
   * over the degrees of freedom), and the noise is what the residual would be at radius
   * 0, taking the part of an exact sample to grow as the radius to the sixth power in
   * the square (the cubic terms beyond the quadric); it is divided by the local spacing
   * (the smaller neighbourhood's radius in the plane times sqrt(pi / kNoiseNeighbours):
   * the spacing of evenly spread samples filling that disc). Dimensionless: about
   * 0.8 sigma / spacing for Gaussian noise of standard deviation sigma (the quartile
   * of a spread estimate), and below 0.0001 on exact samples of smooth and creased
   * surfaces. 0 when nothing could be measured, or when fewer than half of the probes
   * are patches of a surface (kMaxPatchThickness). */
  double relative_noise = 0;
  /** How many neighbourhoods were measured (up to kNoiseProbes). */
  std::size_t measured = 0;
};

/** \brief The number of samples, spread evenly over the index range, whose
 * neighbourhoods estimateNoise measures. */
constexpr std::size_t kNoiseProbes = 4096;

/** \brief Measures the noise of a cloud (see NoiseEstimate) on up to kNoiseProbes
 * samples spread evenly over the index range. Deterministic for a given array, whatever
 * the number of threads.
 * \param[in] points the samples, each finite, in any unit
 * \param[in] threads worker threads (0: every core)
 * \return the estimate; relative_noise 0 for fewer than kNoiseNeighbours points
 * \throws std::bad_alloc when memory runs out */
PCL_COCONE_EXPORT NoiseEstimate
estimateNoise(const std::vector<Eigen::Vector3d>& points, unsigned threads = 0);

/** \brief The largest number of smoothing rounds. */
constexpr unsigned kMaxSmoothingRounds = 4;

/** \brief What smoothSamples made. */
struct SmoothedSamples
{
  /** One point per sample, same order as the input: each sample moved along the normal
   * of its local quadric onto it, round after round. */
  std::vector<Eigen::Vector3d> points;
  /** The rounds run, 1 to kMaxSmoothingRounds. */
  unsigned rounds = 0;
  /** The noise left after the last round, measured as NoiseEstimate::relative_noise
   * on the same neighbourhoods. */
  double remaining_noise = 0;
};

/** \brief A smoothed copy of \a points (scale space): each round fits a quadric height
 * field to every sample's 2 kNoiseNeighbours nearest neighbours (chosen once, on the
 * input: the neighbourhood adapts to the local density) and moves the sample onto it
 * along the fit's normal, which leaves its place along the surface unchanged. The
 * rounds stop once the noise left, measured as estimateNoise does, falls below half of
 * kNoiseThreshold, or after kMaxSmoothingRounds. Identical points stay identical.
 * Deterministic for a given array, whatever the number of threads. \param[in] points
 * the samples, each finite, at least kNoiseNeighbours of them \param[in] threads worker
 * threads (0: every core) \return the smoothed copy; a copy of \a points when they are
 * too few \throws std::bad_alloc when memory runs out */
PCL_COCONE_EXPORT SmoothedSamples
smoothSamples(const std::vector<Eigen::Vector3d>& points, unsigned threads = 0);

} // namespace cocone
} // namespace pcl
