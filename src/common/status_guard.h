// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the one guard every exported core entry runs in, so that no exception
// crosses the core's boundary (core/status.h). Never installed.
#pragma once

#include <pcl/cocone/core/status.h>

#include <exception>
#include <new>
#include <string>

namespace pcl {
namespace cocone {
namespace detail {

/** Sets *message to \a text when a message is wanted. */
inline void
setMessage(std::string* message, const std::string& text)
{
  if (message)
    *message = text;
}

/** Thrown by a stage that got a failed Status from another core entry: runGuarded
 * passes its status and message on unchanged. */
struct StageFailure
{
  Status status;
  std::string message;
};

/** Runs \a body, which returns a Status, and turns whatever it throws into
 * Status::internal_error with a one-line \a message that names \a stage (e.g.
 * "out of memory during stitching"). CGAL's failures (CGAL::Failure_exception) are
 * std::exceptions too. Writing the message can itself run out of memory; then the
 * status still says internal_error. */
template <typename Body>
Status
runGuarded(const char* stage, std::string* message, Body&& body) noexcept
{
  try {
    try {
      return body();
    }
    catch (const StageFailure& failure) {
      setMessage(message, failure.message);
      return failure.status;
    }
    catch (const std::bad_alloc&) {
      setMessage(message, std::string("out of memory during ") + stage);
    }
    catch (const std::exception& e) {
      setMessage(message, std::string(stage) + " failed: " + e.what());
    }
    catch (...) {
      setMessage(message, std::string(stage) + " failed: unknown exception");
    }
  }
  catch (...) { // the message itself could not be built
  }
  return Status::internal_error;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
