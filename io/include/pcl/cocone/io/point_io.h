// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Reading samples from the file formats scans and test data come in. The tools use
 * these readers; they are public so that programs built on the library accept the same
 * files.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/Vertices.h>
#include <pcl/cocone/io/export.h>

#include <string>
#include <string_view>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Reads the samples of \a path into \a cloud, choosing the reader by the file
 * extension (case-insensitive):
 * - `.pcd`: PCL's reader (ascii, binary, binary_compressed); all fields are kept;
 * - `.ply`: ascii or binary PLY; the vertex element's properties become fields (x, y,
 *   z and whatever else the file has, e.g. normals, intensity); other elements (faces,
 *   range_grid) are skipped;
 * - `.obj`: the `v x y z` lines (extra coordinates such as w or vertex colours are
 *   ignored); faces are skipped;
 * - `.off`: OFF, COFF, NOFF headers; the vertices;
 * - `.xyz`, `.pts`, `.txt`: one point per line, whitespace-separated columns whose
 * first three are x y z (further columns are ignored); blank lines and lines starting
 * with
 *   `#` are skipped. Hoppe's a3d streams (his `.pts` files) are read as written: the
 *   points are the `p x y z` records; the normal, colour and command records (`n`,
 *   `d`, `s`, `g`, `o`, `O`, `f`, each with three numbers) are checked and set aside,
 *   `q` ends the stream, and polygon or polyline records (`P`, `L`, `v`, `E`) are an
 *   error;
 * - `.las`, `.laz`: LAS 1.0 to 1.4 (ASPRS), point data record formats 0 to 10, the
 *   legacy or (LAS 1.4) 64-bit point count: fields x, y, z (float, X * scale + offset
 *   from the header, so that far from the origin, e.g. in UTM coordinates, the float
 *   spacing grows to centimetres or more: translate such tiles near the origin first),
 *   intensity (uint16) and classification (uint8). LASzip-compressed data (LAZ) are
 *   refused with the commands that decompress them.
 *
 * Meshes are read as their vertices: the vertices are the samples. The cloud is
 * unorganized (height 1) unless the file itself is organized (PCD), and keeps every
 * point, NaN ones included, in file order.
 *
 * Every count, size and offset a file declares is checked, with arithmetic that cannot
 * overflow, against the bytes the file really has before anything is allocated, so
 * that memory stays bounded by the file's size: binary data must be there in full, a
 * compressed PCD block may not claim more than the 88-fold growth LZF allows, and
 * ascii data are counted line by line. Beyond that, two documented limits: a cloud
 * holds at most 4 GiB of point data (PCLPointCloud2's row_step has 32 bits), and a
 * PLY element at most 65535 properties. Malformed counts, and an ascii PLY with more
 * lines than its header declares, are errors.
 * \param[in] path the file to read
 * \param[out] cloud the samples, with float fields x, y, z at least, in the file's
 *             units; point i is the i-th point (vertex) of the file
 * \param[out] error if not null, receives a one-line reason on failure and is cleared
 *             on success
 * \return true on success; false if the file is missing, unreadable, malformed, of an
 *         unknown extension, or has no point (the cloud is then empty) */
PCL_COCONE_IO_EXPORT bool
loadPointSamples(const std::string& path, pcl::PCLPointCloud2& cloud,
                 std::string* error = nullptr);

/** \brief Reads the faces of a mesh file (`.ply`, `.obj`, `.off`) as polygons of vertex
 * indices (0-based, into the vertices loadPointSamples reads from the same file).
 * Polygons with more than three vertices are kept as they are.
 * \param[in] path the mesh file to read; the format is chosen by the extension
 *            (case-insensitive)
 * \param[out] faces one polygon per face, in file order, with indices into the points
 *             of the cloud loadPointSamples reads from \a path; empty on failure
 * \param[out] error if not null, receives a one-line reason on failure and is cleared
 *             on success
 * \return true on success (a file without faces gives an empty list); false if the file
 *         cannot be read or is not a mesh format */
PCL_COCONE_IO_EXPORT bool
loadMeshFaces(const std::string& path, std::vector<pcl::Vertices>& faces,
              std::string* error = nullptr);

/** \brief \a text with every byte that is not part of a valid UTF-8 sequence written
 * as `\xHH` (hexadecimal), so that a message quoting a file's bytes or a path is valid
 * UTF-8. The readers' and writers' reasons are already escaped so.
 * \param[in] text any bytes
 * \return the same text where it is valid UTF-8 (overlong forms, surrogates and code
 *         points beyond U+10FFFF are not), escapes elsewhere */
PCL_COCONE_IO_EXPORT std::string utf8Escaped(std::string_view text);

} // namespace cocone
} // namespace pcl
