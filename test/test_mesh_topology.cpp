// SPDX-License-Identifier: GPL-3.0-or-later
// analyzeTriangleMesh on small meshes whose topology is known by construction, and the
// geometric checks of test/support/mesh_checks.h.
#include <pcl/cocone/core/mesh_topology.h>

#include "support/mesh_checks.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

namespace {

using pcl::cocone::analyzeTriangleMesh;
using pcl::cocone::MeshTopology;
using pcl::cocone::TriangleIndices;
using Triangles = std::vector<TriangleIndices>;
using Points = std::vector<Eigen::Vector3d>;
namespace checks = pcl::cocone::test;

constexpr double kPi = 3.14159265358979323846;

// --- meshes --------------------------------------------------------------------------

/** Corners of the unit tetrahedron, faces oriented outward. */
Points
tetrahedronPoints()
{
  return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
}

Triangles
tetrahedron(std::uint32_t first = 0)
{
  const std::uint32_t a = first, b = first + 1, c = first + 2, d = first + 3;
  return {{a, c, b}, {a, b, d}, {a, d, c}, {b, c, d}};
}

/** Vertices +-x, +-y, +-z (0..5), faces oriented outward. */
Points
octahedronPoints()
{
  return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
}

Triangles
octahedron(std::uint32_t first = 0)
{
  Triangles result;
  const std::uint32_t px = 0, nx = 1, py = 2, ny = 3, pz = 4, nz = 5;
  for (const std::uint32_t x : {px, nx})
    for (const std::uint32_t y : {py, ny})
      for (const std::uint32_t z : {pz, nz}) {
        // (x, y, z) is counter-clockwise seen from outside when the octant has an even
        // number of negative axes.
        const bool even = ((x == nx) + (y == ny) + (z == nz)) % 2 == 0;
        if (even)
          result.push_back({first + x, first + y, first + z});
        else
          result.push_back({first + x, first + z, first + y});
      }
  return result;
}

/** A rows x cols grid of quads, two triangles each; vertex (i, j) is i * cols + j. With
 * wrap_rows / wrap_cols the grid closes up: a cylinder, or a torus with both. */
Triangles
grid(std::uint32_t rows, std::uint32_t cols, bool wrap_rows, bool wrap_cols)
{
  Triangles result;
  const std::uint32_t quad_rows = wrap_rows ? rows : rows - 1;
  const std::uint32_t quad_cols = wrap_cols ? cols : cols - 1;
  for (std::uint32_t i = 0; i < quad_rows; ++i)
    for (std::uint32_t j = 0; j < quad_cols; ++j) {
      const std::uint32_t i1 = (i + 1) % rows, j1 = (j + 1) % cols;
      const std::uint32_t a = i * cols + j, b = i * cols + j1, c = i1 * cols + j1,
                          d = i1 * cols + j;
      result.push_back({a, b, c});
      result.push_back({a, c, d});
    }
  return result;
}

Points
torusPoints(std::uint32_t rows, std::uint32_t cols)
{
  Points result;
  for (std::uint32_t i = 0; i < rows; ++i)
    for (std::uint32_t j = 0; j < cols; ++j) {
      const double u = 2 * kPi * i / rows, v = 2 * kPi * j / cols;
      const double ring = 1 + 0.35 * std::cos(v);
      result.emplace_back(ring * std::cos(u), ring * std::sin(u), 0.35 * std::sin(v));
    }
  return result;
}

/** Whether \a loop is the cycle \a expected, up to the starting vertex (same
 * direction). */
bool
sameCycle(const std::vector<std::uint32_t>& loop,
          const std::vector<std::uint32_t>& expected)
{
  if (loop.size() != expected.size() || loop.empty())
    return false;
  const auto start = std::find(expected.begin(), expected.end(), loop.front());
  if (start == expected.end())
    return false;
  const std::size_t offset = static_cast<std::size_t>(start - expected.begin());
  for (std::size_t i = 0; i < loop.size(); ++i)
    if (loop[i] != expected[(offset + i) % expected.size()])
      return false;
  return true;
}

// --- analyzeTriangleMesh -------------------------------------------------------------

TEST(MeshTopology, EmptyInput)
{
  const MeshTopology t = analyzeTriangleMesh({});
  EXPECT_EQ(t.vertices, 0u);
  EXPECT_EQ(t.edges, 0u);
  EXPECT_EQ(t.triangles, 0u);
  EXPECT_EQ(t.components, 0u);
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_FALSE(t.isClosed());
  EXPECT_EQ(t.eulerCharacteristic(), 0);
}

TEST(MeshTopology, SingleTriangle)
{
  const MeshTopology t = analyzeTriangleMesh({{7, 3, 9}});
  EXPECT_EQ(t.vertices, 3u);
  EXPECT_EQ(t.edges, 3u);
  EXPECT_EQ(t.triangles, 1u);
  EXPECT_EQ(t.boundary_edges, 3u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.isManifold());
  EXPECT_FALSE(t.isClosed());
  EXPECT_TRUE(t.isConsistentlyOriented());
  EXPECT_EQ(t.eulerCharacteristic(), 1);
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_TRUE(sameCycle(t.boundary_loops[0], {7, 3, 9}));
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, Tetrahedron)
{
  const MeshTopology t = analyzeTriangleMesh(tetrahedron());
  EXPECT_EQ(t.vertices, 4u);
  EXPECT_EQ(t.edges, 6u);
  EXPECT_EQ(t.triangles, 4u);
  EXPECT_EQ(t.boundary_edges, 0u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_EQ(t.non_manifold_vertices, 0u);
  EXPECT_EQ(t.inconsistently_oriented_edges, 0u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.isClosed());
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_EQ(t.eulerCharacteristic(), 2);
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, Octahedron)
{
  const MeshTopology t = analyzeTriangleMesh(octahedron());
  EXPECT_EQ(t.vertices, 6u);
  EXPECT_EQ(t.edges, 12u);
  EXPECT_EQ(t.triangles, 8u);
  EXPECT_TRUE(t.isClosed());
  EXPECT_TRUE(t.isConsistentlyOriented());
  EXPECT_EQ(t.eulerCharacteristic(), 2);
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, TorusFromGrid)
{
  const MeshTopology t = analyzeTriangleMesh(grid(12, 8, true, true));
  EXPECT_EQ(t.vertices, 96u);
  EXPECT_EQ(t.edges, 3u * 96u);
  EXPECT_EQ(t.triangles, 2u * 96u);
  EXPECT_TRUE(t.isClosed());
  EXPECT_TRUE(t.isConsistentlyOriented());
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.eulerCharacteristic(), 0);
  EXPECT_EQ(t.genus(), 1);
}

TEST(MeshTopology, DiscHasOneLoopInTriangleOrder)
{
  // A fan around vertex 0 over the ring 1..8: triangle (0, i, i + 1) traverses the rim
  // edge i -> i + 1.
  Triangles fan;
  const std::uint32_t ring = 8;
  for (std::uint32_t i = 0; i < ring; ++i)
    fan.push_back({0, 1 + i, 1 + (i + 1) % ring});
  const MeshTopology t = analyzeTriangleMesh(fan);
  EXPECT_EQ(t.vertices, 9u);
  EXPECT_EQ(t.edges, 16u);
  EXPECT_EQ(t.boundary_edges, 8u);
  EXPECT_TRUE(t.isManifold());
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_TRUE(sameCycle(t.boundary_loops[0], {1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(t.eulerCharacteristic(), 1);
  EXPECT_EQ(t.genus(), 0);

  // Reversing every triangle reverses the loop.
  for (TriangleIndices& tri : fan)
    std::swap(tri[1], tri[2]);
  const MeshTopology reversed = analyzeTriangleMesh(fan);
  ASSERT_EQ(reversed.boundary_loops.size(), 1u);
  EXPECT_TRUE(sameCycle(reversed.boundary_loops[0], {8, 7, 6, 5, 4, 3, 2, 1}));
}

TEST(MeshTopology, CylinderHasTwoLoops)
{
  // Rows 0..3 of a grid closed around its columns: rows 0 and 3 are the rims.
  const std::uint32_t rows = 4, cols = 10;
  const MeshTopology t = analyzeTriangleMesh(grid(rows, cols, false, true));
  EXPECT_TRUE(t.isManifold());
  EXPECT_TRUE(t.isConsistentlyOriented());
  EXPECT_EQ(t.boundary_edges, 2u * cols);
  EXPECT_EQ(t.eulerCharacteristic(), 0);
  EXPECT_EQ(t.components, 1u);
  ASSERT_EQ(t.boundary_loops.size(), 2u);
  // Triangle (a, b, c) of quad (i, j) runs along row i from column j to j + 1, and
  // triangle (a, c, d) along row i + 1 backwards.
  std::vector<std::uint32_t> first_row, last_row;
  for (std::uint32_t j = 0; j < cols; ++j) {
    first_row.push_back(j);
    last_row.push_back((rows - 1) * cols + (cols - 1 - j));
  }
  const auto& loops = t.boundary_loops;
  const bool order = loops[0].front() < cols;
  EXPECT_TRUE(sameCycle(loops[order ? 0 : 1], first_row));
  EXPECT_TRUE(sameCycle(loops[order ? 1 : 0], last_row));
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, BowtieVertex)
{
  const MeshTopology t = analyzeTriangleMesh({{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(t.vertices, 5u);
  EXPECT_EQ(t.edges, 6u);
  EXPECT_EQ(t.non_manifold_vertices, 1u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_EQ(t.components, 2u);
  EXPECT_FALSE(t.isManifold());
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_EQ(t.genus(), -1);
}

TEST(MeshTopology, ClosedSurfacesPinchedAtAVertex)
{
  // Two octahedra sharing the vertex +x: no boundary, but the vertex has two fans.
  Triangles mesh = octahedron();
  Triangles second = octahedron(6);
  for (TriangleIndices& tri : second)
    for (std::uint32_t& v : tri)
      if (v == 6)
        v = 0;
  mesh.insert(mesh.end(), second.begin(), second.end());
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.boundary_edges, 0u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_EQ(t.non_manifold_vertices, 1u);
  EXPECT_EQ(t.components, 2u);
  EXPECT_FALSE(t.isClosed());
}

TEST(MeshTopology, VertexOnTwoBoundaryArcs)
{
  // A strip of four triangles bent round so that its two ends meet at vertex 0 only:
  // edge-connected, but the boundary passes through 0 twice.
  const Triangles strip = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}, {4, 5, 0}};
  const MeshTopology t = analyzeTriangleMesh(strip);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_EQ(t.non_manifold_vertices, 1u);
  EXPECT_FALSE(t.isManifold());
  EXPECT_TRUE(t.boundary_loops.empty());
}

TEST(MeshTopology, EdgeWithThreeTriangles)
{
  const MeshTopology t = analyzeTriangleMesh({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  EXPECT_EQ(t.vertices, 5u);
  EXPECT_EQ(t.edges, 7u);
  EXPECT_EQ(t.non_manifold_edges, 1u);
  EXPECT_EQ(t.boundary_edges, 6u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_FALSE(t.isManifold());
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_EQ(t.genus(), -1);
}

TEST(MeshTopology, FlippedTriangleInClosedMesh)
{
  Triangles mesh = octahedron();
  std::swap(mesh[3][1], mesh[3][2]);
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_TRUE(t.isManifold());
  EXPECT_TRUE(t.isClosed());
  EXPECT_EQ(t.inconsistently_oriented_edges, 3u);
  EXPECT_FALSE(t.isConsistentlyOriented());
  EXPECT_EQ(t.genus(), -1);
}

TEST(MeshTopology, MoebiusStripIsNotOrientable)
{
  // A strip of 2 x 6 vertices whose last column is glued to the first one upside down.
  const std::uint32_t cols = 6;
  Triangles strip;
  for (std::uint32_t j = 0; j < cols; ++j) {
    std::uint32_t a = j, d = cols + j;
    std::uint32_t b = j + 1, c = cols + j + 1;
    if (j + 1 == cols) {
      b = cols; // bottom of column 0
      c = 0;    // top of column 0
    }
    strip.push_back({a, b, c});
    strip.push_back({a, c, d});
  }
  const MeshTopology t = analyzeTriangleMesh(strip);
  EXPECT_TRUE(t.isManifold());
  EXPECT_GT(t.inconsistently_oriented_edges, 0u);
  EXPECT_EQ(t.eulerCharacteristic(), 0);
  // The boundary of a Moebius strip is one circle through all its vertices.
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_EQ(t.boundary_loops[0].size(), 2u * cols);
  EXPECT_EQ(t.genus(), -1);
}

TEST(MeshTopology, DuplicateAndDegenerateTriangles)
{
  Triangles mesh = tetrahedron();
  mesh.push_back({mesh[1][2], mesh[1][0], mesh[1][1]}); // same vertex set, rotated
  MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.triangles, 5u);
  EXPECT_EQ(t.duplicate_triangles, 1u);
  EXPECT_EQ(t.degenerate_triangles, 0u);
  EXPECT_EQ(t.edges, 6u);
  EXPECT_EQ(t.non_manifold_edges, 3u); // the repeated triangle's edges have three
  EXPECT_FALSE(t.isManifold());
  EXPECT_EQ(t.genus(), -1);

  mesh = tetrahedron();
  mesh.push_back({0, 0, 1});
  mesh.push_back({2, 3, 2});
  t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.triangles, 6u);
  EXPECT_EQ(t.degenerate_triangles, 2u);
  EXPECT_EQ(t.duplicate_triangles, 0u);
  EXPECT_EQ(t.vertices, 4u);
  EXPECT_EQ(t.edges, 6u);
  EXPECT_EQ(t.non_manifold_edges, 0u);
  EXPECT_FALSE(t.isManifold());
  EXPECT_EQ(t.genus(), -1);

  // A triangle and its reverse: the same vertex set, edges in opposite directions.
  t = analyzeTriangleMesh({{0, 1, 2}, {0, 2, 1}});
  EXPECT_EQ(t.duplicate_triangles, 1u);
  EXPECT_EQ(t.boundary_edges, 0u);
  EXPECT_EQ(t.inconsistently_oriented_edges, 0u);
}

TEST(MeshTopology, TwoDisjointTetrahedra)
{
  Triangles mesh = tetrahedron();
  const Triangles second = tetrahedron(10);
  mesh.insert(mesh.end(), second.begin(), second.end());
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.vertices, 8u);
  EXPECT_EQ(t.components, 2u);
  EXPECT_TRUE(t.isClosed());
  EXPECT_EQ(t.eulerCharacteristic(), 4);
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, SparseAndHugeIndices)
{
  // Indices far apart in the whole 32-bit range; unreferenced ones do not count.
  const std::uint32_t big = 4000000000u;
  const Triangles mesh = {{5, big, 17}, {17, big, big + 7}};
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.vertices, 4u);
  EXPECT_EQ(t.edges, 5u);
  EXPECT_EQ(t.boundary_edges, 4u);
  EXPECT_TRUE(t.isManifold());
  EXPECT_TRUE(t.isConsistentlyOriented());
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_TRUE(sameCycle(t.boundary_loops[0], {5, big, big + 7, 17}));
  EXPECT_EQ(t.genus(), 0);
}

TEST(MeshTopology, GenusIsInvariantUnderTriangleOrder)
{
  Triangles mesh = grid(20, 30, true, true);
  std::reverse(mesh.begin(), mesh.end());
  std::rotate(mesh.begin(), mesh.begin() + 77, mesh.end());
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_TRUE(t.isClosed());
  EXPECT_EQ(t.genus(), 1);
}

// Speed is measured by the benchmarks; this checks that large inputs come out right.
TEST(MeshTopology, TwoMillionTriangleTorus)
{
  const Triangles mesh = grid(1000, 1000, true, true);
  ASSERT_EQ(mesh.size(), 2000000u);
  const MeshTopology t = analyzeTriangleMesh(mesh);
  EXPECT_EQ(t.genus(), 1);
  EXPECT_EQ(t.edges, 3000000u);
}

// --- mesh_checks ---------------------------------------------------------------------

TEST(MeshChecks, CrossingTrianglesIntersectOnce)
{
  const Points points = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0},
                         {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, 0.2, 0}};
  EXPECT_EQ(pcl::cocone::countSelfIntersections(points, {{0, 1, 2}, {3, 4, 5}}), 1u);
  // Far apart: none.
  const Points apart = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                        {0, 0, 5}, {1, 0, 5}, {0, 1, 6}};
  EXPECT_EQ(pcl::cocone::countSelfIntersections(apart, {{0, 1, 2}, {3, 4, 5}}), 0u);
}

// The answer is the exact one at any scale, where double arithmetic underflows or
// overflows too; a triangle with a non-finite corner is skipped.
TEST(MeshChecks, CrossingsAtExtremeScalesAndNonFiniteCorners)
{
  const Points crossing = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0},
                           {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, 0.2, 0}};
  const Points apart = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                        {0, 0, 5}, {1, 0, 5}, {0, 1, 6}};
  for (const double scale : {1e-160, 1e-100, 1.0, 1e100, 1e150}) {
    Points c = crossing, a = apart;
    for (Eigen::Vector3d& p : c)
      p *= scale;
    for (Eigen::Vector3d& p : a)
      p *= scale;
    EXPECT_EQ(pcl::cocone::countSelfIntersections(c, {{0, 1, 2}, {3, 4, 5}}), 1u)
        << scale;
    EXPECT_EQ(pcl::cocone::countSelfIntersections(a, {{0, 1, 2}, {3, 4, 5}}), 0u)
        << scale;
  }
  Points with_nan = crossing;
  with_nan.emplace_back(std::nan(""), 0, 0);
  EXPECT_EQ(
      pcl::cocone::countSelfIntersections(with_nan, {{0, 1, 2}, {3, 4, 5}, {0, 1, 6}}),
      1u);
  EXPECT_FALSE(pcl::cocone::trianglesIntersect(with_nan, {0, 1, 6}, {3, 4, 5}));
}

TEST(MeshChecks, ClosedMeshesDoNotSelfIntersect)
{
  EXPECT_EQ(pcl::cocone::countSelfIntersections(tetrahedronPoints(), tetrahedron()),
            0u);
  EXPECT_EQ(pcl::cocone::countSelfIntersections(octahedronPoints(), octahedron()), 0u);
  Points torus = torusPoints(24, 12);
  const Triangles triangles = grid(24, 12, true, true);
  EXPECT_EQ(pcl::cocone::countSelfIntersections(torus, triangles), 0u);
  // Push one vertex of the outer equator through the tube to the far side.
  torus[0] = Eigen::Vector3d(0.5, 0, 0);
  EXPECT_GT(pcl::cocone::countSelfIntersections(torus, triangles), 0u);
}

/** Every pair of \a triangles, each tested alone: what findSelfIntersections must
 * find with its grid or its segment tree. */
std::vector<std::pair<std::size_t, std::size_t>>
everyIntersectingPair(const Points& points, const Triangles& triangles)
{
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < triangles.size(); ++a)
    for (std::size_t b = a + 1; b < triangles.size(); ++b)
      if (pcl::cocone::trianglesIntersect(points, triangles[a], triangles[b]))
        pairs.emplace_back(a, b);
  return pairs;
}

// The box search finds exactly the pairs that testing every pair finds: on a folded
// torus (the grid of cells), on a lattice whose triangles touch along cell walls, and
// with huge triangles through a fine mesh (beyond the grid's budget: the segment tree).
TEST(MeshChecks, SelfIntersectionsAreThoseOfEveryPair)
{
  std::mt19937 random(11);
  const Triangles torus_triangles = grid(40, 20, true, true);
  for (const double noise : {0.0, 0.01, 0.03, 0.1}) {
    std::normal_distribution<double> jitter(0, noise);
    Points torus = torusPoints(40, 20);
    for (Eigen::Vector3d& p : torus)
      p += Eigen::Vector3d(jitter(random), jitter(random), jitter(random));
    const auto expected = everyIntersectingPair(torus, torus_triangles);
    for (const unsigned threads : {0u, 1u, 2u})
      EXPECT_EQ(pcl::cocone::findSelfIntersections(torus, torus_triangles, threads),
                expected)
          << "noise " << noise << ", threads " << threads;
    if (noise >= 0.1)
      EXPECT_FALSE(expected.empty()) << "noise " << noise;
  }

  // A torus of 6400 triangles spans more grid cells than one chunk of the parallel
  // loop (256 cells): on two threads the cells are split, and the pairs are still
  // exactly those of every pair tested alone.
  {
    std::normal_distribution<double> jitter(0, 0.02);
    Points torus = torusPoints(80, 40);
    for (Eigen::Vector3d& p : torus)
      p += Eigen::Vector3d(jitter(random), jitter(random), jitter(random));
    const Triangles triangles = grid(80, 40, true, true);
    const auto expected = everyIntersectingPair(torus, triangles);
    EXPECT_FALSE(expected.empty());
    for (const unsigned threads : {1u, 2u})
      EXPECT_EQ(pcl::cocone::findSelfIntersections(torus, triangles, threads), expected)
          << "threads " << threads;
  }

  // A mesh of 320k triangles, whose grid cells are tested in many chunks: the same
  // pairs on one thread and on two, each pair once.
  std::normal_distribution<double> fine_jitter(0, 0.002);
  Points fine_torus = torusPoints(400, 400);
  for (Eigen::Vector3d& p : fine_torus)
    p += Eigen::Vector3d(fine_jitter(random), fine_jitter(random), fine_jitter(random));
  const Triangles fine_triangles = grid(400, 400, true, true);
  const auto on_one = pcl::cocone::findSelfIntersections(fine_torus, fine_triangles, 1);
  EXPECT_GT(on_one.size(), 100u);
  EXPECT_EQ(pcl::cocone::findSelfIntersections(fine_torus, fine_triangles, 2), on_one);
  EXPECT_EQ(std::adjacent_find(on_one.begin(), on_one.end()), on_one.end());
  for (std::size_t k = 0; k < on_one.size(); k += 37) // a sample of them, each alone
    EXPECT_TRUE(pcl::cocone::trianglesIntersect(
        fine_torus, fine_triangles[on_one[k].first], fine_triangles[on_one[k].second]));

  // Integer coordinates: boxes meet exactly on the cells' walls; every third quad is
  // repeated with its diagonal flipped, which overlaps it in its plane.
  Points lattice;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      lattice.emplace_back(i, j, (i * j) % 3 == 0 ? 0 : 1);
  Triangles folded = grid(12, 12, false, false);
  for (std::uint32_t q = 0; q + 2 < 11 * 11; q += 3) {
    const std::uint32_t i = q / 11, j = q % 11;
    const std::uint32_t a = i * 12 + j, b = a + 1, c = a + 13, d = a + 12;
    folded.push_back({a, b, d});
    folded.push_back({b, c, d});
  }
  const auto lattice_expected = everyIntersectingPair(lattice, folded);
  EXPECT_FALSE(lattice_expected.empty());
  EXPECT_EQ(pcl::cocone::findSelfIntersections(lattice, folded), lattice_expected);

  // Three huge triangles through the torus's tube. The grid's cells are about 0.3
  // wide, so each of them covers more than 60 x 60 x 3 cells, over the budget of 8 per
  // triangle: the segment tree answers.
  Points with_huge = torusPoints(40, 20);
  Triangles huge_triangles = torus_triangles;
  for (int k = 0; k < 3; ++k) {
    const auto first = static_cast<std::uint32_t>(with_huge.size());
    with_huge.emplace_back(-10, -10 + k, -0.5);
    with_huge.emplace_back(10, -10, 0.5);
    with_huge.emplace_back(0, 10, 0.1 * k);
    huge_triangles.push_back({first, first + 1, first + 2});
  }
  const auto huge_expected = everyIntersectingPair(with_huge, huge_triangles);
  EXPECT_FALSE(huge_expected.empty());
  EXPECT_EQ(pcl::cocone::findSelfIntersections(with_huge, huge_triangles),
            huge_expected);
}

TEST(MeshChecks, SharedVertexAndSharedEdgeCases)
{
  // Triangles 0: (0, 1, 2) in z = 0; the others share vertex 0 or edge 0-1 with it.
  const Points p = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0}, // 0 1 2
                    {-1, -1, 1},    {-1, 0, 1},               // 3 4: apart
                    {0.6, 0.6, -1}, {0.6, 0.6, 1},            // 5 6: pierce
                    {1, 0.5, 0},    {0.5, 1, 0},              // 7 8: coplanar inside
                    {1, -1, 0},     {1, 1, 0},                // 9 10: coplanar
                    {1, 0, 1}};                               // 11: above the edge
  const Triangles base = {{0, 1, 2}};
  auto count = [&](const TriangleIndices& other) {
    Triangles soup = base;
    soup.push_back(other);
    return pcl::cocone::countSelfIntersections(p, soup);
  };
  EXPECT_EQ(count({0, 3, 4}), 0u);  // vertex shared, nothing else
  EXPECT_EQ(count({0, 5, 6}), 1u);  // vertex shared, the far edge pierces triangle 0
  EXPECT_EQ(count({0, 7, 8}), 1u);  // vertex shared, coplanar and inside
  EXPECT_EQ(count({0, 1, 9}), 0u);  // edge shared, coplanar, other side
  EXPECT_EQ(count({0, 1, 10}), 1u); // edge shared, coplanar, same side: folded over
  EXPECT_EQ(count({1, 0, 11}), 0u); // edge shared, at an angle
  EXPECT_EQ(count({2, 1, 0}), 1u);  // the same triangle again
}

TEST(MeshChecks, SegmentAgainstTriangle)
{
  // Triangle (0, 1, 2) in z = 0, and segment ends around it.
  const Points p = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0}, // 0 1 2
                    {0.5, 0.5, -1}, {0.5, 0.5, 1},            // 3 4: through it
                    {3, 3, -1},     {3, 3, 1},                // 5 6: beside it
                    {1, 1, 1},                                // 7: above
                    {1, 0.5, 0},    {-1, -1, 0},              // 8 9: in its plane
                    {1, 0, 0},      {3, 0, 0},                // 10 11: on line 0-1
                    {0.5, 0.5, 0},  {1, 1, 0}}; // 12: inside; 13: on edge 1-2
  const auto crosses = [&](std::uint32_t a, std::uint32_t b) {
    return pcl::cocone::segmentCrossesTriangle(p, a, b, {0, 1, 2});
  };
  EXPECT_TRUE(crosses(3, 4));  // pierces the interior
  EXPECT_FALSE(crosses(5, 6)); // passes beside it
  EXPECT_FALSE(crosses(0, 7)); // leaves a shared vertex, off the plane
  EXPECT_TRUE(crosses(0, 8));  // leaves a shared vertex into the triangle
  EXPECT_FALSE(crosses(9, 0)); // reaches a shared vertex from outside, in the plane
  EXPECT_TRUE(crosses(0, 10)); // runs along an edge, shared vertex 0 only
  EXPECT_FALSE(
      crosses(11, 1)); // on the line of edge 0-1, beyond vertex 1: meets it there
  EXPECT_FALSE(crosses(1, 0)); // an edge of the triangle itself
  EXPECT_TRUE(crosses(7, 12)); // touches the interior at its end
  EXPECT_TRUE(crosses(0, 13)); // ends on the far edge
  EXPECT_FALSE(pcl::cocone::segmentCrossesTriangle(p, 3, 4, {0, 10, 1})); // no area
  EXPECT_THROW(pcl::cocone::segmentCrossesTriangle(p, 0, 99, {0, 1, 2}),
               std::out_of_range);
}

// trianglesIntersect decides most pairs in double arithmetic before the exact
// predicates; countSelfIntersections always asks the exact ones (16000 pairs). They
// must agree, also where a corner lies on the other triangle's plane up to rounding or
// is shared, and far from the origin (geographic coordinates) where the differences
// carry the rounding.
TEST(MeshChecks, PairTestAgreesWithTheExactCount)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto vector = [&] {
    return Eigen::Vector3d(unit(random), unit(random), unit(random));
  };
  std::size_t meeting = 0, pairs = 0;
  for (const Eigen::Vector3d offset :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(5e5, 4e6, 120)})
    for (const double size : {1.0, 1e-3})
      for (int trial = 0; trial < 4000; ++trial) {
        Points p(6);
        for (int k = 0; k < 3; ++k)
          p[k] = offset + size * vector();
        // The other triangle: random, or with a corner put on the first one's plane
        // (exactly there only up to rounding), or sharing a corner or an edge with it.
        for (int k = 3; k < 6; ++k)
          p[k] = offset + size * vector();
        const int kind = trial % 4;
        if (kind == 1) {
          const double u = 0.5 * (1 + unit(random)),
                       v = 0.5 * (1 - u) * (1 + unit(random));
          p[3] = p[0] + u * (p[1] - p[0]) + v * (p[2] - p[0]);
        }
        if (kind == 3 && trial % 8 == 3) // folded onto the first one's plane, or not
          p[5] = p[0] + unit(random) * (p[1] - p[0]) + unit(random) * (p[2] - p[0]);
        const TriangleIndices first = {0, 1, 2};
        const TriangleIndices second = {kind >= 2 ? 0u : 3u, kind == 3 ? 1u : 4u, 5};
        const bool pair = pcl::cocone::trianglesIntersect(p, first, second);
        EXPECT_EQ(pair, pcl::cocone::countSelfIntersections(p, {first, second}) == 1)
            << "offset " << offset.transpose() << ", size " << size << ", trial "
            << trial;
        meeting += pair;
        ++pairs;
      }
  // Both outcomes are well represented.
  EXPECT_GT(meeting, pairs / 10);
  EXPECT_LT(meeting, pairs * 9 / 10);
}

TEST(MeshChecks, NonManifoldSoupsAreAccepted)
{
  // Three fins on one edge, and a bowtie: no intersection beyond shared features.
  const Points p = {{0, 0, 0},   {1, 0, 0},  {0.5, 1, 0}, {0.5, -1, 0.2},
                    {0.5, 0, 1}, {-1, 1, 0}, {-1, -1, 0}};
  EXPECT_EQ(pcl::cocone::countSelfIntersections(p, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}),
            0u);
  EXPECT_EQ(pcl::cocone::countSelfIntersections(p, {{0, 1, 2}, {0, 5, 6}}), 0u);
}

TEST(MeshChecks, SignedVolumeFollowsOrientation)
{
  EXPECT_NEAR(checks::signedVolume(tetrahedronPoints(), tetrahedron()), 1.0 / 6, 1e-12);
  EXPECT_NEAR(checks::signedVolume(octahedronPoints(), octahedron()), 4.0 / 3, 1e-12);
  Triangles flipped = octahedron();
  for (TriangleIndices& t : flipped)
    std::swap(t[0], t[1]);
  EXPECT_NEAR(checks::signedVolume(octahedronPoints(), flipped), -4.0 / 3, 1e-12);
  // Translation does not matter for a closed mesh.
  Points moved = octahedronPoints();
  for (Eigen::Vector3d& q : moved)
    q += Eigen::Vector3d(1e3, -2e3, 5e2);
  EXPECT_NEAR(checks::signedVolume(moved, octahedron()), 4.0 / 3, 1e-9);
}

TEST(MeshChecks, DistancesAndHausdorff)
{
  const Points square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Triangles two = {{0, 1, 2}, {0, 2, 3}};
  Points shifted = square;
  for (Eigen::Vector3d& q : shifted)
    q.z() += 0.1;
  EXPECT_NEAR(checks::hausdorffDistance(square, two, shifted, two), 0.1, 1e-12);
  EXPECT_NEAR(checks::hausdorffDistance(square, two, square, two), 0.0, 1e-12);

  const checks::DistanceStats stats = checks::distancesToMesh(
      {{0.5, 0.5, 0.3}, {0.2, 0.7, -0.1}, {2, 0.5, 0}}, square, two);
  EXPECT_NEAR(stats.max, 1.0, 1e-12);
  EXPECT_NEAR(stats.mean, (0.3 + 0.1 + 1.0) / 3, 1e-12);
  EXPECT_NEAR(stats.rms, std::sqrt((0.09 + 0.01 + 1.0) / 3), 1e-12);
}

TEST(MeshChecks, SamplesLieOnTheMesh)
{
  const Points points = octahedronPoints();
  const Triangles triangles = octahedron();
  const Points samples = checks::samplePointsOnMesh(points, triangles, 50);
  EXPECT_EQ(samples.size(), 6u + 400u);
  EXPECT_LT(checks::distancesToMesh(samples, points, triangles).max, 1e-12);
  // Equal areas: each face gets its share.
  std::size_t upper = 0;
  for (const Eigen::Vector3d& s : samples)
    upper += s.z() > 1e-9;
  EXPECT_NEAR(static_cast<double>(upper), 201.0, 2.0); // 200 + the top vertex
  // Deterministic.
  EXPECT_EQ(samples, checks::samplePointsOnMesh(points, triangles, 50));
}

void
validateBowtie()
{
  const Points p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0.5}};
  checks::expectValidSurface(p, {{0, 1, 2}, {0, 3, 4}}, "bowtie");
}

void
validateCrossing()
{
  const Points p = {{0, 0, 0},      {2, 0, 0},     {0, 2, 0},
                    {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, 0.2, 0}};
  checks::expectValidSurface(p, {{0, 1, 2}, {3, 4, 5}}, "crossing");
}

TEST(MeshChecks, ExpectValidSurface)
{
  const MeshTopology t =
      checks::expectValidSurface(torusPoints(16, 8), grid(16, 8, true, true), "torus");
  EXPECT_EQ(t.genus(), 1);
  EXPECT_NONFATAL_FAILURE(validateBowtie(), "non-manifold vertices");
  EXPECT_NONFATAL_FAILURE(validateCrossing(), "self-intersecting");
}

} // namespace
