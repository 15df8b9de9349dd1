// SPDX-License-Identifier: GPL-3.0-or-later
// Private: a stage's share of a progress callback (core/status.h). Never installed.
#pragma once

#include "common/status_guard.h"

#include <pcl/cocone/core/status.h>

#include <algorithm>

namespace pcl {
namespace cocone {
namespace detail {

/** The part [low, high] of a whole computation's progress that one stage reports in.
 * report() maps the stage's own share to it and calls the callback; a callback that
 * returns false cancels: report() throws StageFailure, which the entry's guard turns
 * into Status::internal_error with the message "cancelled". Only ever called from the
 * thread that called the entry, so that a callback may touch its caller's state (e.g.
 * Python's interpreter). Does nothing without a callback. */
class StageProgress
{
public:
  StageProgress(const ProgressCallback& callback, double low, double high)
    : callback_(callback), low_(low), high_(high)
  {}

  /** Reports that \a share (0 to 1) of this stage is done. */
  void
  report(double share) const
  {
    if (!callback_)
      return;
    const double done = low_ + (high_ - low_) * std::clamp(share, 0.0, 1.0);
    if (!callback_(done))
      throw StageFailure{Status::internal_error, "cancelled"};
  }

  /** The part [from, to] of this stage, as a stage of its own. */
  StageProgress
  part(double from, double to) const
  {
    return {callback_, low_ + (high_ - low_) * from, low_ + (high_ - low_) * to};
  }

private:
  const ProgressCallback& callback_;
  double low_, high_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
