// SPDX-License-Identifier: GPL-3.0-or-later
#include <pcl/cocone/core/status.h>

namespace pcl {
namespace cocone {

const char*
toString(Status status)
{
  switch (status) {
  case Status::ok:
    return "ok";
  case Status::not_computed:
    return "not_computed";
  case Status::too_few_points:
    return "too_few_points";
  case Status::non_finite_input:
    return "non_finite_input";
  case Status::degenerate_dimension:
    return "degenerate_dimension";
  case Status::too_many_points:
    return "too_many_points";
  case Status::invalid_parameter:
    return "invalid_parameter";
  case Status::internal_error:
    return "internal_error";
  }
  return "unknown";
}

} // namespace cocone
} // namespace pcl
