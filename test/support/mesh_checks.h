// SPDX-License-Identifier: GPL-3.0-or-later
// Geometric checks of reconstructed meshes, for tests and benchmarks (CGAL inside).
#pragma once

#include <pcl/cocone/core/mesh_geometry.h>
#include <pcl/cocone/core/mesh_topology.h>

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

// countSelfIntersections comes from the library: pcl/cocone/core/mesh_geometry.h.

/** Distances from a set of query points to a triangle mesh (AABB tree); +infinity
 * when the mesh has no triangle with area, 0 when there are no queries. */
struct DistanceStats
{
  double max = 0;
  double mean = 0;
  double rms = 0;
};
DistanceStats distancesToMesh(const std::vector<Eigen::Vector3d>& queries,
                              const std::vector<Eigen::Vector3d>& points,
                              const std::vector<TriangleIndices>& triangles);

/** Points sampled uniformly (by area, deterministic) on a triangle mesh: \a
 * per_triangle points per triangle on average, plus the vertices used. */
std::vector<Eigen::Vector3d>
samplePointsOnMesh(const std::vector<Eigen::Vector3d>& points,
                   const std::vector<TriangleIndices>& triangles,
                   double per_triangle = 3);

/** The diagonal of the bounding box of \a points (non-empty). */
double boundingBoxDiagonal(const std::vector<Eigen::Vector3d>& points);

/** Symmetric Hausdorff distance between two meshes, estimated with samplePointsOnMesh
 * on each side. */
double hausdorffDistance(const std::vector<Eigen::Vector3d>& points_a,
                         const std::vector<TriangleIndices>& triangles_a,
                         const std::vector<Eigen::Vector3d>& points_b,
                         const std::vector<TriangleIndices>& triangles_b);

/** For a closed, consistently oriented mesh: the signed volume (positive when the
 * triangles face outward). */
double signedVolume(const std::vector<Eigen::Vector3d>& points,
                    const std::vector<TriangleIndices>& triangles);

/** Asserts (with gtest EXPECT_*) everything every reconstruction must satisfy: only
 * manifold edges and vertices, consistent orientation, no self-intersection; reports
 * the topology in the test output (RecordProperty and stdout). Returns the topology. */
MeshTopology expectValidSurface(const std::vector<Eigen::Vector3d>& points,
                                const std::vector<TriangleIndices>& triangles,
                                const std::string& label);

} // namespace test
} // namespace cocone
} // namespace pcl
