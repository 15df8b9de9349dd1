// SPDX-License-Identifier: GPL-3.0-or-later
//
// Values and point layout of the clouds the readers build: typed loads and stores,
// range checks, and fields appended at aligned offsets. Internal to pcl_cocone_io.
#pragma once

#include <pcl/PCLPointCloud2.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace io_internal {

using Field = pcl::PCLPointField;

/** double to float without the undefined behaviour of an out-of-range conversion. */
float toFloat(double value);

/** The value of \a datatype at \a source, byte-swapped when \a swap is set. */
double loadValue(const std::uint8_t* source, std::uint8_t datatype, bool swap);

/** Stores \a value as \a datatype; only called with values that fit the type (see
 * fitsDatatype). */
void storeValue(std::uint8_t* target, std::uint8_t datatype, double value);

/** Whether \a value is within the range of \a datatype (floats take anything, NaN
 * included). */
bool fitsDatatype(double value, std::uint8_t datatype);

/** Appends a field of \a count values at the next offset aligned to its size, so that
 * code reading it through a pointer of its type sees aligned data. */
void appendField(pcl::PCLPointCloud2& cloud, const std::string& name,
                 std::uint8_t datatype, std::uint32_t count = 1);

/** Fails (std::length_error) when \a points points of \a point_step bytes exceed the
 * 4 GiB that PCLPointCloud2's 32-bit row_step can describe: a documented limit of the
 * readers, checked before anything is allocated. */
void checkDataSize(std::uint64_t point_step, std::uint64_t points);

/** Pads the point to the alignment of its widest field and sizes the cloud for
 * \a points points (unorganized, zeroed). */
void finishLayout(pcl::PCLPointCloud2& cloud, std::size_t points);

/** The index of the field \a name, -1 if there is none. */
int fieldIndex(const pcl::PCLPointCloud2& cloud, const std::string& name);

/** is_dense as PCL means it: every point has finite x, y and z (float fields). */
bool allFinite(const pcl::PCLPointCloud2& cloud);

/** An x, y, z float cloud of the coordinates \a xyz (three per point). */
void makeXyzCloud(const std::vector<float>& xyz, pcl::PCLPointCloud2& cloud);

/** Rewrites x, y and z stored as other types (double, integers) as float. */
void makeXyzFloat(pcl::PCLPointCloud2& cloud);

} // namespace io_internal
} // namespace cocone
} // namespace pcl
