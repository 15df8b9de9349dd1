// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Geometric checks of triangle meshes given as index triples into a point array.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/core/mesh_topology.h>

#include <Eigen/Core>

#include <cstddef>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief Whether two triangles of a mesh intersect other than along the edge or at
 * the vertex they share (shared by index); touching counts as intersecting. Exact
 * predicates: the answer is right for any coordinates.
 * \param[in] points the vertex coordinates (any unit)
 * \param[in] a first triangle, as three indices into \a points
 * \param[in] b second triangle, as three indices into \a points
 * \return true when \a a and \a b intersect beyond their shared vertices; false
 *         otherwise, and always when either triangle has no area (a repeated index or
 *         collinear corners) or a non-finite corner
 * \throws std::out_of_range for an index outside \a points */
PCL_COCONE_EXPORT bool
trianglesIntersect(const std::vector<Eigen::Vector3d>& points, const TriangleIndices& a,
                   const TriangleIndices& b);

/** \brief Whether segment \a a \a b meets triangle \a t other than at a vertex they
 * share (by index); touching counts as meeting, and an edge of \a t meets it only in
 * itself. Exact predicates.
 * \param[in] points the vertex coordinates (any unit)
 * \param[in] a first end of the segment, an index into \a points
 * \param[in] b second end of the segment, an index into \a points
 * \param[in] t the triangle, as three indices into \a points
 * \return true when they meet beyond their shared vertex; false otherwise, and always
 *         when \a t has no area
 * \throws std::out_of_range for an index outside \a points */
PCL_COCONE_EXPORT bool
segmentCrossesTriangle(const std::vector<Eigen::Vector3d>& points, std::uint32_t a,
                       std::uint32_t b, const TriangleIndices& t);

/** \brief The pairs of triangles of a mesh that intersect (see trianglesIntersect).
 * Triangles without area (a repeated index or collinear corners) are skipped, and so
 * are triangles with a non-finite corner. Bounding-box filtered: a uniform grid for a
 * mesh of triangles alike in size (a few box tests per triangle), CGAL's segment tree
 * otherwise (O(T log^3 T) for any mesh).
 * \param[in] points the vertex coordinates (any unit)
 * \param[in] triangles the mesh, as index triples into \a points
 * \param[in] threads the most threads the grid's cells are tested on (0: every core);
 *            the pairs are the same for any count
 * \return the intersecting pairs as positions in \a triangles, the smaller first,
 *         sorted; empty for a mesh without self-intersection
 * \throws std::out_of_range for an index outside \a points */
PCL_COCONE_EXPORT std::vector<std::pair<std::size_t, std::size_t>>
findSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                      const std::vector<TriangleIndices>& triangles,
                      unsigned threads = 0);

/** \brief Counts the pairs of triangles of a mesh that intersect (see
 * trianglesIntersect). Triangles without area (a repeated index or collinear corners)
 * are skipped. Bounding-box filtered, as findSelfIntersections.
 * \param[in] points the vertex coordinates (any unit)
 * \param[in] triangles the mesh, as index triples into \a points
 * \param[in] threads the most threads to use (0: every core)
 * \return the number of intersecting pairs; 0 for a mesh without self-intersection
 * \throws std::out_of_range for an index outside \a points */
PCL_COCONE_EXPORT std::size_t
countSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<TriangleIndices>& triangles,
                       unsigned threads = 0);

} // namespace cocone
} // namespace pcl
