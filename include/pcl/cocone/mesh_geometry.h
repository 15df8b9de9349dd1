// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Geometric checks of triangle meshes given as index triples into a point array.
 */
#pragma once

#include <pcl/cocone/export.h>
#include <pcl/cocone/mesh_topology.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief True when triangles \a a and \a b (indices into \a points) intersect other
 * than along the edge or at the vertex they share; touching counts as intersecting.
 * Exact predicates: the answer is right for any coordinates. */
PCL_COCONE_EXPORT bool
trianglesIntersect(const std::vector<Eigen::Vector3d>& points,
                   const TriangleIndices& a,
                   const TriangleIndices& b);

/** \brief Number of pairs of triangles of \a triangles that intersect (see
 * trianglesIntersect); 0 for a mesh without self-intersection. Triangles without area
 * (a repeated index or collinear corners) are skipped. Bounding-box filtered:
 * O(T log T) for a well-spread mesh.
 * \throws std::out_of_range for an index outside \a points */
PCL_COCONE_EXPORT std::size_t
countSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<TriangleIndices>& triangles);

} // namespace cocone
} // namespace pcl
