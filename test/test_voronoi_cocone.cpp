// SPDX-License-Identifier: GPL-3.0-or-later
// VoronoiCocone, the core shared by the three PCL classes: duplicates, the centred
// frame, large coordinates, poles and heights against closed-form facts, the marked
// triangles and their incidence lists, the documented errors, thread independence.
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <support/decimation.h>
#include <support/shapes.h>

#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <thread>
#include <vector>

namespace {

using pcl::cocone::DecimationLevels;
using pcl::cocone::MarkedTriangle;
using pcl::cocone::SampleIndex;
using pcl::cocone::Status;
using pcl::cocone::VoronoiCocone;
using namespace pcl::cocone::test;
using Points = std::vector<Eigen::Vector3d>;

constexpr double kPi = 3.14159265358979323846;

/** Uniform doubles from std::mt19937 (its output is fixed by the standard). */
class Uniform
{
public:
  explicit Uniform(std::uint32_t seed) : engine_(seed) {}
  double
  operator()(double lo, double hi)
  {
    return lo + (hi - lo) * (engine_() * (1.0 / 4294967296.0));
  }

private:
  std::mt19937 engine_;
};

double
median(std::vector<double> values)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

/** Two doubles are the same value (NaN equals NaN, infinities by sign). */
bool
sameValue(double a, double b)
{
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

bool
sameVector(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return sameValue(a.x(), b.x()) && sameValue(a.y(), b.y()) && sameValue(a.z(), b.z());
}

/** Relative difference, 0 for equal values (infinities included). */
double
relativeDifference(double a, double b)
{
  if (a == b)
    return 0;
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

/** The vertex set of a marked triangle, ascending. */
std::array<SampleIndex, 3>
sortedVertices(const MarkedTriangle& t)
{
  std::array<SampleIndex, 3> v = t.vertex;
  std::sort(v.begin(), v.end());
  return v;
}

// ---------------------------------------------------------------------------------
// Duplicates

// Exact copies collapse into one Delaunay vertex named after the smallest index; every
// copy reads that representative's values.
TEST(VoronoiCocone, DuplicatesMapToTheSmallestIndexAndShareValues)
{
  const SampledShape sphere = sampleSphere(600, 3);
  Points points = sphere.points;
  // Copies after the original, a copy before it (index 0 copies point 100, which
  // becomes index 101 after the insertion), and a triple.
  points.insert(points.begin(), sphere.points[100]);
  points.push_back(sphere.points[5]);
  points.push_back(sphere.points[7]);
  points.push_back(sphere.points[5]);
  const std::size_t n = points.size();

  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
  EXPECT_EQ(voronoi.status(), Status::ok);
  EXPECT_TRUE(voronoi.errorMessage().empty());
  EXPECT_EQ(voronoi.size(), n);
  EXPECT_EQ(voronoi.numUniqueSamples(), sphere.points.size());

  // Expected representative: the first index with the same coordinates (brute force).
  std::size_t duplicates = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t first = i;
    for (std::size_t j = 0; j < i; ++j)
      if (points[j] == points[i]) {
        first = j;
        break;
      }
    duplicates += first != i;
    const SampleIndex r = voronoi.representative(static_cast<SampleIndex>(i));
    ASSERT_EQ(r, first) << "sample " << i;
    const SampleIndex s = static_cast<SampleIndex>(i);
    EXPECT_TRUE(sameVector(voronoi.poleVector(s), voronoi.poleVector(r)));
    EXPECT_EQ(voronoi.positivePoleAtInfinity(s), voronoi.positivePoleAtInfinity(r));
    EXPECT_TRUE(sameVector(voronoi.positivePole(s), voronoi.positivePole(r)));
    EXPECT_TRUE(sameVector(voronoi.negativePole(s), voronoi.negativePole(r)));
    EXPECT_TRUE(sameValue(voronoi.height(s), voronoi.height(r)));
    EXPECT_TRUE(sameValue(voronoi.coconeRadius(s), voronoi.coconeRadius(r)));
    EXPECT_TRUE(sameValue(voronoi.ratio(s), voronoi.ratio(r)));
    const auto mine = voronoi.trianglesAround(s);
    const auto theirs = voronoi.trianglesAround(r);
    EXPECT_TRUE(std::equal(mine.begin(), mine.end(), theirs.begin(), theirs.end()));
  }
  EXPECT_EQ(duplicates, 4u);
  EXPECT_EQ(voronoi.size() - voronoi.numUniqueSamples(), duplicates);
  EXPECT_EQ(voronoi.representative(0), 0u);
  EXPECT_EQ(voronoi.representative(101), 0u);
  EXPECT_EQ(voronoi.representative(static_cast<SampleIndex>(n - 1)), 6u); // point 5

  // Duplicates appear in no marked triangle and in no neighbour list.
  for (const MarkedTriangle& t : voronoi.markedTriangles())
    for (const SampleIndex v : t.vertex)
      EXPECT_EQ(voronoi.representative(v), v);
  std::vector<SampleIndex> neighbours;
  voronoi.coconeNeighbours(static_cast<SampleIndex>(n - 1), neighbours);
  std::vector<SampleIndex> of_representative;
  voronoi.coconeNeighbours(6, of_representative);
  EXPECT_EQ(neighbours, of_representative);
  EXPECT_FALSE(neighbours.empty());

  // Decimation gives the duplicates level 0.
  std::vector<SampleIndex> representative(n);
  for (std::size_t i = 0; i < n; ++i)
    representative[i] = voronoi.representative(static_cast<SampleIndex>(i));
  DecimationLevels levels;
  std::string message;
  ASSERT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::ok)
      << message;
  ASSERT_EQ(levels.level.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    if (representative[i] != i) {
      EXPECT_EQ(levels.level[i], 0.0) << "duplicate " << i;
    }
  }
}

// ---------------------------------------------------------------------------------
// The centred frame and large coordinates

Points
translated(const Points& points, const Eigen::Vector3d& by)
{
  Points out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points)
    out.push_back(p + by);
  return out;
}

TEST(VoronoiCocone, CenteredPointsPlusOffsetReproduceTheInput)
{
  const SampledShape torus = sampleTorus(1500, 2);
  for (const Eigen::Vector3d& shift :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(5e5, 4e6, 100)}) {
    const Points points = translated(torus.points, shift);
    VoronoiCocone voronoi;
    ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
    const Points& centered = voronoi.centeredPoints();
    ASSERT_EQ(centered.size(), points.size());
    // The offset is the centroid.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points)
      centroid += p;
    centroid /= static_cast<double>(points.size());
    EXPECT_LT((voronoi.offset() - centroid).norm(), 1e-12 * (1 + centroid.norm()));
    double worst = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      // One rounding in p - offset and one in + offset: a few ulps of |p|.
      const double error = (centered[i] + voronoi.offset() - points[i]).norm();
      const double ulp = std::numeric_limits<double>::epsilon() * points[i].norm();
      worst =
          std::max(worst, error / std::max(ulp, std::numeric_limits<double>::min()));
      sum += centered[i];
    }
    // The centred points average to zero up to the rounding of the subtraction.
    const double centroid_of_centered = sum.norm() / static_cast<double>(points.size());
    const double offset_ulp =
        std::numeric_limits<double>::epsilon() * std::max(1.0, voronoi.offset().norm());
    std::cout << "[ measured ] shift " << shift.transpose()
              << ": largest |centered + offset - input| = " << worst
              << " ulps of |input|, |centroid of centered| = " << centroid_of_centered
              << " (" << centroid_of_centered / offset_ulp << " ulps of |offset|)"
              << std::endl;
    EXPECT_LE(worst, 4.0);
    EXPECT_LT(centroid_of_centered, 4 * offset_ulp);
  }
}

// A sphere far from the origin (as UTM coordinates) gives the values it has at the
// origin: the points are centred before anything is computed.
TEST(VoronoiCocone, LargeCoordinatesGiveTheSameGeometry)
{
  const SampledShape sphere = sampleSphere(2000, 4);
  const Points far_away = translated(sphere.points, Eigen::Vector3d(5e5, 4e6, 100));
  VoronoiCocone near, far;
  ASSERT_EQ(near.compute(sphere.points), Status::ok) << near.errorMessage();
  ASSERT_EQ(far.compute(far_away), Status::ok) << far.errorMessage();
  ASSERT_EQ(far.numUniqueSamples(), near.numUniqueSamples());
  double worst_angle = 0, worst_height = 0, worst_radius = 0;
  std::size_t infinity_mismatch = 0;
  for (SampleIndex i = 0; i < sphere.points.size(); ++i) {
    const double cosine =
        std::min(1.0, std::max(-1.0, near.poleVector(i).dot(far.poleVector(i))));
    worst_angle = std::max(worst_angle, std::acos(cosine) * 180 / kPi);
    worst_height =
        std::max(worst_height, relativeDifference(near.height(i), far.height(i)));
    worst_radius = std::max(
        worst_radius, relativeDifference(near.coconeRadius(i), far.coconeRadius(i)));
    infinity_mismatch +=
        near.positivePoleAtInfinity(i) != far.positivePoleAtInfinity(i);
  }
  std::cout
      << "[ measured ] sphere at (5e5, 4e6, 100) vs origin: largest pole-vector angle "
      << worst_angle << " deg, largest relative height difference " << worst_height
      << ", largest relative radius difference " << worst_radius << std::endl;
  EXPECT_LT(worst_angle, 0.5);
  EXPECT_LT(worst_height, 1e-6);
  EXPECT_LT(worst_radius, 1e-6);
  EXPECT_EQ(infinity_mismatch, 0u);
}

// ---------------------------------------------------------------------------------
// Poles and heights

/** Hull vertices of points in general position, by brute force: a point is a hull
 * vertex exactly when it belongs to a triangle with every other point on one side. */
std::vector<bool>
bruteForceHullVertices(const Points& points)
{
  const std::size_t n = points.size();
  std::vector<bool> on_hull(n, false);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      for (std::size_t c = b + 1; c < n; ++c) {
        if (on_hull[a] && on_hull[b] && on_hull[c])
          continue;
        const Eigen::Vector3d normal =
            (points[b] - points[a]).cross(points[c] - points[a]);
        bool above = false, below = false;
        for (std::size_t d = 0; d < n && !(above && below); ++d) {
          if (d == a || d == b || d == c)
            continue;
          const double side = normal.dot(points[d] - points[a]);
          above = above || side > 0;
          below = below || side < 0;
        }
        if (!(above && below))
          on_hull[a] = on_hull[b] = on_hull[c] = true;
      }
  return on_hull;
}

TEST(VoronoiCocone, PositivePoleAtInfinityExactlyOnTheConvexHull)
{
  // Random points in a ball: general position, a few dozen on the hull.
  Uniform uniform(11);
  Points points;
  while (points.size() < 160) {
    const Eigen::Vector3d p(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    if (p.norm() <= 1)
      points.push_back(p);
  }
  const std::vector<bool> on_hull = bruteForceHullVertices(points);
  // Points filling a ball are no surface: the noise estimate measures nothing and
  // leaves them as given (kMaxPatchThickness).
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
  std::size_t hull = 0, mismatches = 0;
  for (SampleIndex i = 0; i < points.size(); ++i) {
    hull += on_hull[i];
    mismatches += voronoi.positivePoleAtInfinity(i) != on_hull[i];
    EXPECT_NEAR(voronoi.poleVector(i).norm(), 1.0, 1e-12) << "sample " << i;
    if (voronoi.positivePoleAtInfinity(i)) {
      EXPECT_TRUE(std::isinf(voronoi.positivePole(i).x()));
      // The pole vector of a hull sample points out of the hull: away from the centroid
      // of the others (the ball is convex, so this holds for the average hull normal).
      EXPECT_GT(voronoi.poleVector(i).dot(points[i]), 0) << "sample " << i;
    }
    else {
      EXPECT_TRUE(voronoi.positivePole(i).allFinite());
      const Eigen::Vector3d to_pole = voronoi.positivePole(i) - points[i];
      EXPECT_LT((to_pole.normalized() - voronoi.poleVector(i)).norm(), 1e-9);
    }
  }
  std::cout << "[ measured ] " << hull << " of " << points.size()
            << " random points are hull vertices; " << mismatches << " mismatches"
            << std::endl;
  EXPECT_GT(hull, 10u);
  EXPECT_EQ(mismatches, 0u);
}

// On a sphere and a torus the height (distance to the negative pole) estimates the
// local feature size, known in closed form; pole vectors are unit and normal.
TEST(VoronoiCocone, HeightsEqualTheLocalFeatureSize)
{
  for (const SampledShape& shape : {sampleSphere(3000, 5), sampleTorus(4000, 5)}) {
    VoronoiCocone voronoi;
    ASSERT_EQ(voronoi.compute(shape.points), Status::ok) << voronoi.errorMessage();
    std::vector<double> errors, normal_angles;
    std::size_t undefined = 0;
    double worst_norm = 0;
    for (SampleIndex i = 0; i < shape.points.size(); ++i) {
      const double lfs = shape.local_feature_size(shape.points[i]);
      const double h = voronoi.height(i);
      if (!(h > 0)) {
        ++undefined;
        continue;
      }
      EXPECT_NEAR((voronoi.negativePole(i) - shape.points[i]).norm(), h, 1e-9 * h);
      errors.push_back(std::abs(h - lfs) / lfs);
      worst_norm = std::max(worst_norm, std::abs(voronoi.poleVector(i).norm() - 1));
      normal_angles.push_back(
          std::acos(
              std::min(1.0, std::abs(voronoi.poleVector(i).dot(shape.normals[i])))) *
          180 / kPi);
    }
    const double median_error = median(errors);
    std::cout << "[ measured ] " << shape.name
              << ": median |h - lfs| / lfs = " << 100 * median_error << "%, largest "
              << 100 * *std::max_element(errors.begin(), errors.end()) << "%, "
              << undefined
              << " samples without a negative pole; median pole-vector/normal angle "
              << median(normal_angles) << " deg; largest | |v| - 1 | = " << worst_norm
              << std::endl;
    EXPECT_LT(median_error, 0.01) << shape.name;
    EXPECT_EQ(undefined, 0u) << shape.name;
    EXPECT_LT(worst_norm, 1e-12) << shape.name;
    EXPECT_LT(median(normal_angles), 5.0) << shape.name;
  }
}

// ---------------------------------------------------------------------------------
// Marked triangles and incidence

TEST(VoronoiCocone, MarkedTrianglesAndIncidenceListsAgree)
{
  const SampledShape torus = sampleTorus(2000, 6);
  Points points = torus.points;
  points.push_back(torus.points[10]); // a duplicate reads its representative's lists
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
  const std::vector<MarkedTriangle>& triangles = voronoi.markedTriangles();
  ASSERT_FALSE(triangles.empty());
  const std::size_t n = points.size();

  std::vector<std::vector<std::uint32_t>> containing(n);
  std::vector<std::set<SampleIndex>> marked_neighbours(n);
  std::set<std::array<SampleIndex, 3>> distinct;
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const MarkedTriangle& triangle = triangles[t];
    EXPECT_NE(triangle.marked_by, 0) << "triangle " << t;
    EXPECT_LT(triangle.marked_by, 8) << "triangle " << t;
    const auto& v = triangle.vertex;
    EXPECT_TRUE(v[0] != v[1] && v[1] != v[2] && v[0] != v[2]) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      ASSERT_LT(v[k], n);
      EXPECT_EQ(voronoi.representative(v[k]), v[k]) << "triangle " << t;
      containing[v[k]].push_back(t);
      if (triangle.isMarkedBy(k))
        for (int other = 0; other < 3; ++other)
          if (other != k)
            marked_neighbours[v[k]].insert(v[other]);
    }
    EXPECT_TRUE(distinct.insert(sortedVertices(triangle)).second)
        << "triangle " << t << " is listed twice";
  }

  std::vector<SampleIndex> neighbours;
  std::size_t total_neighbours = 0;
  for (SampleIndex i = 0; i < n; ++i) {
    const SampleIndex r = voronoi.representative(i);
    std::vector<std::uint32_t> around(voronoi.trianglesAround(i).begin(),
                                      voronoi.trianglesAround(i).end());
    std::sort(around.begin(), around.end());
    EXPECT_EQ(around, containing[r]) << "sample " << i;
    voronoi.coconeNeighbours(i, neighbours);
    EXPECT_TRUE(std::is_sorted(neighbours.begin(), neighbours.end()));
    EXPECT_EQ(std::vector<SampleIndex>(marked_neighbours[r].begin(),
                                       marked_neighbours[r].end()),
              neighbours)
        << "sample " << i;
    total_neighbours += neighbours.size();
  }
  std::cout << "[ measured ] torus 2000: " << triangles.size()
            << " marked triangles, mean cocone neighbours "
            << static_cast<double>(total_neighbours) / static_cast<double>(n)
            << std::endl;
}

// The neighbour lists against the edges of every Delaunay triangle: sorted, each
// neighbour once, a duplicate answering with its representative's list. The lookups
// keep per-thread marks across calls and across diagrams, so they are repeated on a
// second, smaller diagram, then again on the first, and from two threads at once.
TEST(VoronoiCocone, DelaunayNeighboursAreTheEdgesOfTheTriangulation)
{
  const auto expectedLists = [](const VoronoiCocone& voronoi) {
    std::vector<SampleIndex> all(voronoi.size());
    std::iota(all.begin(), all.end(), 0u);
    std::vector<std::array<SampleIndex, 3>> triangles;
    voronoi.delaunayTrianglesAmong(all, triangles);
    std::vector<std::set<SampleIndex>> edges(voronoi.size());
    for (const auto& t : triangles)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (a != b)
            edges[t[a]].insert(t[b]);
    std::vector<std::vector<SampleIndex>> lists(voronoi.size());
    for (SampleIndex i = 0; i < voronoi.size(); ++i) {
      const std::set<SampleIndex>& of = edges[voronoi.representative(i)];
      lists[i].assign(of.begin(), of.end());
    }
    return lists;
  };
  const auto lookedUp = [](const VoronoiCocone& voronoi, SampleIndex first,
                           SampleIndex step) {
    std::vector<std::vector<SampleIndex>> lists(voronoi.size());
    for (SampleIndex i = first; i < voronoi.size(); i += step)
      voronoi.delaunayNeighbours(i, lists[i]);
    return lists;
  };

  Points torus = sampleTorus(1500, 3).points;
  torus.push_back(torus[10]); // duplicates read their representative's list
  torus.push_back(torus[700]);
  VoronoiCocone big;
  ASSERT_EQ(big.compute(torus), Status::ok) << big.errorMessage();
  const std::vector<std::vector<SampleIndex>> expected = expectedLists(big);
  EXPECT_EQ(lookedUp(big, 0, 1), expected);
  EXPECT_FALSE(expected[torus.size() - 1].empty());
  EXPECT_EQ(expected[torus.size() - 1], expected[700]);

  VoronoiCocone small;
  ASSERT_EQ(small.compute(sampleSphere(200, 4).points), Status::ok)
      << small.errorMessage();
  EXPECT_EQ(lookedUp(small, 0, 1), expectedLists(small));
  EXPECT_EQ(lookedUp(big, 0, 1), expected);

  std::vector<std::vector<SampleIndex>> even, odd;
  std::thread other([&] { odd = lookedUp(big, 1, 2); });
  even = lookedUp(big, 0, 2);
  other.join();
  for (SampleIndex i = 0; i < big.size(); ++i)
    EXPECT_EQ(i % 2 ? odd[i] : even[i], expected[i]) << "sample " << i;
}

// The core answers its Delaunay queries from flat arrays it keeps after the geometry,
// once CGAL's triangulation is freed: they must give what a triangulation of the same
// points built here gives, convex hull and duplicates included, and nothing once
// decimate() has consumed them.
TEST(VoronoiCocone, DelaunayQueriesAgreeWithAnIndependentTriangulation)
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vertex = CGAL::Triangulation_vertex_base_with_info_3<SampleIndex, Kernel>;
  using Triangulation =
      CGAL::Delaunay_triangulation_3<Kernel,
                                     CGAL::Triangulation_data_structure_3<Vertex>>;

  Points points = sampleTorus(2000, 5).points;
  const Points cap = sampleHemisphere(300, 6).points; // a second part, its own hull
  for (const Eigen::Vector3d& p : cap)
    points.push_back(p * 0.3 + Eigen::Vector3d(3, 0, 0));
  points.push_back(points[17]);
  points.push_back(points[2100]);
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();

  // The same points as CGAL sees them, named by the smallest index of each group.
  std::map<std::array<double, 3>, SampleIndex> first_of;
  std::vector<std::pair<Kernel::Point_3, SampleIndex>> input;
  for (SampleIndex i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = voronoi.centeredPoints()[i];
    if (first_of.emplace(std::array<double, 3>{c.x(), c.y(), c.z()}, i).second)
      input.emplace_back(Kernel::Point_3(c.x(), c.y(), c.z()), i);
  }
  const Triangulation reference(input.begin(), input.end());
  ASSERT_EQ(reference.number_of_vertices(), voronoi.numUniqueSamples());

  std::vector<std::vector<SampleIndex>> expected_neighbours(points.size());
  for (auto v = reference.finite_vertices_begin(); v != reference.finite_vertices_end();
       ++v) {
    std::vector<Triangulation::Vertex_handle> adjacent;
    reference.finite_adjacent_vertices(v, std::back_inserter(adjacent));
    std::vector<SampleIndex>& list = expected_neighbours[v->info()];
    for (const auto& w : adjacent)
      list.push_back(w->info());
    std::sort(list.begin(), list.end());
  }
  std::vector<SampleIndex> neighbours;
  for (SampleIndex i = 0; i < points.size(); ++i) {
    voronoi.delaunayNeighbours(i, neighbours);
    EXPECT_EQ(neighbours, expected_neighbours[voronoi.representative(i)])
        << "sample " << i;
  }

  std::vector<std::array<SampleIndex, 3>> expected_triangles;
  for (auto f = reference.finite_facets_begin(); f != reference.finite_facets_end();
       ++f) {
    std::array<SampleIndex, 3> t;
    for (int k = 0, m = 0; k < 4; ++k)
      if (k != f->second)
        t[m++] = f->first->vertex(k)->info();
    std::sort(t.begin(), t.end());
    expected_triangles.push_back(t);
  }
  std::sort(expected_triangles.begin(), expected_triangles.end());
  std::vector<SampleIndex> all(points.size());
  std::iota(all.begin(), all.end(), 0u);
  std::vector<std::array<SampleIndex, 3>> triangles;
  voronoi.delaunayTrianglesAmong(all, triangles);
  EXPECT_EQ(triangles, expected_triangles);
  std::cout << "[ measured ] " << voronoi.numUniqueSamples() << " distinct samples, "
            << triangles.size() << " Delaunay triangles, "
            << reference.number_of_finite_cells() << " finite cells" << std::endl;

  DecimationLevels levels;
  std::string message;
  ASSERT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::ok)
      << message;
  voronoi.delaunayNeighbours(0, neighbours);
  EXPECT_TRUE(neighbours.empty());
  voronoi.delaunayTrianglesAmong(all, triangles);
  EXPECT_TRUE(triangles.empty());
}

TEST(VoronoiCocone, DelaunayTrianglesAmongASmallSet)
{
  // A tetrahedron and a copy of its first vertex: one cell, four triangles.
  {
    const Points points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
    VoronoiCocone voronoi;
    ASSERT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
    std::vector<std::array<SampleIndex, 3>> triangles;
    voronoi.delaunayTrianglesAmong({0, 1, 2, 3}, triangles);
    const std::vector<std::array<SampleIndex, 3>> all = {
        {0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    EXPECT_EQ(triangles, all);
    voronoi.delaunayTrianglesAmong({3, 1, 2}, triangles);
    EXPECT_EQ(triangles, (std::vector<std::array<SampleIndex, 3>>{{1, 2, 3}}));
    // The duplicate 4 stands for 0.
    voronoi.delaunayTrianglesAmong({4, 2, 1}, triangles);
    EXPECT_EQ(triangles, (std::vector<std::array<SampleIndex, 3>>{{0, 1, 2}}));
    voronoi.delaunayTrianglesAmong({0, 1}, triangles);
    EXPECT_TRUE(triangles.empty());
  }

  // A patch of a sphere: only triangles inside the set, each once, and every marked
  // triangle inside the set among them.
  const SampledShape sphere = sampleSphere(1500, 8);
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(sphere.points), Status::ok) << voronoi.errorMessage();
  std::vector<SampleIndex> patch;
  for (SampleIndex i = 0; i < sphere.points.size(); ++i)
    if (sphere.points[i].z() > 0.9)
      patch.push_back(i);
  ASSERT_GT(patch.size(), 20u);
  std::vector<SampleIndex> shuffled = patch;
  std::reverse(shuffled.begin(), shuffled.end());
  shuffled.push_back(patch.front()); // repeats are harmless
  std::vector<std::array<SampleIndex, 3>> triangles;
  voronoi.delaunayTrianglesAmong(shuffled, triangles);
  std::set<std::array<SampleIndex, 3>> seen;
  std::vector<SampleIndex> neighbours;
  for (const auto& t : triangles) {
    EXPECT_TRUE(t[0] < t[1] && t[1] < t[2]) << "vertices not ascending";
    for (const SampleIndex v : t)
      EXPECT_TRUE(std::binary_search(patch.begin(), patch.end(), v))
          << v << " not in the set";
    EXPECT_TRUE(seen.insert(t).second) << "triangle reported twice";
    // Its edges are Delaunay edges.
    voronoi.delaunayNeighbours(t[0], neighbours);
    EXPECT_TRUE(std::binary_search(neighbours.begin(), neighbours.end(), t[1]));
    EXPECT_TRUE(std::binary_search(neighbours.begin(), neighbours.end(), t[2]));
  }
  std::size_t marked_inside = 0;
  for (const MarkedTriangle& m : voronoi.markedTriangles()) {
    const auto v = sortedVertices(m);
    if (std::all_of(v.begin(), v.end(), [&](SampleIndex s) {
          return std::binary_search(patch.begin(), patch.end(), s);
        })) {
      ++marked_inside;
      EXPECT_TRUE(seen.count(v)) << "a marked triangle of the set is missing";
    }
  }
  std::cout << "[ measured ] sphere patch of " << patch.size()
            << " samples: " << triangles.size() << " Delaunay triangles among them, "
            << marked_inside << " of them marked" << std::endl;
  EXPECT_GT(marked_inside, patch.size());
}

// ---------------------------------------------------------------------------------
// Errors

void
expectFailure(const Points& points, Status expected, const std::string& label)
{
  VoronoiCocone voronoi;
  const Status status = voronoi.compute(points);
  EXPECT_EQ(status, expected) << label << ": got " << pcl::cocone::toString(status);
  EXPECT_EQ(voronoi.status(), expected) << label;
  EXPECT_FALSE(voronoi.errorMessage().empty()) << label;
  EXPECT_TRUE(voronoi.markedTriangles().empty()) << label;
  std::cout << "[ measured ] " << label << ": " << pcl::cocone::toString(status) << ": "
            << voronoi.errorMessage() << std::endl;
  DecimationLevels levels;
  std::string message;
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::not_computed)
      << label;
  EXPECT_FALSE(message.empty()) << label;
}

TEST(VoronoiCocone, DegenerateInputGivesTheDocumentedStatus)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectFailure({}, Status::too_few_points, "no point");
  expectFailure({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Status::too_few_points, "3 points");
  expectFailure({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}},
                Status::degenerate_dimension, "3 distinct points out of 5");
  expectFailure({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, Status::too_few_points,
                "4 identical points");
  expectFailure({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                Status::degenerate_dimension, "4 coplanar points");
  expectFailure({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {-1, -1, -1}},
                Status::degenerate_dimension, "5 collinear points");
  expectFailure({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {nan, 0, 0}},
                Status::non_finite_input, "NaN input");
  expectFailure({{0, 0, 0},
                 {1, 0, 0},
                 {0, 1, 0},
                 {0, 0, std::numeric_limits<double>::infinity()}},
                Status::non_finite_input, "infinite input");
  // Coplanar at large coordinates: the centring rounds, the test must not.
  Points plane;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      plane.emplace_back(5e5 + 0.1 * i, 4e6 + 0.1 * j, 100.0);
  expectFailure(plane, Status::degenerate_dimension,
                "100 coplanar points at UTM coordinates");

  // A failure after a success forgets the success.
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(sampleSphere(100, 1).points), Status::ok);
  EXPECT_EQ(voronoi.compute({{0, 0, 0}, {1, 0, 0}}), Status::too_few_points);
  EXPECT_EQ(voronoi.status(), Status::too_few_points);
  EXPECT_FALSE(voronoi.errorMessage().empty());
}

/** What needs the triangulation refuses to run on what decimate() left of it. */
void
expectConsumed(VoronoiCocone& voronoi)
{
  EXPECT_EQ(voronoi.status(), Status::not_computed);
  std::vector<pcl::cocone::TriangleIndices> triangles;
  pcl::cocone::ReconstructionReport report;
  EXPECT_EQ(pcl::cocone::reconstructSurface(voronoi, {}, triangles, report),
            Status::not_computed);
  EXPECT_TRUE(triangles.empty());
  std::vector<SampleIndex> neighbours;
  voronoi.delaunayNeighbours(0, neighbours);
  EXPECT_TRUE(neighbours.empty());
  DecimationLevels levels;
  std::string message;
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::not_computed);
  EXPECT_FALSE(message.empty());
}

TEST(VoronoiCocone, DecimateNeedsAFreshComputation)
{
  VoronoiCocone voronoi;
  DecimationLevels levels;
  std::string message;
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::not_computed);
  EXPECT_FALSE(message.empty());
  std::cout << "[ measured ] before compute(): " << message << std::endl;

  ASSERT_EQ(voronoi.compute(sampleSphere(1000, 2).points), Status::ok);
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0, levels), Status::invalid_parameter);
  EXPECT_EQ(decimateUpTo(std::move(voronoi), std::numeric_limits<double>::quiet_NaN(),
                         levels),
            Status::invalid_parameter);
  ASSERT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels, nullptr, &message),
            Status::ok)
      << message;
  EXPECT_GT(levels.removals, 0u);
  EXPECT_EQ(levels.level.size(), 1000u);
  EXPECT_TRUE(voronoi.markedTriangles().empty()); // consumed
  expectConsumed(voronoi);
  // A new compute() makes it usable again.
  ASSERT_EQ(voronoi.compute(sampleSphere(1000, 2).points), Status::ok);
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels), Status::ok);
}

// A cancelled decimate() has consumed the triangulation as much as a finished one: what
// needs the diagram must refuse the leftovers, not run on empty candidate lists.
TEST(VoronoiCocone, CancelledDecimationLeavesNoUsableDiagram)
{
  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(sampleSphere(6000, 3).points), Status::ok);
  std::size_t calls = 0;
  DecimationLevels levels;
  std::string message;
  EXPECT_EQ(decimateUpTo(
                std::move(voronoi), 0.3, levels, [&](double) { return ++calls < 2; },
                &message),
            Status::internal_error);
  EXPECT_EQ(calls, 2u); // asked every 1024 removals: cancelled at the second
  EXPECT_EQ(levels.removals, 2048u);
  EXPECT_EQ(message, "cancelled");
  expectConsumed(voronoi);
  // A new compute() makes it usable again.
  ASSERT_EQ(voronoi.compute(sampleSphere(6000, 3).points), Status::ok);
  EXPECT_EQ(decimateUpTo(std::move(voronoi), 0.3, levels), Status::ok);
  EXPECT_GT(levels.removals, 2048u);
}

TEST(VoronoiCocone, OutOfRangeCoconeAngleIsRefused)
{
  VoronoiCocone voronoi;
  EXPECT_DOUBLE_EQ(voronoi.getCoconeAngle(), kPi / 8);
  for (const double bad :
       {0.0, -0.1, kPi / 2, 2.0, std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(voronoi.setCoconeAngle(bad), Status::invalid_parameter) << bad;
    EXPECT_DOUBLE_EQ(voronoi.getCoconeAngle(), kPi / 8) << bad;
  }
  EXPECT_EQ(voronoi.setCoconeAngle(0.3), Status::ok);
  EXPECT_DOUBLE_EQ(voronoi.getCoconeAngle(), 0.3);
}

// A cocone angle out of range given to the constructor is refused by compute().
TEST(VoronoiCocone, OutOfRangeCoconeAngleInTheParametersIsRefusedByCompute)
{
  pcl::cocone::VoronoiParameters parameters;
  parameters.cocone_angle = 2.0;
  VoronoiCocone voronoi(parameters);
  EXPECT_EQ(voronoi.compute(sampleSphere(200, 1).points), Status::invalid_parameter);
  EXPECT_NE(voronoi.errorMessage().find("cocone angle"), std::string::npos)
      << voronoi.errorMessage();
  EXPECT_EQ(voronoi.status(), Status::invalid_parameter);
}

// ---------------------------------------------------------------------------------
// Threads

/** Differences between two computations on the same points. */
struct Differences
{
  std::size_t values = 0; ///< per-sample values (poles, pole vector, height, radius)
  double largest_relative = 0; ///< the largest relative difference among them
  std::size_t triangles =
      0; ///< marked triangles (vertex sets with their marks) not in both
};

/** A marked triangle as (sorted vertices, marks in that order). */
std::pair<std::array<SampleIndex, 3>, int>
canonical(const MarkedTriangle& t)
{
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return t.vertex[a] < t.vertex[b]; });
  std::array<SampleIndex, 3> vertices;
  int marks = 0;
  for (int k = 0; k < 3; ++k) {
    vertices[k] = t.vertex[order[k]];
    marks |= t.isMarkedBy(order[k]) << k;
  }
  return {vertices, marks};
}

Differences
compare(const VoronoiCocone& a, const VoronoiCocone& b)
{
  Differences d;
  const auto value = [&](double x, double y) {
    if (sameValue(x, y))
      return;
    ++d.values;
    d.largest_relative = std::max(d.largest_relative, relativeDifference(x, y));
  };
  const auto vector = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    if (sameVector(x, y))
      return;
    ++d.values;
    d.largest_relative =
        std::max(d.largest_relative, (x - y).norm() / std::max(x.norm(), y.norm()));
  };
  for (SampleIndex i = 0; i < a.size(); ++i) {
    vector(a.poleVector(i), b.poleVector(i));
    vector(a.positivePole(i), b.positivePole(i));
    vector(a.negativePole(i), b.negativePole(i));
    value(a.height(i), b.height(i));
    value(a.coconeRadius(i), b.coconeRadius(i));
  }
  std::set<std::pair<std::array<SampleIndex, 3>, int>> in_a, in_b;
  for (const MarkedTriangle& t : a.markedTriangles())
    in_a.insert(canonical(t));
  for (const MarkedTriangle& t : b.markedTriangles())
    in_b.insert(canonical(t));
  for (const auto& t : in_a)
    d.triangles += !in_b.count(t);
  for (const auto& t : in_b)
    d.triangles += !in_a.count(t);
  return d;
}

// Identical results: per-sample values bit for bit, the same marked triangles (with
// the same marks; their order in the list and the order of the vertices in a triangle
// are unspecified), the same decimation levels. A second single-threaded run is
// compared too: it tells a dependence on the thread count from one on the run.
// (computeCoconeRadius clips each Voronoi edge from the cell of lower index, and cells
// are numbered in container order, which does not depend on threads or on the heap
// layout; an earlier version chose the cell at the lower address, and a few hundred
// radii then differed by up to 4e-9 relatively from run to run.)
TEST(VoronoiCocone, OneThreadAndAllThreadsGiveIdenticalResults)
{
  const SampledShape torus = sampleTorus(5000, 9);
  VoronoiCocone single, parallel, single_again;
  single.setNumberOfThreads(1);
  parallel.setNumberOfThreads(0);
  single_again.setNumberOfThreads(1);
  EXPECT_EQ(single.getNumberOfThreads(), 1u);
  EXPECT_EQ(parallel.getNumberOfThreads(), 0u);
  ASSERT_EQ(single.compute(torus.points), Status::ok);
  ASSERT_EQ(parallel.compute(torus.points), Status::ok);
  ASSERT_EQ(single_again.compute(torus.points), Status::ok);
  ASSERT_EQ(single.size(), parallel.size());
  const Differences threads = compare(single, parallel);
  const Differences runs = compare(single, single_again);
  const std::size_t triangles = single.markedTriangles().size();
  std::cout << "[ measured ] torus 5000, " << triangles
            << " marked triangles; 1 vs all "
            << "threads: " << threads.values << " of " << 5 * torus.points.size()
            << " per-sample values differ (largest relative difference "
            << threads.largest_relative << "), " << threads.triangles
            << " marked triangles differ; 1 thread vs 1 thread (a second run): "
            << runs.values << " values differ (largest " << runs.largest_relative
            << "), " << runs.triangles << " triangles" << std::endl;
  EXPECT_EQ(threads.values, 0u);
  EXPECT_EQ(threads.triangles, 0u);
  EXPECT_EQ(runs.values, 0u);
  EXPECT_EQ(runs.triangles, 0u);

  DecimationLevels levels_single, levels_parallel;
  ASSERT_EQ(decimateUpTo(std::move(single), 0.4, levels_single), Status::ok);
  ASSERT_EQ(decimateUpTo(std::move(parallel), 0.4, levels_parallel), Status::ok);
  std::size_t level_differences = 0, kept_differences = 0;
  for (std::size_t i = 0; i < torus.points.size(); ++i) {
    level_differences += !sameValue(levels_single.level[i], levels_parallel.level[i]);
    for (const double rho : {0.3, 0.4})
      kept_differences +=
          (levels_single.level[i] >= rho) != (levels_parallel.level[i] >= rho);
  }
  std::cout << "[ measured ] decimation up to rho 0.4: " << levels_single.removals
            << " and " << levels_parallel.removals << " removals; " << level_differences
            << " levels differ; " << kept_differences
            << " kept-at-rho (0.3, 0.4) differ" << std::endl;
  EXPECT_EQ(levels_single.removals, levels_parallel.removals);
  EXPECT_EQ(level_differences, 0u);
  EXPECT_EQ(kept_differences, 0u);
}

} // namespace

// spatialOrder: a permutation that follows space (consecutive points are close), is
// stable (identical points keep their order), and sends non-finite points last.
TEST(SpatialOrder, APermutationAlongSpaceStableForIdenticalPoints)
{
  EXPECT_TRUE(pcl::cocone::spatialOrder(Points()).empty());

  Points points = sampleSphere(20000, 4).points;
  const std::size_t distinct = points.size();
  // Copies of point 7 at later positions, and points that cannot be placed.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  points.push_back(points[7]);
  points.emplace_back(nan, 0, 0);
  points.push_back(points[7]);
  points.emplace_back(0, inf, 0);
  const std::vector<SampleIndex> order = pcl::cocone::spatialOrder(points, 1);
  ASSERT_EQ(order.size(), points.size());
  EXPECT_EQ(pcl::cocone::spatialOrder(points, 0), order); // threads change nothing

  std::vector<SampleIndex> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k)
    ASSERT_EQ(sorted[k], k);

  // The non-finite points last, in their input order.
  EXPECT_EQ(order[points.size() - 2], distinct + 1);
  EXPECT_EQ(order[points.size() - 1], distinct + 3);
  // The copies of point 7 right after it, in input order.
  const auto first = std::find(order.begin(), order.end(), SampleIndex(7));
  ASSERT_LE(first + 3, order.end());
  EXPECT_EQ(first[1], distinct);
  EXPECT_EQ(first[2], distinct + 2);

  // Along the curve, consecutive samples are neighbours: on average about a spacing
  // apart, where the input order (blue noise, random) jumps across the sphere.
  const auto meanStep = [&](const std::vector<SampleIndex>& sequence) {
    double sum = 0;
    for (std::size_t k = 1; k < distinct; ++k)
      sum += (points[sequence[k]] - points[sequence[k - 1]]).norm();
    return sum / static_cast<double>(distinct - 1);
  };
  std::vector<SampleIndex> input(distinct);
  std::iota(input.begin(), input.end(), SampleIndex(0));
  const double spacing = std::sqrt(4 * M_PI / static_cast<double>(distinct));
  const double along_curve = meanStep(order), as_given = meanStep(input);
  std::cout << "[ measured ] mean step between consecutive samples: " << along_curve
            << " (curve) and " << as_given << " (input order); spacing " << spacing
            << std::endl;
  EXPECT_LT(along_curve, 3 * spacing);
  EXPECT_GT(as_given, 20 * spacing);
}

// A single point, and points all at one place: nothing to sort, the order is the input.
TEST(SpatialOrder, NoExtentKeepsTheInputOrder)
{
  const Points same(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(pcl::cocone::spatialOrder(same), (std::vector<SampleIndex>{0, 1, 2, 3, 4}));
  EXPECT_EQ(pcl::cocone::spatialOrder(Points(1, Eigen::Vector3d::Zero())),
            std::vector<SampleIndex>{0});
}
