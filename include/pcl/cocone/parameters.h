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
