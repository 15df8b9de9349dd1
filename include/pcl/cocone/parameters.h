// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The valid ranges of the parameters shared by the three classes and the tools, and
 * the one check every setter makes.
 */
#pragma once

#include <pcl/console/print.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace pcl {
namespace cocone {

/** \brief A closed, open or half-open interval of valid values. */
struct ParameterRange
{
  double low;
  double high;
  bool low_open;
  bool high_open;

  /** \brief True when \a value lies in the interval (NaN never does). */
  constexpr bool
  contains(double value) const
  {
    return (low_open ? value > low : value >= low) &&
           (high_open ? value < high : value <= high);
  }

  /** \brief The interval as text, e.g. "(0, 10]". */
  std::string
  text() const
  {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%c%g, %g%c", low_open ? '(' : '[', low, high,
                  high_open ? ')' : ']');
    return buffer;
  }
};

/** Cocone angle theta, radians. */
constexpr ParameterRange kCoconeAngleRange{0, M_PI / 2, true, true};
/** Ratio bound rho of BOUNDARY and DECIMATE, dimensionless. */
constexpr ParameterRange kRatioBoundRange{0, 10, true, false};
/** Normal agreement angle alpha of BOUNDARY, radians. */
constexpr ParameterRange kNormalAngleRange{0, M_PI / 2, true, false};
/** True-boundary size ratio of the reconstruction, in local spacings. */
constexpr ParameterRange kTrueBoundaryRatioRange{0.5, 1000, false, false};
/** Rings of the optional boundary band. */
constexpr ParameterRange kBandRingsRange{0, 64, false, false};

/** \brief Whether \a value may be set; if not, says so with PCL_ERROR, e.g.
 * "[pcl::CoconeReconstruction::setRatioBound] rho = -1 is outside (0, 10]; keeping
 * 0.99." */
inline bool
acceptParameter(const std::string& class_name,
                const char* setter,
                const char* name,
                double value,
                const ParameterRange& range,
                double current)
{
  if (range.contains(value))
    return true;
  PCL_ERROR("[pcl::%s::%s] %s = %g is outside %s; keeping %g.\n", class_name.c_str(),
            setter, name, value, range.text().c_str(), current);
  return false;
}

} // namespace cocone
} // namespace pcl
