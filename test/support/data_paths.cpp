// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/data_paths.h"

#include <pcl/cocone/io/point_io.h>
#include <pcl/conversions.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace pcl {
namespace cocone {
namespace test {

std::string
dataDirectory()
{
  if (const char* overridden = std::getenv("PCL_COCONE_DATA_DIR"))
    if (*overridden != '\0')
      return overridden;
#ifdef PCL_COCONE_DATA_DIR
  // The default is spelled relative to the source tree (".../main/../shared/data");
  // resolved, the skip messages name a folder one can look for. weakly_canonical, not
  // lexically_normal, so that ".." after a symbolic link goes where the system goes.
  std::error_code ec;
  const std::filesystem::path resolved =
      std::filesystem::weakly_canonical(PCL_COCONE_DATA_DIR, ec);
  return ec ? std::string(PCL_COCONE_DATA_DIR) : resolved.string();
#else
  return std::string();
#endif
}

std::string
dataFile(const std::string& file)
{
  const std::string directory = dataDirectory();
  if (directory.empty())
    return std::string();
  const std::filesystem::path path = std::filesystem::path(directory) / file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return std::string();
  return path.string();
}

pcl::PointCloud<pcl::PointXYZ>::Ptr
loadCloud(const std::string& path)
{
  pcl::PCLPointCloud2 blob;
  std::string error;
  EXPECT_TRUE(pcl::cocone::loadPointSamples(path, blob, &error)) << error;
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::fromPCLPointCloud2(blob, *cloud);
  return cloud;
}

} // namespace test
} // namespace cocone
} // namespace pcl
