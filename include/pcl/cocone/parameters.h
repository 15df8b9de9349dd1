// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The parameters of the three classes, in one shape: every class holds the diagram's
 * parameters (VoronoiParameters: the cocone angle and the threads) and those of its
 * algorithm (BoundaryParameters, ReconstructionParameters or DecimationParameters).
 * The core functions take the same structs. Each value has a documented unit, default
 * and valid range; setters check it with acceptParameter, whole structs with isValid.
 */
#pragma once

#include <pcl/console/print.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace pcl {
namespace cocone {

class TileExchange; // core/tile_exchange.h

/** \brief A closed, open or half-open interval of valid values, in the unit of the
 * parameter it bounds. */
struct ParameterRange
{
  double low;     ///< lower end of the interval
  double high;    ///< upper end of the interval
  bool low_open;  ///< true: \a low is excluded, "(low, ..."; false: "[low, ..."
  bool high_open; ///< true: \a high is excluded, "..., high)"; false: "..., high]"

  /** \brief Whether \a value lies in the interval.
   * \param[in] value the value to test, in the parameter's unit
   * \return true when \a value lies in the interval; false otherwise, and always for
   *         NaN */
  constexpr bool
  contains(double value) const
  {
    return (low_open ? value > low : value >= low) &&
           (high_open ? value < high : value <= high);
  }

  /** \brief The interval as text, for messages.
   * \return the interval in mathematical notation, e.g. "(0, 10]" (printf's %g for the
   *         ends) */
  std::string
  text() const
  {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%c%g, %g%c", low_open ? '(' : '[', low, high,
                  high_open ? ')' : ']');
    return buffer;
  }
};

/** \brief Valid range of the cocone angle theta: (0, pi/2), radians. */
constexpr ParameterRange kCoconeAngleRange{0, M_PI / 2, true, true};
/** \brief Valid range of the ratio bound rho of BOUNDARY and DECIMATE: (0, 10],
 * dimensionless. */
constexpr ParameterRange kRatioBoundRange{0, 10, true, false};
/** \brief Valid range of the normal agreement angle alpha of BOUNDARY: (0, pi/2],
 * radians. */
constexpr ParameterRange kNormalAngleRange{0, M_PI / 2, true, false};
/** \brief Valid range of the true-boundary size ratio of the reconstruction:
 * [0.5, 1000], in local sample spacings. */
constexpr ParameterRange kTrueBoundaryRatioRange{0.5, 1000, false, false};
/** \brief Valid range of the number of rings of the optional boundary band: [0, 64],
 * rings of cocone neighbours. */
constexpr ParameterRange kBandRingsRange{0, 64, false, false};
/** \brief Valid range of the number of relaxation rounds after DECIMATE: [0, 1000]. */
constexpr ParameterRange kRelaxationIterationsRange{0, 1000, false, false};

/** \brief Whether the diagram is built on a smoothed copy of the samples (see
 * VoronoiParameters::denoise and docs/noise.md). */
enum class DenoiseMode
{
  automatic, ///< measure the cloud's noise (core/denoise.h) and smooth when it is noisy
  on,        ///< always smooth
  off        ///< never smooth: the diagram of the samples as given
};

/** \brief The name of a denoising mode, as the tools take it.
 * \param[in] mode the mode
 * \return "auto", "on" or "off" */
inline const char*
toString(DenoiseMode mode)
{
  switch (mode) {
  case DenoiseMode::on:
    return "on";
  case DenoiseMode::off:
    return "off";
  default:
    return "auto";
  }
}

/** \brief The mode named \a text ("auto", "on" or "off").
 * \param[in] text the name
 * \param[out] mode the mode, when \a text names one (unchanged otherwise)
 * \return whether \a text names a mode */
inline bool
parseDenoiseMode(const std::string& text, DenoiseMode& mode)
{
  for (const DenoiseMode m :
       {DenoiseMode::automatic, DenoiseMode::on, DenoiseMode::off})
    if (text == toString(m)) {
      mode = m;
      return true;
    }
  return false;
}

/** \brief Parameters of the Voronoi diagram that every class builds first. */
struct VoronoiParameters
{
  /** \brief theta, the cocone angle: the cocone of p is the part of its Voronoi cell
   * within theta of the plane orthogonal to the pole vector. Radians; default pi/8 (the
   * paper's value); valid range (0, pi/2) (kCoconeAngleRange). */
  double cocone_angle = M_PI / 8;
  /** \brief Worker threads of the per-sample work; 0 (default) lets TBB use every core;
   * any value is valid. Results do not depend on it. */
  unsigned threads = 0;
  /** \brief Beyond the paper: scanner noise. When on, the diagram (and with it every
   * pole, flag and triangle choice) is built on a smoothed copy of the samples (scale
   * space: each sample moved onto a quadric fitted to its nearest neighbours, a few
   * rounds), while every result stays indexed by the input samples, so that a mesh
   * keeps the input coordinates as its vertices. Automatic (default): on when the
   * cloud's measured noise exceeds kNoiseThreshold (core/denoise.h; clean clouds
   * measure below it and keep the results of the diagram as published); on; off. Any
   * value is valid. */
  DenoiseMode denoise = DenoiseMode::automatic;
  /** \brief Beyond the paper (after SuperCocone and distributed Delaunay): the number
   * of tiles the diagram is built in. The distinct samples are cut into this many tiles
   * balanced by count; each tile is triangulated with a halo of neighbouring samples,
   * grown until the Delaunay star of every sample of the tile is exactly its star in
   * the whole cloud; the tiles run in parallel and their results are joined. The
   * results do not depend on it: any tile count gives the same diagram, bit for bit.
   * A tile gives up when its halo would exceed 3 times its own samples (plus 2048)
   * and the diagram is then built as one tile; so it is where the Voronoi cells reach
   * far, as they do on compact surfaces cut into small tiles (a sphere's cells all
   * meet near its centre). 0 (default): automatic, which is one tile (the measured
   * halos, docs/scaling.md, cost more than parallel tiles gain on one machine; the
   * one triangulation is built on every core); 1: one tile. Any value is valid; it is
   * capped at 1024 and at one tile per 128 distinct samples. */
  unsigned tiles = 0;
  /** \brief Beyond the paper: the processes that build the diagram together
   * (core/tile_exchange.h; the MPI driver sets it). The tiles are dealt out among
   * them, the root joins their results, and the diagram is the same as without it.
   * Empty (default): this process builds the whole diagram. */
  std::shared_ptr<TileExchange> exchange;
};

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
   * whose nearby cocone neighbours leave a gap wider than 2 pi / 3 in its tangent plane
   * is flagged as well. Grown only from flags, it adds no flag to a shape that has
   * none. Default true; false gives BOUNDARY as published. Either value is valid. */
  bool complete_rim_row = true;
};

/** \brief Parameters of the reconstruction (the cocone angle is the diagram's). */
struct ReconstructionParameters
{
  /** \brief BOUNDARY's parameters (rho, alpha; see BoundaryParameters for units,
   * defaults and ranges); band_rings and complete_rim_row are ignored here: the samples
   * that cast no vote are BOUNDARY's as published. */
  BoundaryParameters boundary;
  /** \brief Detect boundary samples and let them cast no vote. Default true; false
   * gives the original COCONE candidate rule (a triangle needs the marks of all its
   * vertices). Either value is valid. */
  bool detect_boundary = true;
  /** \brief Close the holes that are not true boundaries. Default true; either value is
   * valid. */
  bool stitch_holes = true;
  /** \brief A hole is a true boundary, and stays open, when its size (twice its area
   * over its perimeter: the radius of a round hole, half the width of a long one)
   * exceeds this many local sample spacings and BOUNDARY flags its rim (a fifth of the
   * rim samples, at 2 places at least, 3 for a hole of fewer than 10 edges at the
   * polygon fill, flags at sharp edges aside: docs/topology.md); other holes are
   * stitched.
   * The same test removes candidate triangles that cover such a hole. In local spacings
   * (about 1.1 times sqrt(area / n) on evenly spread samples); default 2; valid range
   * [0.5, 1000] (kTrueBoundaryRatioRange). */
  double true_boundary_ratio = 2;
};

/** \brief Parameters of DECIMATE and what follows it. */
struct DecimationParameters
{
  /** \brief rho: samples with r_p / h_p below it are removed, smallest first.
   * Dimensionless; default 0.3; valid range (0, 10] (kRatioBoundRange), useful range
   * 0.25 to 0.4 (the paper removed 56% to 83% of its scans at 0.3). */
  double ratio_bound = 0.3;
  /** \brief Beyond the paper: measure each rim sample of an open surface on the side of
   * its Voronoi cell where the surface is, so that rims are thinned like the rest.
   * Default true; false gives DECIMATE as published. Either value is valid. */
  bool thin_rims = true;
  /** \brief Beyond the paper: rounds of relaxation that even out the kept sample at the
   * same size; 0 gives DECIMATE's own sample. Default 10; valid range [0, 1000]
   * (kRelaxationIterationsRange). */
  unsigned relaxation_iterations = 10;
};

/** \brief Whether the diagram's parameters lie in their ranges.
 * \param[in] parameters the values to check
 * \return true when every value lies in its documented range */
inline bool
isValid(const VoronoiParameters& parameters)
{
  return kCoconeAngleRange.contains(parameters.cocone_angle);
}

/** \brief Whether BOUNDARY's parameters lie in their ranges.
 * \param[in] parameters the values to check
 * \return true when every value lies in its documented range */
inline bool
isValid(const BoundaryParameters& parameters)
{
  return kRatioBoundRange.contains(parameters.ratio_bound) &&
         kNormalAngleRange.contains(parameters.normal_angle) &&
         kBandRingsRange.contains(parameters.band_rings);
}

/** \brief Whether the reconstruction's parameters lie in their ranges;
 * boundary.band_rings is checked too, although the reconstruction ignores it.
 * \param[in] parameters the values to check
 * \return true when every value lies in its documented range */
inline bool
isValid(const ReconstructionParameters& parameters)
{
  return isValid(parameters.boundary) &&
         kTrueBoundaryRatioRange.contains(parameters.true_boundary_ratio);
}

/** \brief Whether DECIMATE's parameters lie in their ranges.
 * \param[in] parameters the values to check
 * \return true when every value lies in its documented range */
inline bool
isValid(const DecimationParameters& parameters)
{
  return kRatioBoundRange.contains(parameters.ratio_bound) &&
         kRelaxationIterationsRange.contains(parameters.relaxation_iterations);
}

/** \brief Whether \a value may be set; if not, says so with PCL_ERROR, e.g.
 * "[pcl::CoconeReconstruction::setRatioBound] rho = -1 is outside (0, 10]; keeping
 * 0.99."
 * \param[in] class_name the class named in the message, e.g. "CoconeReconstruction"
 * \param[in] setter the function named in the message, e.g. "setRatioBound"
 * \param[in] name the parameter's name in the message, e.g. "rho"
 * \param[in] value the value to check, in the parameter's unit
 * \param[in] range the valid range of the parameter
 * \param[in] current the value kept when \a value is refused (only printed)
 * \return true when \a value lies in \a range; false (after PCL_ERROR) otherwise */
inline bool
acceptParameter(const std::string& class_name, const char* setter, const char* name,
                double value, const ParameterRange& range, double current)
{
  if (range.contains(value))
    return true;
  PCL_ERROR("[pcl::%s::%s] %s = %g is outside %s; keeping %g.\n", class_name.c_str(),
            setter, name, value, range.text().c_str(), current);
  return false;
}

} // namespace cocone
} // namespace pcl
