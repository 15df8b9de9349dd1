// SPDX-License-Identifier: GPL-3.0-or-later
// Private: running TBB work with the thread count the user chose. Free of CGAL, so that
// the mesher can use it too. Never installed.
#pragma once

#include <tbb/task_arena.h>

namespace pcl {
namespace cocone {
namespace detail {

/** Runs \a function with at most \a threads workers (0: TBB's default). */
template <typename Function>
void
runInArena(unsigned threads, Function&& function)
{
  if (threads == 0) {
    function();
    return;
  }
  tbb::task_arena arena(static_cast<int>(threads));
  arena.execute(function);
}

} // namespace detail
} // namespace cocone
} // namespace pcl
