// SPDX-License-Identifier: GPL-3.0-or-later
//
// The format readers behind loadPointSamples and loadMeshFaces, one source file per
// format. Each parses the whole file already in memory (\a text) and fails through
// \a source (FormatError); point_io.cpp chooses among them by extension. Internal to
// pcl_cocone_io; the fuzz targets (fuzz/) call them directly.
#pragma once

#include "text_scan.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/Vertices.h>

#include <string>
#include <string_view>
#include <vector>

namespace pcl {
namespace cocone {
namespace io_internal {

/** .xyz, .pts, .txt: appends three coordinates per point to \a xyz. */
void readColumns(const Source& source, std::string_view text, std::vector<float>& xyz);

/** Wavefront OBJ: the `v` lines into \a xyz and, when \a faces is set, the `f` lines
 * (0-based). */
void readObj(const Source& source, std::string_view text, std::vector<float>& xyz,
             std::vector<pcl::Vertices>* faces);

/** Geomview OFF: the vertices into \a xyz and, when \a faces is set, the faces. */
void readOff(const Source& source, std::string_view text, std::vector<float>& xyz,
             std::vector<pcl::Vertices>* faces);

/** PLY: the vertex element's scalar properties as fields of \a cloud. */
void readPlyVertices(const Source& source, std::string_view text,
                     pcl::PCLPointCloud2& cloud);

/** PLY: the face element's vertex_indices (or vertex_index) list. */
void readPlyFaces(const Source& source, std::string_view text,
                  std::vector<pcl::Vertices>& faces);

/** LAS 1.0 to 1.4, point formats 0 to 10: x, y, z, intensity and classification as
 * fields of \a cloud. LAZ is refused. */
void readLas(const Source& source, std::string_view text, pcl::PCLPointCloud2& cloud);

/** PCD: \a text is checked here, then PCL's reader parses it. */
void readPcd(const Source& source, std::string_view text, pcl::PCLPointCloud2& cloud);

} // namespace io_internal
} // namespace cocone
} // namespace pcl
