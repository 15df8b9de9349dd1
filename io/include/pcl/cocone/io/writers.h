// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Writing what the tools compute: clouds as binary PCD, triangle meshes as PLY, VTK or
 * OBJ, and any bytes (a picture, say) to a file. Every write is atomic (writeFile): a
 * failure gives the system's reason and leaves the files as they were. meshForWriting
 * makes a reconstruction's mesh as pcl_cocone_reconstruction and the Python module
 * write it, so that both write the same file.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/cocone/io/export.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/types.h>

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

/** \brief A reconstructed mesh as the tools write it (see meshForWriting). */
struct MeshForWriting
{
  /** The vertex positions: the input points with finite coordinates that are not far,
   * in input order. */
  std::vector<std::array<float, 3>> vertices;
  /** The triangles, renumbered to index \a vertices. */
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /** The input points left out for a NaN or infinite coordinate. */
  std::size_t non_finite_dropped = 0;
  /** The input points left out as far beyond the cloud's scale. */
  std::size_t far_dropped = 0;
};

/** \brief The mesh of a reconstruction over \a points as pcl_cocone_reconstruction and
 * the Python module's Mesh.save write it: the points with finite coordinates that are
 * not in \a far_points, in input order, and \a triangles renumbered to match. A NaN
 * vertex cannot be written to PLY or OBJ meaningfully, and a far point, in no triangle,
 * would make a viewer zoom out to it. Write the result with saveMesh.
 * \param[in] points the reconstruction's input cloud
 * \param[in] triangles three indices of \a points per triangle
 * \param[in] far_points the points the reconstruction left out as far
 *            (CoconeReconstruction::getFarIndices())
 * \param[out] mesh the vertices and triangles to write, and what was left out
 * \param[out] error if not null, receives a one-line reason on failure and is cleared
 *             on success
 * \return true on success; false when a triangle uses an index beyond \a points, a
 *         point with a non-finite coordinate or a far point, or a far index is beyond
 *         \a points (then \a mesh is empty) */
PCL_COCONE_IO_EXPORT bool
meshForWriting(const pcl::PointCloud<pcl::PointXYZ>& points,
               const std::vector<std::array<std::uint32_t, 3>>& triangles,
               const pcl::Indices& far_points, MeshForWriting& mesh,
               std::string* error = nullptr);

/** \brief Whether saveMesh writes the format of \a path's extension (`.ply`, `.vtk`,
 * `.obj`, case-insensitive).
 * \param[in] path a file name or path
 * \return true for the extensions saveMesh knows */
PCL_COCONE_IO_EXPORT bool isMeshFormat(const std::string& path);

} // namespace cocone
} // namespace pcl
