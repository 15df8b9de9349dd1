// SPDX-License-Identifier: GPL-3.0-or-later
#include "bench_quality.h"

#include <pcl/cocone/core/mesh_geometry.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

namespace pcl {
namespace cocone {
namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Primitive =
    CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

} // namespace

struct TriangleDistance::Impl
{
  std::vector<Triangle> triangles;
  Tree tree;
};

TriangleDistance::TriangleDistance(const std::vector<Eigen::Vector3d>& vertices,
                                   const std::vector<TriangleIndices>& triangles)
  : impl_(std::make_unique<Impl>())
{
  impl_->triangles.reserve(triangles.size());
  for (const TriangleIndices& t : triangles) {
    const Point a(vertices[t[0]].x(), vertices[t[0]].y(), vertices[t[0]].z());
    const Point b(vertices[t[1]].x(), vertices[t[1]].y(), vertices[t[1]].z());
    const Point c(vertices[t[2]].x(), vertices[t[2]].y(), vertices[t[2]].z());
    if (!CGAL::collinear(a, b, c))
      impl_->triangles.emplace_back(a, b, c);
  }
  if (!impl_->triangles.empty()) {
    impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
    impl_->tree.build();
    impl_->tree.accelerate_distance_queries();
  }
}

TriangleDistance::~TriangleDistance() = default;

bool
TriangleDistance::valid() const
{
  return !impl_->triangles.empty();
}

double
TriangleDistance::operator()(const Eigen::Vector3d& q) const
{
  if (!valid())
    return std::numeric_limits<double>::infinity();
  return std::sqrt(impl_->tree.squared_distance(Point(q.x(), q.y(), q.z())));
}

SurfaceDistance
surfaceDistance(const Input& input, const std::vector<Eigen::Vector3d>& vertices,
                const std::vector<TriangleIndices>& triangles)
{
  SurfaceDistance d;
  if (!input.hasReference() || triangles.empty()) {
    d.to_reference_max = d.to_reference_mean = d.from_reference_max =
        d.from_reference_mean = triangles.empty() && input.hasReference()
                                    ? std::numeric_limits<double>::infinity()
                                    : kNaN;
    return d;
  }
  const double unit = input.spacing > 0 ? input.spacing : 1.0;

  // Mesh -> reference: the vertices in use and one random point per triangle (at most
  // a million of them).
  std::vector<Eigen::Vector3d> probes;
  {
    std::vector<std::uint8_t> used(vertices.size(), 0);
    for (const TriangleIndices& t : triangles)
      for (const std::uint32_t v : t)
        if (!used[v]) {
          used[v] = 1;
          probes.push_back(vertices[v]);
        }
    const std::size_t stride = std::max<std::size_t>(1, triangles.size() / 1000000);
    std::mt19937_64 random(99);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (std::size_t i = 0; i < triangles.size(); i += stride) {
      const TriangleIndices& t = triangles[i];
      double u = uniform(random), v = uniform(random);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      probes.push_back(vertices[t[0]] + u * (vertices[t[1]] - vertices[t[0]]) +
                       v * (vertices[t[2]] - vertices[t[0]]));
    }
  }
  double sum = 0, largest = 0;
  if (input.shape) {
    for (const Eigen::Vector3d& p : probes) {
      const double e = input.shape->distance_to_surface(p);
      sum += e;
      largest = std::max(largest, e);
    }
  }
  else {
    const TriangleDistance reference(input.mesh_vertices, input.mesh_triangles);
    for (const Eigen::Vector3d& p : probes) {
      const double e = reference(p);
      sum += e;
      largest = std::max(largest, e);
    }
  }
  d.to_reference_max = largest / unit;
  d.to_reference_mean =
      probes.empty() ? kNaN : sum / static_cast<double>(probes.size()) / unit;

  // Reference -> mesh.
  const TriangleDistance mesh(vertices, triangles);
  sum = 0;
  largest = 0;
  for (const Eigen::Vector3d& p : input.reference_probes) {
    const double e = mesh(p);
    sum += e;
    largest = std::max(largest, e);
  }
  d.from_reference_max = largest / unit;
  d.from_reference_mean =
      input.reference_probes.empty()
          ? kNaN
          : sum / static_cast<double>(input.reference_probes.size()) / unit;
  return d;
}

void
recordMeshQuality(const Input& input, const std::vector<Eigen::Vector3d>& vertices,
                  const std::vector<TriangleIndices>& triangles,
                  bool vertices_are_samples, Measurement& m)
{
  const MeshTopology topology = analyzeTriangleMesh(triangles);
  m.values["triangles"] = static_cast<double>(triangles.size());
  m.values["nm_edges"] = static_cast<double>(topology.non_manifold_edges);
  m.values["nm_vertices"] = static_cast<double>(topology.non_manifold_vertices);
  m.values["degenerate"] =
      static_cast<double>(topology.degenerate_triangles + topology.duplicate_triangles);
  m.values["boundary_edges"] = static_cast<double>(topology.boundary_edges);
  m.values["loops"] =
      topology.non_manifold_edges == 0 && topology.non_manifold_vertices == 0
          ? static_cast<double>(topology.boundary_loops.size())
          : kNaN;
  m.values["closed"] = topology.isClosed() ? 1 : 0;
  m.values["chi"] = static_cast<double>(topology.eulerCharacteristic());
  m.values["genus"] = static_cast<double>(topology.genus());
  m.values["oriented"] = topology.isConsistentlyOriented() ? 1 : 0;
  m.values["components"] = static_cast<double>(topology.components);

  if (vertices_are_samples && input.unique > 0) {
    std::vector<std::array<double, 3>> used;
    std::vector<std::uint8_t> seen(vertices.size(), 0);
    for (const TriangleIndices& t : triangles)
      for (const std::uint32_t v : t)
        if (!seen[v]) {
          seen[v] = 1;
          used.push_back({vertices[v].x(), vertices[v].y(), vertices[v].z()});
        }
    std::sort(used.begin(), used.end());
    const auto distinct =
        static_cast<double>(std::unique(used.begin(), used.end()) - used.begin());
    m.values["used"] = std::min(1.0, distinct / static_cast<double>(input.unique));
  }
  else
    m.values["used"] = kNaN;

  if (triangles.size() <= kSelfIntersectionLimit)
    m.values["self_intersections"] =
        static_cast<double>(countSelfIntersections(vertices, triangles));
  else
    m.values["self_intersections"] = kNaN;

  const SurfaceDistance d = surfaceDistance(input, vertices, triangles);
  m.values["d_hausdorff"] = d.hausdorff();
  m.values["d_mean"] = d.mean();
  m.values["d_to_ref_max"] = d.to_reference_max;
  m.values["d_from_ref_max"] = d.from_reference_max;
}

} // namespace bench
} // namespace cocone
} // namespace pcl
