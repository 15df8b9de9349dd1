// SPDX-License-Identifier: GPL-3.0-or-later
#include "cloud_layout.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace pcl {
namespace cocone {
namespace io_internal {

namespace {

template <typename T>
T
loadScalar(const std::uint8_t* source, bool swap)
{
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, source, sizeof(T));
  if (swap)
    std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <typename T>
void
storeScalar(std::uint8_t* target, T value)
{
  std::memcpy(target, &value, sizeof(T));
}

template <typename T>
bool
fitsRange(double value)
{
  return value >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
         value <= static_cast<double>(std::numeric_limits<T>::max());
}

} // namespace

float
toFloat(double value)
{
  constexpr double max = std::numeric_limits<float>::max();
  if (value > max)
    return std::numeric_limits<float>::infinity();
  if (value < -max)
    return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

double
loadValue(const std::uint8_t* source, std::uint8_t datatype, bool swap)
{
  switch (datatype) {
  case Field::INT8:
    return loadScalar<std::int8_t>(source, swap);
  case Field::UINT8:
    return loadScalar<std::uint8_t>(source, swap);
  case Field::INT16:
    return loadScalar<std::int16_t>(source, swap);
  case Field::UINT16:
    return loadScalar<std::uint16_t>(source, swap);
  case Field::INT32:
    return loadScalar<std::int32_t>(source, swap);
  case Field::UINT32:
    return loadScalar<std::uint32_t>(source, swap);
  case Field::INT64:
    return static_cast<double>(loadScalar<std::int64_t>(source, swap));
  case Field::UINT64:
    return static_cast<double>(loadScalar<std::uint64_t>(source, swap));
  case Field::FLOAT32:
    return loadScalar<float>(source, swap);
  case Field::FLOAT64:
    return loadScalar<double>(source, swap);
  case Field::BOOL:
    return loadScalar<std::uint8_t>(source, swap) != 0 ? 1.0 : 0.0;
  }
  return 0;
}

void
storeValue(std::uint8_t* target, std::uint8_t datatype, double value)
{
  switch (datatype) {
  case Field::INT8:
    return storeScalar(target, static_cast<std::int8_t>(value));
  case Field::UINT8:
    return storeScalar(target, static_cast<std::uint8_t>(value));
  case Field::INT16:
    return storeScalar(target, static_cast<std::int16_t>(value));
  case Field::UINT16:
    return storeScalar(target, static_cast<std::uint16_t>(value));
  case Field::INT32:
    return storeScalar(target, static_cast<std::int32_t>(value));
  case Field::UINT32:
    return storeScalar(target, static_cast<std::uint32_t>(value));
  case Field::FLOAT32:
    return storeScalar(target, toFloat(value));
  case Field::FLOAT64:
    return storeScalar(target, value);
  }
}

bool
fitsDatatype(double value, std::uint8_t datatype)
{
  switch (datatype) {
  case Field::INT8:
    return fitsRange<std::int8_t>(value);
  case Field::UINT8:
    return fitsRange<std::uint8_t>(value);
  case Field::INT16:
    return fitsRange<std::int16_t>(value);
  case Field::UINT16:
    return fitsRange<std::uint16_t>(value);
  case Field::INT32:
    return fitsRange<std::int32_t>(value);
  case Field::UINT32:
    return fitsRange<std::uint32_t>(value);
  default:
    return true; // floats take anything, NaN included
  }
}

void
appendField(pcl::PCLPointCloud2& cloud, const std::string& name, std::uint8_t datatype,
            std::uint32_t count)
{
  const auto size = static_cast<std::uint32_t>(pcl::getFieldSize(datatype));
  Field field;
  field.name = name;
  field.datatype = datatype;
  field.count = count;
  field.offset = (cloud.point_step + size - 1) / size * size;
  cloud.fields.push_back(field);
  cloud.point_step = field.offset + size * count;
}

void
checkDataSize(std::uint64_t point_step, std::uint64_t points)
{
  constexpr std::uint64_t max = std::numeric_limits<std::uint32_t>::max();
  if (point_step > 0 && points > max / point_step)
    throw std::length_error("more than 4 GiB of point data (" + std::to_string(points) +
                            " points of " + std::to_string(point_step) + " bytes)");
}

void
finishLayout(pcl::PCLPointCloud2& cloud, std::size_t points)
{
  std::uint32_t alignment = 1;
  for (const Field& field : cloud.fields)
    alignment = std::max<std::uint32_t>(alignment, pcl::getFieldSize(field.datatype));
  cloud.point_step = (cloud.point_step + alignment - 1) / alignment * alignment;
  checkDataSize(cloud.point_step, points);
  cloud.width = static_cast<std::uint32_t>(points);
  cloud.height = 1;
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_bigendian = false;
  cloud.data.assign(static_cast<std::size_t>(cloud.point_step) * points, 0);
}

int
fieldIndex(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  for (std::size_t i = 0; i < cloud.fields.size(); ++i)
    if (cloud.fields[i].name == name)
      return static_cast<int>(i);
  return -1;
}

bool
allFinite(const pcl::PCLPointCloud2& cloud)
{
  const std::uint32_t offsets[3] = {cloud.fields[fieldIndex(cloud, "x")].offset,
                                    cloud.fields[fieldIndex(cloud, "y")].offset,
                                    cloud.fields[fieldIndex(cloud, "z")].offset};
  const std::size_t points = static_cast<std::size_t>(cloud.width) * cloud.height;
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    for (const std::uint32_t offset : offsets) {
      float value;
      std::memcpy(&value, point + offset, sizeof(float));
      if (!std::isfinite(value))
        return false;
    }
  }
  return true;
}

void
makeXyzCloud(const std::vector<float>& xyz, pcl::PCLPointCloud2& cloud)
{
  cloud = pcl::PCLPointCloud2();
  appendField(cloud, "x", Field::FLOAT32);
  appendField(cloud, "y", Field::FLOAT32);
  appendField(cloud, "z", Field::FLOAT32);
  finishLayout(cloud, xyz.size() / 3);
  if (!xyz.empty())
    std::memcpy(cloud.data.data(), xyz.data(), xyz.size() * sizeof(float));
  cloud.is_dense = allFinite(cloud);
}

void
makeXyzFloat(pcl::PCLPointCloud2& cloud)
{
  bool convert = false;
  for (const Field& field : cloud.fields)
    if ((field.name == "x" || field.name == "y" || field.name == "z") &&
        field.datatype != Field::FLOAT32)
      convert = true;
  if (!convert)
    return;
  pcl::PCLPointCloud2 out;
  out.header = cloud.header;
  for (const Field& field : cloud.fields) {
    const bool coordinate = field.name == "x" || field.name == "y" || field.name == "z";
    appendField(out, field.name,
                coordinate ? static_cast<std::uint8_t>(Field::FLOAT32) : field.datatype,
                field.count);
  }
  const std::uint32_t width = cloud.width;
  const std::uint32_t height = cloud.height;
  finishLayout(out, static_cast<std::size_t>(width) * height);
  out.width = width;
  out.height = height;
  out.row_step = out.point_step * width;
  const std::size_t points = static_cast<std::size_t>(width) * height;
  for (std::size_t i = 0; i < points; ++i) {
    const std::uint8_t* from = cloud.data.data() + i * cloud.point_step;
    std::uint8_t* to = out.data.data() + i * out.point_step;
    for (std::size_t f = 0; f < cloud.fields.size(); ++f) {
      const Field& source = cloud.fields[f];
      const Field& target = out.fields[f];
      if (source.datatype == target.datatype)
        std::memcpy(to + target.offset, from + source.offset,
                    pcl::getFieldSize(source.datatype) * source.count);
      else
        storeValue(to + target.offset, target.datatype,
                   loadValue(from + source.offset, source.datatype, false));
    }
  }
  cloud = std::move(out);
}

} // namespace io_internal
} // namespace cocone
} // namespace pcl
