// SPDX-License-Identifier: GPL-3.0-or-later
// Real scans live outside the repository (PCL_COCONE_DATA_DIR, by default
// ../shared/data); tests that need one skip with a clear message when it is absent.
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <string>

namespace pcl {
namespace cocone {
namespace test {

/** The data folder configured at build time (CMake cache variable PCL_COCONE_DATA_DIR),
 * overridable at run time with the environment variable PCL_COCONE_DATA_DIR. */
std::string dataDirectory();

/** Full path of \a file in the data folder, or an empty string if it is not there. */
std::string dataFile(const std::string& file);

/** The samples of the file at \a path as PointXYZ; a failed read is a test failure and
 * gives an empty cloud. */
pcl::PointCloud<pcl::PointXYZ>::Ptr loadCloud(const std::string& path);

} // namespace test
} // namespace cocone
} // namespace pcl

/** In a TEST body: binds \a variable to the path of \a file, or skips the test with a
 * message naming the missing file and the folder searched. */
#define PCL_COCONE_REQUIRE_DATA_FILE(variable, file)                                   \
  const std::string variable = ::pcl::cocone::test::dataFile(file);                    \
  if (variable.empty())                                                                \
  GTEST_SKIP() << "data file " << (file) << " not found in "                           \
               << ::pcl::cocone::test::dataDirectory()                                 \
               << " (set PCL_COCONE_DATA_DIR to the folder with the shared data)"
