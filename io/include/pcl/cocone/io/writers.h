// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Writing what the tools compute: clouds as binary PCD, triangle meshes as PLY, VTK or
 * OBJ, and any bytes (a picture, say) to a file, each reporting a failed write with the
 * system's reason instead of leaving a short file behind.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/cocone/io/export.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Writes \a size bytes from \a data to \a path.
 * \param[in] path the file to write
 * \param[in] data the bytes
 * \param[in] size their number
 * \param[out] error if not null, receives "cannot write", the path and the system's
 *             reason on failure, and is cleared on success
 * \return true if every byte was written; false otherwise, and then no partial file is
 *         left at \a path */
PCL_COCONE_IO_EXPORT bool
writeFile(const std::string& path,
          const void* data,
          std::size_t size,
          std::string* error = nullptr);

/** \brief Writes \a cloud to \a path as binary PCD: the header of pcl::PCDWriter, then
 * the data as they are (every field, the cloud's own layout).
 * \param[in] path the file to write
 * \param[in] cloud the cloud
 * \param[out] error as for writeFile; also set when the cloud's data size does not
 *             match width * height * point_step
 * \return true on success */
PCL_COCONE_IO_EXPORT bool
saveCloud(const std::string& path,
          const pcl::PCLPointCloud2& cloud,
          std::string* error = nullptr);

/** \brief Writes a triangle mesh to \a path in the format of its extension
 * (case-insensitive): `.ply` (binary little endian: float x y z, face list uchar int
 * vertex_indices), `.vtk` (legacy ASCII POLYDATA) or `.obj`. Coordinates are written
 * with enough digits to read back the same floats.
 * \param[in] path the file to write
 * \param[in] vertices the vertex positions
 * \param[in] triangles three 0-based vertex indices per triangle
 * \param[in] creator the program named in the file's comment ("written by" \a creator)
 * \param[out] error as for writeFile; also set for an unknown extension
 * \return true on success */
PCL_COCONE_IO_EXPORT bool
saveMesh(const std::string& path,
         const std::vector<std::array<float, 3>>& vertices,
         const std::vector<std::array<std::uint32_t, 3>>& triangles,
         const std::string& creator,
         std::string* error = nullptr);

} // namespace cocone
} // namespace pcl
