// SPDX-License-Identifier: GPL-3.0-or-later
// A folder of its own for one test, and the fields of a PCLPointCloud2, shared by the
// reader and writer tests. Header only.
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

namespace pcl {
namespace cocone {
namespace test {

/** A new empty folder under GoogleTest's TempDir, named after \a prefix, the process
 * and a counter, so that tests running in parallel never share one. It is removed with
 * everything in it when the object dies, its permissions restored first (for tests
 * that take them away). */
class ScratchFolder
{
public:
  explicit ScratchFolder(const std::string& prefix)
  {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::path(::testing::TempDir()) /
            (prefix + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }

  ~ScratchFolder()
  {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }

  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::filesystem::path&
  path() const
  {
    return path_;
  }

private:
  std::filesystem::path path_;
};

/** The field \a name of \a cloud, or null. */
inline const pcl::PCLPointField*
findField(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  for (const pcl::PCLPointField& field : cloud.fields)
    if (field.name == name)
      return &field;
  return nullptr;
}

/** The value of field \a name of point \a point as a T (T{} when there is no such
 * field). */
template <typename T>
T
valueAt(const pcl::PCLPointCloud2& cloud, std::size_t point, const std::string& name)
{
  const pcl::PCLPointField* field = findField(cloud, name);
  T value{};
  if (field)
    std::memcpy(&value, cloud.data.data() + point * cloud.point_step + field->offset,
                sizeof(T));
  return value;
}

} // namespace test
} // namespace cocone
} // namespace pcl
