// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the local sample spacing, the mesher's unit of length, and the size of a
// hole or patch in that unit (which decides what is a true boundary). Never installed.
#pragma once

#include <pcl/cocone/core/voronoi_cocone.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
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

/** Whether a hole or patch of \a area and \a perimeter is larger than
 * \a true_boundary_ratio local spacings of \a spacing: twice the area over the
 * perimeter (see the source). The size half of HoleRule. */
bool isTrueBoundary(double area, double perimeter, double spacing,
                    double true_boundary_ratio);

/** What BOUNDARY says along the rim of a hole or patch. */
struct RimFlags
{
  std::size_t rim = 0;      ///< distinct rim samples
  std::size_t flagged = 0;  ///< of which flagged
  std::size_t distinct = 0; ///< flags more than kDistinctFlagDistance spacings apart
};

/** A flag within this many local spacings of one counted already is not counted again
 * in RimFlags::distinct (a close pair of a random sample flags twice at one place). */
constexpr double kDistinctFlagDistance = 0.25;
/** A true boundary has at least this share of its rim samples flagged (the lowest
 * share measured on the true rims of the shared scans is 0.30; most sampling gaps have
 * no flag at all)... */
constexpr double kTrueRimFlagShare = 0.2;
/** ... at this many distinct places at least (no gap of a smooth random shape at 100k
 * showed 2; 3 leaves the lids over small holes of real scans; see the source). */
constexpr std::size_t kTrueRimDistinctFlags = 2;

/** A hole of fewer than this many edges that the polygon fill can close (the last
 * stage of stitching) ... */
constexpr std::size_t kSmallHoleEdges = 10;
/** ... stays open only with flags at this many distinct places at least: at 4M random
 * samples a gap can flag 2 places of its own rim (see the source). */
constexpr std::size_t kSmallHoleDistinctFlags = 3;

/** A flagged sample is at a sharp edge when the unflagged samples near it have pole
 * vectors (signs aside) more than this far apart (cosine of 60 degrees) ... */
constexpr double kCreaseCosine = 0.5;
/** ... and every one of them is within this of one of those two (cosine of 25
 * degrees): the two faces are each nearly flat at this scale ... */
constexpr double kCreaseFaceCosine = 0.906;
/** ... each of the two groups holding at least this many of them ... */
constexpr std::size_t kCreaseFaceNormals = 2;
/** ... near it meaning at most two Delaunay edges away and within this many local
 * spacings of it, the spacing being the median over its Delaunay neighbours'. */
constexpr double kCreaseReach = 3;

/** BOUNDARY's flags \a boundary, less those at sharp edges (kCreaseCosine, with the
 * local spacings \a spacing of measureLocalSpacing): the flags
 * that HoleRule takes as evidence of a true boundary. A sharp edge is undersampled at
 * any density (the paper's motivation for BOUNDARY), so its flags say nothing about a
 * hole across it; see the source. In parallel, with the threads of \a voronoi. */
std::vector<std::uint8_t>
rimEvidence(const VoronoiCocone& voronoi, const std::vector<std::uint8_t>& boundary,
            const std::vector<double>& spacing);

/** The decision between a true boundary, which stays open, and an undersampling hole,
 * which the mesher closes (see the source for the rule and the evidence behind each
 * constant): a hole or patch is a true boundary when
 *  (a) it is larger than true_boundary_ratio local spacings (isTrueBoundary above),
 *  (b) at least kTrueRimFlagShare of its rim samples are BOUNDARY's flags (less those
 *      at sharp edges: rimEvidence), and
 *  (c) those flags are at least kTrueRimDistinctFlags distinct places, or
 *      kSmallHoleDistinctFlags for a small hole at the polygon fill.
 * The same rule decides wherever a hole is judged: lids, stitching, polygon fills. */
class HoleRule
{
public:
  /** Judges with the flags \a boundary (one per sample of \a points; all 0 makes
   * every hole an undersampling hole) and the size ratio \a true_boundary_ratio. */
  HoleRule(const std::vector<Eigen::Vector3d>& points,
           const std::vector<std::uint8_t>& boundary, double true_boundary_ratio)
    : points_(points), boundary_(boundary), ratio_(true_boundary_ratio)
  {}

  /** The flags along \a rim (samples; repeats count once), \a spacing apart. */
  RimFlags rimFlags(const std::vector<SampleIndex>& rim, double spacing) const;

  /** Whether the hole or patch of \a area and \a perimeter whose rim runs through the
   * samples \a rim, \a spacing apart, is a true boundary. */
  bool isTrueBoundary(double area, double perimeter, double spacing,
                      const std::vector<SampleIndex>& rim) const;

  /** The same for a hole that the polygon fill would close, \a loop being its loop:
   * isTrueBoundary, and a loop of fewer than kSmallHoleEdges edges needs flags at
   * kSmallHoleDistinctFlags places. */
  bool isTrueBoundaryAtPolygonFill(double area, double perimeter, double spacing,
                                   const std::vector<SampleIndex>& loop) const;

  double
  sizeRatio() const
  {
    return ratio_;
  }

private:
  /** isTrueBoundary, with flags at \a places distinct places at least. */
  bool judge(double area, double perimeter, double spacing,
             const std::vector<SampleIndex>& rim, std::size_t places) const;

  const std::vector<Eigen::Vector3d>& points_;
  const std::vector<std::uint8_t>& boundary_;
  const double ratio_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
