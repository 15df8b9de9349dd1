// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Quality of a reconstructed triangle mesh: topology (pcl/cocone/core/mesh_topology.h),
 * self-intersections (pcl/cocone/core/mesh_geometry.h) and the two-sided distance to
 * the input's reference surface (analytic, or the file's mesh through a CGAL AABB
 * tree).
 */
#pragma once

#include "bench_common.h"
#include "bench_inputs.h"

#include <pcl/cocone/core/mesh_topology.h>

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl {
namespace cocone {
namespace bench {

/** \brief Meshes with more triangles are not checked for self-intersections; the
 * tables say "skipped". The check takes about 1 s per million triangles of a mesh (its
 * grid of cells), so every 1M-point input is checked and the 4M ones are not. */
constexpr std::size_t kSelfIntersectionLimit = 3000000;

/** \brief Distance from points to a triangle mesh (CGAL AABB tree, EPICK). */
class TriangleDistance
{
public:
  TriangleDistance(const std::vector<Eigen::Vector3d>& vertices,
                   const std::vector<TriangleIndices>& triangles);
  ~TriangleDistance();
  /** \brief False when the mesh has no triangle with area. */
  bool valid() const;
  double operator()(const Eigen::Vector3d& query) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/** \brief Two-sided distance between a mesh and an input's reference surface, in
 * units of the input's spacing: max and mean of both directions. NaN without
 * reference. */
struct SurfaceDistance
{
  double to_reference_max =
      0; ///< mesh -> reference (vertices + one point per triangle)
  double to_reference_mean = 0;
  double from_reference_max = 0; ///< reference probes -> mesh
  double from_reference_mean = 0;
  double
  hausdorff() const
  {
    return std::max(to_reference_max, from_reference_max);
  }
  double
  mean() const
  {
    return 0.5 * (to_reference_mean + from_reference_mean);
  }
};
SurfaceDistance
surfaceDistance(const Input& input, const std::vector<Eigen::Vector3d>& vertices,
                const std::vector<TriangleIndices>& triangles);

/** \brief Records the quality of a mesh in \a m: triangles, used (share of the distinct
 * input samples that are mesh vertices; NaN unless \a vertices_are_samples),
 * nm_edges, nm_vertices, boundary_edges, loops, closed, chi, genus, oriented,
 * components, self_intersections (NaN when skipped), d_hausdorff and d_mean (two-sided,
 * in spacings; NaN without reference) and their one-sided parts. */
void recordMeshQuality(const Input& input, const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<TriangleIndices>& triangles,
                       bool vertices_are_samples, Measurement& m);

} // namespace bench
} // namespace cocone
} // namespace pcl
