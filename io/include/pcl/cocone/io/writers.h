// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Writing what the tools compute: clouds as binary PCD, triangle meshes as PLY, VTK or
 * OBJ, and any bytes (a picture, say) to a file. Every write is atomic (writeFile): a
 * failure gives the system's reason and leaves the files as they were.
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

/** \brief Writes \a size bytes from \a data to \a path, atomically: to a new file in
 * the same folder, synced, then renamed over \a path. Until the rename \a path is
 * untouched, so a failed write (a full disk, a quota, a file size limit) leaves it as
 * it was and \a path may be the file the data were read from. A file replaced keeps
 * its permission bits; a new one gets 0666 less the umask, as with fopen. A symbolic
 * link is followed (the file it names is replaced); a device or FIFO is written
 * directly. A file size limit (RLIMIT_FSIZE) ends the process with SIGXFSZ unless the
 * program ignores that signal, as the tools do; then the write fails with "File too
 * large" and leaves nothing behind.
 * \param[in] path the file to write
 * \param[in] data the bytes
 * \param[in] size their number
 * \param[out] error if not null, receives "cannot write", the path and the system's
 *             reason on failure, and is cleared on success
 * \return true if every byte was written; false otherwise, and then \a path is as it
 *         was and no temporary file is left */
PCL_COCONE_IO_EXPORT bool writeFile(const std::string& path, const void* data,
                                    std::size_t size, std::string* error = nullptr);

/** \brief Writes \a cloud to \a path as binary PCD: the header of pcl::PCDWriter, then
 * the data as they are (every field, the cloud's own layout).
 * \param[in] path the file to write
 * \param[in] cloud the cloud
 * \param[out] error as for writeFile; also set when the cloud's data size does not
 *             match width * height * point_step
 * \return true on success */
PCL_COCONE_IO_EXPORT bool
saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
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
saveMesh(const std::string& path, const std::vector<std::array<float, 3>>& vertices,
         const std::vector<std::array<std::uint32_t, 3>>& triangles,
         const std::string& creator, std::string* error = nullptr);

} // namespace cocone
} // namespace pcl
