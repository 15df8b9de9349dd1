// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/mesh_checks.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

namespace pcl {
namespace cocone {
namespace test {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;

std::vector<Point>
toCgal(const std::vector<Eigen::Vector3d>& points)
{
  std::vector<Point> result;
  result.reserve(points.size());
  for (const Eigen::Vector3d& p : points)
    result.emplace_back(p.x(), p.y(), p.z());
  return result;
}

void
checkIndices(std::size_t num_points, const std::vector<TriangleIndices>& triangles)
{
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t)
      if (v >= num_points)
        throw std::out_of_range("triangle vertex index " + std::to_string(v) +
                                " out of range (" + std::to_string(num_points) +
                                " points)");
}

} // namespace

DistanceStats
distancesToMesh(const std::vector<Eigen::Vector3d>& queries,
                const std::vector<Eigen::Vector3d>& points,
                const std::vector<TriangleIndices>& triangles)
{
  checkIndices(points.size(), triangles);
  DistanceStats stats;
  if (queries.empty())
    return stats;
  const std::vector<Point> p = toCgal(points);
  std::vector<Triangle> cgal_triangles;
  cgal_triangles.reserve(triangles.size());
  for (const TriangleIndices& t : triangles)
    if (!CGAL::collinear(p[t[0]], p[t[1]], p[t[2]]))
      cgal_triangles.emplace_back(p[t[0]], p[t[1]], p[t[2]]);
  if (cgal_triangles.empty()) {
    const double inf = std::numeric_limits<double>::infinity();
    stats.max = stats.mean = stats.rms = inf;
    return stats;
  }
  using Primitive =
      CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Tree tree(cgal_triangles.begin(), cgal_triangles.end());
  tree.accelerate_distance_queries();
  double sum = 0, sum_squares = 0;
  for (const Eigen::Vector3d& q : queries) {
    const double squared = tree.squared_distance(Point(q.x(), q.y(), q.z()));
    const double d = std::sqrt(squared);
    stats.max = std::max(stats.max, d);
    sum += d;
    sum_squares += squared;
  }
  stats.mean = sum / static_cast<double>(queries.size());
  stats.rms = std::sqrt(sum_squares / static_cast<double>(queries.size()));
  return stats;
}

std::vector<Eigen::Vector3d>
samplePointsOnMesh(const std::vector<Eigen::Vector3d>& points,
                   const std::vector<TriangleIndices>& triangles, double per_triangle)
{
  checkIndices(points.size(), triangles);
  std::vector<double> cumulative(triangles.size() + 1, 0.0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const TriangleIndices& tri = triangles[t];
    const double area =
        0.5 *
        (points[tri[1]] - points[tri[0]]).cross(points[tri[2]] - points[tri[0]]).norm();
    cumulative[t + 1] = cumulative[t] + area;
  }
  const double total_area = cumulative.back();
  const double total_samples =
      std::max(0.0, std::round(per_triangle * static_cast<double>(triangles.size())));

  std::vector<Eigen::Vector3d> result;
  std::vector<std::uint8_t> used(points.size(), 0);
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t)
      if (!used[v]) {
        used[v] = 1;
        result.push_back(points[v]);
      }
  if (total_area <= 0)
    return result;

  // Each triangle gets the samples whose rank falls into its share of the cumulative
  // area: the counts are proportional to the areas and add up exactly.
  std::mt19937 rng(20010521u);
  auto uniform = [&rng]() { return (rng() >> 8) * (1.0 / 16777216.0); };
  std::size_t emitted = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto until = static_cast<std::size_t>(
        std::floor(cumulative[t + 1] / total_area * total_samples + 0.5));
    const TriangleIndices& tri = triangles[t];
    for (; emitted < until; ++emitted) {
      double u = uniform(), v = uniform();
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      result.push_back(points[tri[0]] + u * (points[tri[1]] - points[tri[0]]) +
                       v * (points[tri[2]] - points[tri[0]]));
    }
  }
  return result;
}

double
hausdorffDistance(const std::vector<Eigen::Vector3d>& points_a,
                  const std::vector<TriangleIndices>& triangles_a,
                  const std::vector<Eigen::Vector3d>& points_b,
                  const std::vector<TriangleIndices>& triangles_b)
{
  const double a_to_b =
      distancesToMesh(samplePointsOnMesh(points_a, triangles_a), points_b, triangles_b)
          .max;
  const double b_to_a =
      distancesToMesh(samplePointsOnMesh(points_b, triangles_b), points_a, triangles_a)
          .max;
  return std::max(a_to_b, b_to_a);
}

double
signedVolume(const std::vector<Eigen::Vector3d>& points,
             const std::vector<TriangleIndices>& triangles)
{
  checkIndices(points.size(), triangles);
  // Divergence theorem with the field x / 3; the terms are taken relative to the
  // centroid so that a mesh far from the origin loses no precision.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    centre += p;
  if (!points.empty())
    centre /= static_cast<double>(points.size());
  double six_volume = 0;
  for (const TriangleIndices& t : triangles)
    six_volume += (points[t[0]] - centre)
                      .dot((points[t[1]] - centre).cross(points[t[2]] - centre));
  return six_volume / 6.0;
}

MeshTopology
expectValidSurface(const std::vector<Eigen::Vector3d>& points,
                   const std::vector<TriangleIndices>& triangles,
                   const std::string& label)
{
  const MeshTopology topology = analyzeTriangleMesh(triangles);
  std::size_t bad_indices = 0;
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t)
      bad_indices += v >= points.size();
  EXPECT_EQ(bad_indices, 0u) << label << ": vertex indices out of range";
  EXPECT_GT(topology.triangles, 0u) << label << ": empty mesh";
  EXPECT_EQ(topology.non_manifold_edges, 0u) << label << ": non-manifold edges";
  EXPECT_EQ(topology.non_manifold_vertices, 0u) << label << ": non-manifold vertices";
  EXPECT_EQ(topology.degenerate_triangles, 0u) << label << ": degenerate triangles";
  EXPECT_EQ(topology.duplicate_triangles, 0u) << label << ": duplicate triangles";
  EXPECT_EQ(topology.inconsistently_oriented_edges, 0u)
      << label << ": inconsistently oriented edges";
  const std::size_t intersections =
      bad_indices == 0 ? countSelfIntersections(points, triangles) : 0;
  EXPECT_EQ(intersections, 0u) << label << ": self-intersecting triangle pairs";

  std::ostringstream loops;
  for (std::size_t i = 0; i < topology.boundary_loops.size(); ++i)
    loops << (i ? "," : "") << topology.boundary_loops[i].size();
  std::ostringstream line;
  line << label << ": V=" << topology.vertices << " E=" << topology.edges
       << " F=" << topology.triangles << " chi=" << topology.eulerCharacteristic()
       << " components=" << topology.components << " genus=" << topology.genus()
       << " boundary_loops=" << topology.boundary_loops.size() << " [" << loops.str()
       << "] boundary_edges=" << topology.boundary_edges
       << " non_manifold_edges=" << topology.non_manifold_edges
       << " non_manifold_vertices=" << topology.non_manifold_vertices
       << " misoriented_edges=" << topology.inconsistently_oriented_edges
       << " self_intersections=" << intersections;
  std::cout << "[ surface  ] " << line.str() << std::endl;

  ::testing::Test::RecordProperty(label + ".vertices",
                                  std::to_string(topology.vertices));
  ::testing::Test::RecordProperty(label + ".triangles",
                                  std::to_string(topology.triangles));
  ::testing::Test::RecordProperty(label + ".components",
                                  std::to_string(topology.components));
  ::testing::Test::RecordProperty(label + ".genus", std::to_string(topology.genus()));
  ::testing::Test::RecordProperty(label + ".boundary_loops",
                                  std::to_string(topology.boundary_loops.size()));
  ::testing::Test::RecordProperty(label + ".self_intersections",
                                  std::to_string(intersections));
  return topology;
}

double
boundingBoxDiagonal(const std::vector<Eigen::Vector3d>& points)
{
  Eigen::Vector3d low = points.front(), high = points.front();
  for (const Eigen::Vector3d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return (high - low).norm();
}

} // namespace test
} // namespace cocone
} // namespace pcl
