// SPDX-License-Identifier: GPL-3.0-or-later
// pcl::BoundarySampleEstimation: algorithm BOUNDARY (Dey et al. 2001, section 3.3) on
// analytic blue-noise samples whose rims, normals and local feature sizes are known,
// on two real scans (measured and reported), on bad input and over several point
// types. Every check is a property (distances in spacings, fractions), never a list of
// indices or a count that only this implementation would produce.
//
// "spacing" is sqrt(area / n) (SampledShape::spacing()). The measured numbers are
// printed on lines starting with "[ measured ]" so that the margins can be read off a
// test log; the data tests also record them with RecordProperty (XML/JSON output).
#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/io/point_io.h>
#include <pcl/conversions.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/clouds.h"
#include "support/data_paths.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using pcl::cocone::test::SampledShape;
using pcl::cocone::test::toCloud;
using pcl::cocone::test::toPoints;
namespace shapes = pcl::cocone::test;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/** Samples per analytic shape: enough for the rims to be resolved, small enough for
 * the whole file to run in well under a minute. */
constexpr std::size_t kSamples = 6000;

using ShapeGenerator = SampledShape (*)(std::size_t, std::uint32_t);

/** Each analytic shape is sampled once per process (the generators are deterministic
 * for a seed; several tests read the same sample). */
const SampledShape&
cachedShape(const std::string& name, ShapeGenerator generate, std::size_t n = kSamples)
{
  static std::map<std::string, std::unique_ptr<SampledShape>> cache;
  const std::string key = name + "/" + std::to_string(n);
  auto it = cache.find(key);
  if (it == cache.end())
    it = cache.emplace(key, std::make_unique<SampledShape>(generate(n, 1))).first;
  return *it->second;
}

// ---------------------------------------------------------------------------------
// Clouds and runs

/** What one compute() produced, copied out of the estimator. */
struct BoundaryRun
{
  std::size_t rows = 0;
  bool is_dense = true;
  std::vector<std::uint8_t> flags;
  std::vector<std::uint8_t> validity;
  std::vector<Eigen::Vector3f> poles;
  std::vector<float> heights;
  std::vector<float> ratios;
  std::size_t count = 0;
};

template <typename PointT>
BoundaryRun
runBoundary(const typename pcl::PointCloud<PointT>::ConstPtr& cloud,
            unsigned band_rings = 0, const pcl::IndicesPtr& indices = nullptr,
            bool complete_rim_row = true,
            pcl::cocone::DenoiseMode denoise = pcl::cocone::DenoiseMode::automatic)
{
  pcl::BoundarySampleEstimation<PointT, pcl::Boundary> estimator;
  estimator.setInputCloud(cloud);
  estimator.setDenoise(denoise);
  if (indices)
    estimator.setIndices(indices);
  estimator.setBoundaryBandRings(band_rings);
  estimator.setRimRowCompletion(complete_rim_row);
  pcl::PointCloud<pcl::Boundary> output;
  estimator.compute(output);

  BoundaryRun run;
  run.rows = output.size();
  run.is_dense = output.is_dense;
  for (const pcl::Boundary& b : output)
    run.flags.push_back(b.boundary_point ? 1 : 0);
  run.validity = estimator.getValidity();
  run.poles = estimator.getPoleVectors();
  run.heights = estimator.getHeights();
  run.ratios = estimator.getRatios();
  run.count = estimator.getNumberOfBoundarySamples();
  return run;
}

BoundaryRun
runBoundary(const std::vector<Eigen::Vector3d>& points, unsigned band_rings = 0)
{
  return runBoundary<pcl::PointXYZ>(toCloud(points), band_rings);
}

std::vector<Eigen::Vector3d>
flaggedPoints(const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::uint8_t>& flags)
{
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < points.size() && i < flags.size(); ++i)
    if (flags[i])
      out.push_back(points[i]);
  return out;
}

std::size_t
countFlags(const std::vector<std::uint8_t>& flags)
{
  return static_cast<std::size_t>(std::count(flags.begin(), flags.end(), 1));
}

// ---------------------------------------------------------------------------------
// Nearest neighbours (pcl::KdTreeFLANN over a fixed point set)

class NearestPoint
{
public:
  explicit NearestPoint(const std::vector<Eigen::Vector3d>& points)
    : cloud_(toCloud(points))
  {
    if (!points.empty())
      tree_.setInputCloud(cloud_);
  }

  /** Distance from \a x to the nearest point of the set; +infinity for an empty set. */
  double
  distance(const Eigen::Vector3d& x) const
  {
    if (cloud_->empty())
      return kInfinity;
    pcl::PointXYZ query(static_cast<float>(x.x()), static_cast<float>(x.y()),
                        static_cast<float>(x.z()));
    pcl::Indices index(1);
    std::vector<float> squared(1);
    if (tree_.nearestKSearch(query, 1, index, squared) < 1)
      return kInfinity;
    return (x - cloud_->points[index[0]].getVector3fMap().cast<double>()).norm();
  }

  /** The \a k nearest points of the set to \a x (x itself included when it is one). */
  pcl::Indices
  nearest(const Eigen::Vector3d& x, int k) const
  {
    pcl::PointXYZ query(static_cast<float>(x.x()), static_cast<float>(x.y()),
                        static_cast<float>(x.z()));
    pcl::Indices index;
    std::vector<float> squared;
    tree_.nearestKSearch(query, k, index, squared);
    return index;
  }

private:
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree_;
};

// ---------------------------------------------------------------------------------
// Precision and coverage against a rim

struct RimMetrics
{
  std::size_t samples = 0;
  std::size_t flagged = 0;
  double flagged_fraction = 0;
  /** Share of the flags within 3 spacings of the rim (NaN without flags). */
  double precision = std::numeric_limits<double>::quiet_NaN();
  /** Share of the rim points with a flag within 3 spacings. */
  double coverage = 0;
  /** Largest distance, in spacings, from a rim point to its nearest flag. */
  double largest_gap = kInfinity;
  std::size_t rim_points = 0;
};

/** Coverage of \a rim by \a flagged: share of the rim points with a flag within
 * \a near (and the largest distance), both in input units. */
void
measureCoverage(const std::vector<Eigen::Vector3d>& rim,
                const std::vector<Eigen::Vector3d>& flagged, double near,
                double& coverage, double& largest_gap)
{
  const NearestPoint nearest_flag(flagged);
  std::size_t covered = 0;
  largest_gap = 0;
  for (const Eigen::Vector3d& r : rim) {
    const double d = nearest_flag.distance(r);
    covered += d <= near;
    largest_gap = std::max(largest_gap, d);
  }
  coverage = rim.empty() ? 0 : static_cast<double>(covered) / rim.size();
}

/** Precision (flags within 3 spacings of the rim, by the analytic distance) and
 * coverage (rim points with a flag within 3 spacings) of \a flags on \a shape. */
RimMetrics
measureRim(const SampledShape& shape, const std::vector<std::uint8_t>& flags)
{
  const double h = shape.spacing();
  RimMetrics m;
  m.samples = shape.points.size();
  const std::vector<Eigen::Vector3d> flagged = flaggedPoints(shape.points, flags);
  m.flagged = flagged.size();
  m.flagged_fraction = static_cast<double>(m.flagged) / m.samples;
  if (!flagged.empty()) {
    std::size_t near = 0;
    for (const Eigen::Vector3d& p : flagged)
      near += shape.distance_to_rim(p) <= 3 * h;
    m.precision = static_cast<double>(near) / flagged.size();
  }
  m.rim_points = shape.rim.size();
  measureCoverage(shape.rim, flagged, 3 * h, m.coverage, m.largest_gap);
  m.largest_gap /= h;
  return m;
}

void
printMetrics(const std::string& name, const RimMetrics& m)
{
  std::cout << "[ measured ] " << name << ": n=" << m.samples
            << " flagged=" << m.flagged << " (" << std::setprecision(4)
            << 100 * m.flagged_fraction << "%), precision(3 spacings)=" << m.precision
            << ", coverage(3 spacings)=" << m.coverage << " of " << m.rim_points
            << " rim points, largest rim gap=" << m.largest_gap << " spacings"
            << std::endl;
}

std::string
str(double value)
{
  std::ostringstream out;
  out << std::setprecision(4) << value;
  return out.str();
}

double
median(std::vector<double> values)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

double
quantile(std::vector<double> values, double q)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(
                                       q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

// ---------------------------------------------------------------------------------
// Parameterized shape cases

struct ShapeCase
{
  const char* name;
  ShapeGenerator generate;
};

/** Names the case in gtest's messages (instead of its bytes). */
void
PrintTo(const ShapeCase& shape_case, std::ostream* os)
{
  *os << shape_case.name;
}

std::string
caseName(const testing::TestParamInfo<ShapeCase>& info)
{
  return info.param.name;
}

// --- closed smooth surfaces: (almost) nothing is flagged ---------------------------

class ClosedSmoothSurface : public testing::TestWithParam<ShapeCase>
{};

TEST_P(ClosedSmoothSurface, FlagsAtMostOnePercent)
{
  const SampledShape& shape = cachedShape(GetParam().name, GetParam().generate);
  const BoundaryRun run = runBoundary(shape.points);
  ASSERT_EQ(run.rows, shape.points.size());
  const std::size_t flagged = countFlags(run.flags);
  EXPECT_EQ(run.count, flagged);
  const double fraction = static_cast<double>(flagged) / shape.points.size();
  std::cout << "[ measured ] " << shape.name << ": n=" << shape.points.size()
            << " flagged=" << flagged << " (" << std::setprecision(4) << 100 * fraction
            << "%)" << std::endl;
  RecordProperty("flagged_fraction", str(fraction));
  EXPECT_LE(fraction, 0.01) << shape.name << ": " << flagged << " of "
                            << shape.points.size() << " samples flagged";
}

INSTANTIATE_TEST_SUITE_P(
    BoundarySampleEstimation, ClosedSmoothSurface,
    testing::Values(ShapeCase{"sphere", shapes::sampleSphere},
                    ShapeCase{"torus", shapes::sampleTorus},
                    ShapeCase{"trefoil_knot", shapes::sampleTrefoilKnot},
                    ShapeCase{"sphere_dense_cap", shapes::sampleSphereWithDenseCap}),
    caseName);

// --- open surfaces: the flags are the rim, all of it -------------------------------

class OpenSurface : public testing::TestWithParam<ShapeCase>
{};

TEST_P(OpenSurface, FlagsFollowTheWholeRim)
{
  const SampledShape& shape = cachedShape(GetParam().name, GetParam().generate);
  ASSERT_FALSE(shape.rim.empty());
  const BoundaryRun run = runBoundary(shape.points);
  ASSERT_EQ(run.rows, shape.points.size());
  const RimMetrics m = measureRim(shape, run.flags);
  printMetrics(shape.name, m);
  RecordProperty("precision", str(m.precision));
  RecordProperty("coverage", str(m.coverage));
  RecordProperty("largest_gap_spacings", str(m.largest_gap));

  ASSERT_GT(m.flagged, 0u) << shape.name << ": no sample flagged";
  EXPECT_GE(m.precision, 0.95) << shape.name << ": flags away from the rim";
  EXPECT_GE(m.coverage, 0.95) << shape.name << ": rim points without a nearby flag";
  EXPECT_LE(m.largest_gap, 5.0) << shape.name << ": a stretch of rim has no flag";
}

/** setBoundaryBandRings(2): a band along the rim, as pcl::BoundaryEstimation gives. */
TEST_P(OpenSurface, BoundaryBandCoversTheRimRow)
{
  const SampledShape& shape = cachedShape(GetParam().name, GetParam().generate);
  const double h = shape.spacing();
  const BoundaryRun run = runBoundary(shape.points, 2);
  ASSERT_EQ(run.rows, shape.points.size());

  std::size_t near_rim = 0, near_rim_flagged = 0;
  for (std::size_t i = 0; i < shape.points.size(); ++i)
    if (shape.distance_to_rim(shape.points[i]) <= h) {
      ++near_rim;
      near_rim_flagged += run.flags[i];
    }
  ASSERT_GT(near_rim, 0u);
  const double recall = static_cast<double>(near_rim_flagged) / near_rim;
  const RimMetrics m = measureRim(shape, run.flags);
  std::cout << "[ measured ] " << shape.name << " band (2 rings): flagged=" << m.flagged
            << " (" << std::setprecision(4) << 100 * m.flagged_fraction
            << "%), recall(within 1 spacing)=" << recall << " of " << near_rim
            << " samples, precision(3 spacings)=" << m.precision << std::endl;
  RecordProperty("band_recall", str(recall));
  RecordProperty("band_precision", str(m.precision));
  EXPECT_GE(recall, 0.95) << shape.name;
  EXPECT_GE(m.precision, 0.9) << shape.name;

  // The band contains the outermost row: every flag of the default run stays flagged.
  const BoundaryRun plain = runBoundary(shape.points);
  std::size_t lost = 0;
  for (std::size_t i = 0; i < plain.flags.size(); ++i)
    lost += plain.flags[i] && !run.flags[i];
  EXPECT_EQ(lost, 0u) << shape.name << ": the band dropped flags of the default run";
}

/** The outermost row, as the paper's Definition 1 means it: the samples nearest to the
 * true rim (the nearest sample of each dense rim point). BOUNDARY as published flags
 * part of it and nothing else; the default completion finds (almost) all of it. */
TEST_P(OpenSurface, CompletedRimRowIsTheOutermostRow)
{
  const SampledShape& shape = cachedShape(GetParam().name, GetParam().generate);
  const NearestPoint nearest(shape.points);
  std::vector<std::uint8_t> in_row(shape.points.size(), 0);
  for (const Eigen::Vector3d& r : shape.rim)
    in_row[static_cast<std::size_t>(nearest.nearest(r, 1).at(0))] = 1;
  const std::size_t row = countFlags(in_row);

  const auto score = [&](const BoundaryRun& run, double& precision, double& recall) {
    std::size_t flagged_in_row = 0;
    for (std::size_t i = 0; i < in_row.size(); ++i)
      flagged_in_row += in_row[i] && run.flags[i];
    precision =
        static_cast<double>(flagged_in_row) / std::max<std::size_t>(1, run.count);
    recall = static_cast<double>(flagged_in_row) / row;
  };
  const auto cloud = toCloud(shape.points);
  const BoundaryRun published = runBoundary<pcl::PointXYZ>(cloud, 0, nullptr, false);
  const BoundaryRun completed = runBoundary<pcl::PointXYZ>(cloud);
  double published_precision = 0, published_recall = 0, precision = 0, recall = 0;
  score(published, published_precision, published_recall);
  score(completed, precision, recall);
  std::cout << "[ measured ] " << shape.name << " rim row of " << row
            << " samples: as published precision=" << published_precision
            << " recall=" << published_recall << "; completed precision=" << precision
            << " recall=" << recall << std::endl;
  RecordProperty("row_recall_published", str(published_recall));
  RecordProperty("row_recall_completed", str(recall));

  EXPECT_GE(published_precision, 0.98) << shape.name;
  EXPECT_GE(precision, 0.97) << shape.name << ": completion left the row";
  EXPECT_GE(recall, 0.9) << shape.name << ": completion missed the row";
  EXPECT_GT(recall, published_recall + 0.2) << shape.name;
  std::size_t lost = 0;
  for (std::size_t i = 0; i < published.flags.size(); ++i)
    lost += published.flags[i] && !completed.flags[i];
  EXPECT_EQ(lost, 0u) << shape.name << ": completion dropped flags of BOUNDARY";
}

INSTANTIATE_TEST_SUITE_P(
    BoundarySampleEstimation, OpenSurface,
    testing::Values(ShapeCase{"hemisphere", shapes::sampleHemisphere},
                    ShapeCase{"monkey_saddle", shapes::sampleMonkeySaddle},
                    ShapeCase{"open_cylinder", shapes::sampleOpenCylinder}),
    caseName);

// Random samples (issue 22): the flags stay on the rim, at 6k (three seeds; a 6k random
// hemisphere with a coarser jitter once gave 94% of its flags near the rim) and at 30k,
// on every open shape. Measured: precision 0.968 to 0.996, coverage 1.
TEST(BoundarySampleEstimation, RandomSamplesFlagTheRimOnly)
{
  using shapes::Shape;
  for (const Shape which : {Shape::hemisphere, Shape::monkey_saddle,
                            Shape::open_cylinder, Shape::half_cylinder})
    for (const auto& [n, seed] : {std::pair<std::size_t, std::uint32_t>{6000, 1},
                                  {6000, 2},
                                  {6000, 3},
                                  {30000, 1}}) {
      const SampledShape shape = shapes::sampleRandom(which, n, seed);
      const BoundaryRun run = runBoundary(shape.points);
      ASSERT_EQ(run.rows, shape.points.size());
      const RimMetrics m = measureRim(shape, run.flags);
      printMetrics("random " + shape.name + " seed " + std::to_string(seed), m);
      EXPECT_GE(m.precision, 0.95) << shape.name << " " << n << " seed " << seed;
      EXPECT_GE(m.coverage, 0.95) << shape.name << " " << n << " seed " << seed;
    }
}

// --- the cube: sharp edges are undersampling too ----------------------------------

TEST(BoundarySampleEstimation, CubeFlagsFollowItsEdges)
{
  const SampledShape& shape = cachedShape("cube", shapes::sampleCube);
  const double h = shape.spacing();
  ASSERT_FALSE(shape.rim.empty());
  const BoundaryRun run = runBoundary(shape.points);
  ASSERT_EQ(run.rows, shape.points.size());
  const RimMetrics m = measureRim(shape, run.flags);
  printMetrics("cube (rim = the 12 edges)", m);

  std::size_t far = 0, far_flagged = 0;
  for (std::size_t i = 0; i < shape.points.size(); ++i)
    if (shape.distance_to_rim(shape.points[i]) > 3 * h) {
      ++far;
      far_flagged += run.flags[i];
    }
  ASSERT_GT(far, 0u);
  const double false_rate = static_cast<double>(far_flagged) / far;
  std::cout << "[ measured ] cube: flagged among the " << far
            << " samples farther than 3 spacings from an edge: " << far_flagged << " ("
            << std::setprecision(4) << 100 * false_rate << "%)" << std::endl;
  RecordProperty("coverage", str(m.coverage));
  RecordProperty("largest_gap_spacings", str(m.largest_gap));
  RecordProperty("face_flag_fraction", str(false_rate));

  EXPECT_GE(m.coverage, 0.95);
  EXPECT_LE(m.largest_gap, 5.0);
  EXPECT_LE(false_rate, 0.01);
}

// --- per-point Voronoi values: pole vectors and heights ---------------------------

class PoleAndHeight : public testing::TestWithParam<ShapeCase>
{};

TEST_P(PoleAndHeight, MatchNormalsAndLocalFeatureSize)
{
  const SampledShape& shape = cachedShape(GetParam().name, GetParam().generate);
  ASSERT_TRUE(static_cast<bool>(shape.local_feature_size));
  const BoundaryRun run = runBoundary(shape.points);
  ASSERT_EQ(run.poles.size(), shape.points.size());
  ASSERT_EQ(run.heights.size(), shape.points.size());

  std::vector<double> angles, errors;
  std::size_t undefined_heights = 0;
  for (std::size_t i = 0; i < shape.points.size(); ++i) {
    const Eigen::Vector3d v = run.poles[i].cast<double>();
    ASSERT_TRUE(v.allFinite()) << "row " << i;
    EXPECT_NEAR(v.norm(), 1.0, 1e-4) << "row " << i;
    const double c = std::min(1.0, std::abs(v.normalized().dot(shape.normals[i])));
    angles.push_back(std::acos(c) * 180 / kPi);
    if (!std::isfinite(run.heights[i])) {
      ++undefined_heights;
      continue;
    }
    const double lfs = shape.local_feature_size(shape.points[i]);
    errors.push_back(std::abs(run.heights[i] - lfs) / lfs);
  }
  const double median_angle = median(angles);
  const double median_error = median(errors);
  std::cout << "[ measured ] " << shape.name << ": pole line vs normal: median "
            << std::setprecision(4) << median_angle << " deg, 95% quantile "
            << quantile(angles, 0.95) << " deg; height vs local feature size: median "
            << "relative error " << median_error << ", 95% quantile "
            << quantile(errors, 0.95) << "; undefined heights: " << undefined_heights
            << std::endl;
  RecordProperty("median_pole_angle_deg", str(median_angle));
  RecordProperty("median_height_relative_error", str(median_error));
  EXPECT_LT(median_angle, 2.0);
  EXPECT_LT(median_error, 0.01);
}

INSTANTIATE_TEST_SUITE_P(BoundarySampleEstimation, PoleAndHeight,
                         testing::Values(ShapeCase{"sphere", shapes::sampleSphere},
                                         ShapeCase{"torus", shapes::sampleTorus}),
                         caseName);

// ---------------------------------------------------------------------------------
// Real scans

/** Reads the samples of \a path as PointXYZ. */
pcl::PointCloud<pcl::PointXYZ>::Ptr
loadCloud(const std::string& path)
{
  pcl::PCLPointCloud2 blob;
  std::string error;
  if (!pcl::cocone::loadPointSamples(path, blob, &error)) {
    ADD_FAILURE() << "cannot read " << path << ": " << error;
    return nullptr;
  }
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::fromPCLPointCloud2(blob, *cloud);
  return cloud;
}

/** The Stanford bunny (the paper's BUNNY): its holes are the boundary loops of the
 * reference mesh (in the base). BOUNDARY should find them; it also flags thin,
 * undersampled parts (the ears), which the paper counts as boundary too: its
 * definition covers every kind of undersampling, not only true rims. */
TEST(BoundarySampleEstimation, StanfordBunnyHoles)
{
  PCL_COCONE_REQUIRE_DATA_FILE(path, "bun_zipper_35947.ply");
  const auto cloud = loadCloud(path);
  ASSERT_TRUE(cloud);
  const std::vector<Eigen::Vector3d> points = toPoints(*cloud);

  std::vector<pcl::Vertices> faces;
  std::string error;
  ASSERT_TRUE(pcl::cocone::loadMeshFaces(path, faces, &error)) << error;
  std::vector<pcl::cocone::TriangleIndices> triangles;
  std::vector<std::uint8_t> in_mesh(points.size(), 0);
  double area = 0;
  for (const pcl::Vertices& f : faces) {
    ASSERT_EQ(f.vertices.size(), 3u);
    pcl::cocone::TriangleIndices t;
    for (int k = 0; k < 3; ++k) {
      ASSERT_LT(f.vertices[k], points.size());
      t[k] = f.vertices[k];
      in_mesh[t[k]] = 1;
    }
    triangles.push_back(t);
    area +=
        0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
  }
  const pcl::cocone::MeshTopology topology =
      pcl::cocone::analyzeTriangleMesh(triangles);
  ASSERT_FALSE(topology.boundary_loops.empty())
      << "the reference mesh should have holes (223 boundary edges)";
  // The samples of the surface are the vertices the mesh uses.
  const double h = std::sqrt(area / static_cast<double>(topology.vertices));

  std::vector<Eigen::Vector3d> hole_rim;
  for (const auto& loop : topology.boundary_loops)
    for (const std::uint32_t v : loop)
      hole_rim.push_back(points[v]);

  // BOUNDARY as published, on the samples as given: the automatic noise handling
  // smooths the milk carton (noise 0.19 spacings) and then covers 72% of this rim
  // estimate instead of 80% or more (docs/noise.md, what is left).
  const BoundaryRun run = runBoundary<pcl::PointXYZ>(cloud, 0, nullptr, true,
                                                     pcl::cocone::DenoiseMode::off);
  ASSERT_EQ(run.rows, points.size());
  const std::vector<Eigen::Vector3d> flagged = flaggedPoints(points, run.flags);
  ASSERT_FALSE(flagged.empty());

  double coverage = 0, largest_gap = 0;
  measureCoverage(hole_rim, flagged, 3 * h, coverage, largest_gap);
  std::ostringstream per_hole;
  for (const auto& loop : topology.boundary_loops) {
    std::vector<Eigen::Vector3d> loop_points;
    for (const std::uint32_t v : loop)
      loop_points.push_back(points[v]);
    double loop_coverage = 0, loop_gap = 0;
    measureCoverage(loop_points, flagged, 3 * h, loop_coverage, loop_gap);
    per_hole << " " << std::lround(loop_coverage * loop.size()) << "/" << loop.size();
  }
  std::size_t off_mesh = 0, off_mesh_flagged = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!in_mesh[i]) {
      ++off_mesh;
      off_mesh_flagged += run.flags[i];
    }

  // Where the other flags are: farther than 3 spacings from any hole rim, by height.
  // The bunny stands with y up; the ears are the thin parts at the top (largest y).
  const NearestPoint nearest_rim(hole_rim);
  double y_lo = kInfinity, y_hi = -kInfinity;
  for (const Eigen::Vector3d& p : points) {
    y_lo = std::min(y_lo, p.y());
    y_hi = std::max(y_hi, p.y());
  }
  constexpr int kBands = 5;
  std::vector<std::size_t> off_rim_by_band(kBands, 0), samples_by_band(kBands, 0);
  auto band = [&](const Eigen::Vector3d& p) {
    return std::min(kBands - 1,
                    static_cast<int>(kBands * (p.y() - y_lo) / (y_hi - y_lo)));
  };
  for (const Eigen::Vector3d& p : points)
    ++samples_by_band[band(p)];
  std::size_t off_rim = 0;
  for (const Eigen::Vector3d& p : flagged)
    if (nearest_rim.distance(p) > 3 * h) {
      ++off_rim;
      ++off_rim_by_band[band(p)];
    }
  const double off_rim_fraction = static_cast<double>(off_rim) / flagged.size();
  const double top_share =
      off_rim ? static_cast<double>(off_rim_by_band[kBands - 1]) / off_rim : 0.0;

  std::cout << "[ measured ] bunny: n=" << points.size() << " (" << topology.vertices
            << " in the mesh), spacing=" << std::setprecision(4) << h << ", "
            << topology.boundary_loops.size() << " holes with " << hole_rim.size()
            << " rim vertices; flagged=" << flagged.size() << " ("
            << 100.0 * flagged.size() / points.size() << "%)" << std::endl;
  std::cout << "[ measured ] bunny: hole-rim coverage (flag within 3 spacings)="
            << coverage << " (reference implementation: about 0.80), per hole"
            << per_hole.str() << ", largest gap=" << largest_gap / h << " spacings"
            << std::endl;
  std::cout << "[ measured ] bunny: flags farther than 3 spacings from any hole rim: "
            << off_rim << " (" << 100 * off_rim_fraction << "% of the flags); by height"
            << " (5 bands of y, bottom to top, flags / samples):";
  for (int b = 0; b < kBands; ++b)
    std::cout << " " << off_rim_by_band[b] << "/" << samples_by_band[b];
  std::cout << "; top band (the ears) holds " << 100 * top_share << "% of them; "
            << off_mesh_flagged << " of the " << off_mesh
            << " vertices no triangle uses are flagged" << std::endl;
  RecordProperty("hole_rim_coverage", str(coverage));
  RecordProperty("flagged_fraction",
                 str(static_cast<double>(flagged.size()) / points.size()));
  RecordProperty("off_rim_flag_fraction", str(off_rim_fraction));
  RecordProperty("off_rim_flags_in_top_band", str(top_share));

  EXPECT_GE(coverage, 0.75);
}

/** Rim samples of a scan whose rim is not known: the samples whose 12 nearest
 * neighbours, projected on their PCA plane, leave an angular gap wider than 120
 * degrees (the neighbourhood is one-sided). */
std::vector<std::uint8_t>
estimateRimSamples(const std::vector<Eigen::Vector3d>& points, const NearestPoint& all)
{
  constexpr int kNeighbours = 12;
  std::vector<std::uint8_t> rim(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const pcl::Indices found = all.nearest(points[i], kNeighbours + 1);
    std::vector<Eigen::Vector3d> neighbours;
    for (const pcl::index_t j : found)
      if (static_cast<std::size_t>(j) != i && (points[j] - points[i]).norm() > 0)
        neighbours.push_back(points[j]);
    if (neighbours.size() < 3) {
      rim[i] = 1;
      continue;
    }
    Eigen::Vector3d mean = points[i];
    for (const Eigen::Vector3d& q : neighbours)
      mean += q;
    mean /= static_cast<double>(neighbours.size() + 1);
    Eigen::Matrix3d covariance = (points[i] - mean) * (points[i] - mean).transpose();
    for (const Eigen::Vector3d& q : neighbours)
      covariance += (q - mean) * (q - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    const Eigen::Vector3d u = solver.eigenvectors().col(2);
    const Eigen::Vector3d w = solver.eigenvectors().col(1);
    std::vector<double> angles;
    for (const Eigen::Vector3d& q : neighbours)
      angles.push_back(std::atan2((q - points[i]).dot(w), (q - points[i]).dot(u)));
    std::sort(angles.begin(), angles.end());
    double gap = angles.front() + 2 * kPi - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k)
      gap = std::max(gap, angles[k] - angles[k - 1]);
    rim[i] = gap > 120 * kPi / 180;
  }
  return rim;
}

/** PCL's milk carton: a partial view, so open along the silhouette, plus the box's
 * sharp edges. Its rim is estimated from the samples (see estimateRimSamples). */
TEST(BoundarySampleEstimation, MilkCartonPartialView)
{
  PCL_COCONE_REQUIRE_DATA_FILE(path, "pcl_milk_13704.pcd");
  const auto raw = loadCloud(path);
  ASSERT_TRUE(raw);
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const pcl::PointXYZ& p : *raw)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
      cloud->push_back(p);
  const std::vector<Eigen::Vector3d> points = toPoints(*cloud);
  ASSERT_GE(points.size(), 1000u);

  // Spacing: no reference surface, so a robust estimate from the samples.
  const NearestPoint all(points);
  std::vector<double> nearest_distances;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (const pcl::index_t j : all.nearest(points[i], 4)) {
      const double d = (points[j] - points[i]).norm();
      if (static_cast<std::size_t>(j) != i && d > 0) {
        nearest_distances.push_back(d);
        break;
      }
    }
  }
  const double h = 1.1 * median(nearest_distances);

  const std::vector<std::uint8_t> is_rim = estimateRimSamples(points, all);
  const std::vector<Eigen::Vector3d> rim = flaggedPoints(points, is_rim);
  ASSERT_FALSE(rim.empty());

  // BOUNDARY as published, on the samples as given: the automatic noise handling
  // smooths the milk carton (noise 0.19 spacings) and then covers 72% of this rim
  // estimate instead of 80% or more (docs/noise.md, what is left).
  const BoundaryRun run = runBoundary<pcl::PointXYZ>(cloud, 0, nullptr, true,
                                                     pcl::cocone::DenoiseMode::off);
  ASSERT_EQ(run.rows, points.size());
  const std::vector<Eigen::Vector3d> flagged = flaggedPoints(points, run.flags);
  ASSERT_FALSE(flagged.empty());
  const double flagged_fraction = static_cast<double>(flagged.size()) / points.size();

  double coverage = 0, largest_gap = 0;
  measureCoverage(rim, flagged, 3 * h, coverage, largest_gap);
  const NearestPoint nearest_rim(rim);
  std::size_t near = 0;
  for (const Eigen::Vector3d& p : flagged)
    near += nearest_rim.distance(p) <= 3 * h;
  const double precision = static_cast<double>(near) / flagged.size();
  // Why the flags far from the rim are flags: fat cells (ratio condition fails) or
  // disagreeing pole lines.
  std::size_t far = 0, far_fat = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (run.flags[i] && nearest_rim.distance(points[i]) > 3 * h) {
      ++far;
      far_fat += !(run.ratios[i] <= 0.99);
    }

  std::cout << "[ measured ] milk: n=" << points.size() << " (of " << raw->size()
            << "), spacing~" << std::setprecision(4) << h
            << ", estimated rim samples=" << rim.size() << " ("
            << 100.0 * rim.size() / points.size() << "%); flagged=" << flagged.size()
            << " (" << 100 * flagged_fraction << "%)" << std::endl;
  std::cout << "[ measured ] milk: coverage of the estimated rim (flag within 3 "
            << "spacings)=" << coverage << ", largest gap=" << largest_gap / h
            << " spacings; precision (flags within 3 spacings of the estimated rim)="
            << precision << "; of the " << far << " flags farther away, "
            << 100.0 * far_fat / std::max<std::size_t>(far, 1)
            << "% fail the ratio condition r/h <= 0.99 (fat cells: sharp box edges, "
            << "noise, sparse patches), the rest the normal condition" << std::endl;
  RecordProperty("flagged_fraction", str(flagged_fraction));
  RecordProperty("rim_coverage", str(coverage));
  RecordProperty("rim_precision", str(precision));

  EXPECT_GE(coverage, 0.8);
}

// ---------------------------------------------------------------------------------
// Bad input

/** Runs compute() on \a cloud, capturing what PCL prints on stderr. */
std::size_t
computeCapturingStderr(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud,
                       std::string& printed)
{
  pcl::BoundarySampleEstimation<pcl::PointXYZ> estimator;
  estimator.setInputCloud(cloud);
  pcl::PointCloud<pcl::Boundary> output;
  output.resize(3); // must be emptied
  testing::internal::CaptureStderr();
  estimator.compute(output);
  printed = testing::internal::GetCapturedStderr();
  EXPECT_EQ(estimator.getNumberOfBoundarySamples(), 0u);
  EXPECT_EQ(output.width * output.height, output.size());
  return output.size();
}

TEST(BoundarySampleEstimation, EmptyCloudGivesEmptyOutput)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  std::string printed;
  EXPECT_EQ(computeCapturingStderr(cloud, printed), 0u);
}

TEST(BoundarySampleEstimation, FewerThanFourPointsIsAnError)
{
  // Three points; and five rows of which only three are distinct finite points.
  const std::vector<std::vector<Eigen::Vector3d>> inputs = {
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}},
  };
  for (const auto& points : inputs) {
    std::string printed;
    EXPECT_EQ(computeCapturingStderr(toCloud(points), printed), 0u);
    EXPECT_NE(printed.find("BoundarySampleEstimation"), std::string::npos) << printed;
  }
  auto cloud = toCloud({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  (*cloud)[3].x = std::numeric_limits<float>::quiet_NaN();
  cloud->is_dense = false;
  std::string printed;
  EXPECT_EQ(computeCapturingStderr(cloud, printed), 0u);
  EXPECT_NE(printed.find("BoundarySampleEstimation"), std::string::npos) << printed;
}

TEST(BoundarySampleEstimation, CoplanarAndCollinearPointsAreAnError)
{
  // Exactly coplanar or collinear in float (dyadic coordinates), so that rounding to
  // the cloud's floats cannot lift them into 3D: planes parallel to a coordinate plane
  // and tilted ones, lines through the origin and elsewhere.
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> inputs = {
      {"plane z = 0", {}},
      {"plane z = 0.25", {}},
      {"tilted plane z = x - y", {}},
      {"tilted plane z = 0.5 x + 0.25 y + 3", {}},
      {"line through the origin", {}},
      {"line through (3, 1, -2)", {}}};
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const double x = i + 0.25 * (j % 3), y = j + 0.5 * (i % 2);
      inputs[0].second.emplace_back(x, y, 0);
      inputs[1].second.emplace_back(x, y, 0.25);
      inputs[2].second.emplace_back(x, y, x - y);
      inputs[3].second.emplace_back(x, y, 0.5 * x + 0.25 * y + 3);
    }
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d direction(1, -2, 0.5);
    inputs[4].second.push_back(direction * (0.125 * i * i));
    inputs[5].second.push_back(Eigen::Vector3d(3, 1, -2) + direction * (0.125 * i * i));
  }
  for (const auto& input : inputs) {
    SCOPED_TRACE(input.first);
    std::string printed;
    const std::size_t rows = computeCapturingStderr(toCloud(input.second), printed);
    std::cout << "[ measured ] " << input.first << " (" << input.second.size()
              << " points): output rows=" << rows << ", error reported: "
              << (printed.find("BoundarySampleEstimation") != std::string::npos ? "yes"
                                                                                : "no")
              << std::endl;
    EXPECT_EQ(rows, 0u);
    EXPECT_NE(printed.find("BoundarySampleEstimation"), std::string::npos) << printed;
  }
}

TEST(BoundarySampleEstimation, NonFinitePointsAreSkipped)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere);
  const auto clean = toCloud(shape.points);
  const BoundaryRun reference = runBoundary<pcl::PointXYZ>(clean);
  ASSERT_EQ(reference.rows, clean->size());

  // Every 97th row of the mixed cloud is bad: NaN or infinite in one coordinate.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto mixed = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  std::vector<std::ptrdiff_t> source; // row of `clean`, or -1 for a bad row
  for (std::size_t i = 0; i < clean->size(); ++i) {
    if (i % 97 == 0) {
      const int kind = static_cast<int>(source.size() % 4);
      pcl::PointXYZ bad(0.5f, 0.5f, 0.5f);
      if (kind == 0)
        bad.x = nan;
      else if (kind == 1)
        bad.y = inf;
      else if (kind == 2)
        bad.z = -inf;
      else
        bad = pcl::PointXYZ(nan, nan, nan);
      mixed->push_back(bad);
      source.push_back(-1);
    }
    mixed->push_back((*clean)[i]);
    source.push_back(static_cast<std::ptrdiff_t>(i));
  }
  mixed->is_dense = false;

  const BoundaryRun run = runBoundary<pcl::PointXYZ>(mixed);
  ASSERT_EQ(run.rows, mixed->size());
  ASSERT_EQ(run.validity.size(), mixed->size());
  EXPECT_FALSE(run.is_dense);
  std::size_t bad_rows = 0, changed = 0;
  for (std::size_t row = 0; row < mixed->size(); ++row) {
    if (source[row] < 0) {
      ++bad_rows;
      EXPECT_EQ(run.flags[row], 0) << "row " << row;
      EXPECT_EQ(run.validity[row], 0) << "row " << row;
      EXPECT_TRUE(std::isnan(run.heights[row])) << "row " << row;
      EXPECT_TRUE(std::isnan(run.poles[row].x())) << "row " << row;
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(source[row]);
    EXPECT_EQ(run.validity[row], 1) << "row " << row;
    const bool same = run.flags[row] == reference.flags[i] &&
                      (run.heights[row] == reference.heights[i] ||
                       std::abs(run.heights[row] - reference.heights[i]) <=
                           1e-5f * std::abs(reference.heights[i])) &&
                      (run.poles[row] - reference.poles[i]).norm() <= 1e-5f;
    changed += !same;
  }
  std::cout << "[ measured ] non-finite rows: " << bad_rows << " of " << mixed->size()
            << "; finite rows differing from the run without them: " << changed
            << std::endl;
  EXPECT_GT(bad_rows, 0u);
  EXPECT_EQ(changed, 0u);
  EXPECT_EQ(run.count, reference.count);
}

TEST(BoundarySampleEstimation, DuplicatesGetTheirRepresentativesFlag)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere);
  const auto clean = toCloud(shape.points);
  const BoundaryRun reference = runBoundary<pcl::PointXYZ>(clean);

  // Copies of every 13th point, and several copies of the flagged ones, appended.
  auto doubled = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>(*clean);
  std::vector<std::size_t> original;
  for (std::size_t i = 0; i < clean->size(); ++i) {
    const int copies =
        (i % 13 == 0 ? 1 : 0) + (reference.flags[i] && i % 5 == 0 ? 2 : 0);
    for (int c = 0; c < copies; ++c) {
      doubled->push_back((*clean)[i]);
      original.push_back(i);
    }
  }
  ASSERT_GT(original.size(), 0u);
  const BoundaryRun run = runBoundary<pcl::PointXYZ>(doubled);
  ASSERT_EQ(run.rows, doubled->size());

  std::size_t flagged_copies = 0, mismatched = 0, changed = 0;
  for (std::size_t k = 0; k < original.size(); ++k) {
    const std::size_t row = clean->size() + k;
    mismatched += run.flags[row] != run.flags[original[k]];
    flagged_copies += run.flags[row];
    EXPECT_EQ(run.validity[row], 1);
  }
  for (std::size_t i = 0; i < clean->size(); ++i)
    changed += run.flags[i] != reference.flags[i];
  std::cout << "[ measured ] duplicates: " << original.size() << " copies ("
            << flagged_copies
            << " flagged); copies disagreeing with their original: " << mismatched
            << "; originals changed by the copies: " << changed << std::endl;
  EXPECT_EQ(mismatched, 0u);
  EXPECT_GT(flagged_copies, 0u);
  // Duplicates share one Voronoi cell: the diagram, hence the flags, do not change.
  EXPECT_EQ(changed, 0u);
}

TEST(BoundarySampleEstimation, IndicesSelectRowsOfTheFullRun)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere);
  const auto cloud = toCloud(shape.points);
  const BoundaryRun full = runBoundary<pcl::PointXYZ>(cloud);

  // Every third point, in a shuffled order.
  auto indices = pcl::make_shared<pcl::Indices>();
  for (std::size_t i = 0; i < cloud->size(); i += 3)
    indices->push_back(static_cast<pcl::index_t>(i));
  std::mt19937 engine(7);
  for (std::size_t k = indices->size(); k > 1; --k)
    std::swap((*indices)[k - 1], (*indices)[engine() % k]);

  const BoundaryRun subset = runBoundary<pcl::PointXYZ>(cloud, 0, indices);
  ASSERT_EQ(subset.rows, indices->size());
  ASSERT_EQ(subset.heights.size(), indices->size());
  std::size_t differing = 0, flagged = 0;
  for (std::size_t row = 0; row < indices->size(); ++row) {
    const std::size_t i = static_cast<std::size_t>((*indices)[row]);
    differing += subset.flags[row] != full.flags[i] ||
                 std::abs(subset.heights[row] - full.heights[i]) >
                     1e-5f * std::abs(full.heights[i]) ||
                 (subset.poles[row] - full.poles[i]).norm() > 1e-5f;
    flagged += subset.flags[row];
  }
  std::cout << "[ measured ] indices: " << indices->size() << " rows (" << flagged
            << " flagged); rows differing from the full run: " << differing
            << std::endl;
  EXPECT_GT(flagged, 0u);
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(subset.count, flagged);
}

// The flags and per-point values depend on the points, not on their order in the
// cloud (the samples reach the core in spatial order).
TEST(BoundarySampleEstimation, ShuffledCloudGivesTheSameRows)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere);
  const auto cloud = toCloud(shape.points);
  std::vector<std::size_t> shuffle;
  const auto shuffled = pcl::cocone::test::shuffledCloud(*cloud, 3, shuffle);
  const BoundaryRun as_given = runBoundary<pcl::PointXYZ>(cloud);
  const BoundaryRun reordered = runBoundary<pcl::PointXYZ>(shuffled);
  ASSERT_EQ(reordered.rows, shuffle.size());
  std::size_t differing = 0;
  for (std::size_t row = 0; row < shuffle.size(); ++row) {
    const std::size_t i = shuffle[row];
    differing += reordered.flags[row] != as_given.flags[i] ||
                 reordered.heights[row] != as_given.heights[i] ||
                 reordered.ratios[row] != as_given.ratios[i] ||
                 reordered.poles[row] != as_given.poles[i];
  }
  EXPECT_GT(as_given.count, 0u);
  EXPECT_EQ(reordered.count, as_given.count);
  EXPECT_EQ(differing, 0u);
}

TEST(BoundarySampleEstimation, OutOfRangeSettersKeepTheValue)
{
  pcl::BoundarySampleEstimation<pcl::PointXYZ> estimator;
  EXPECT_DOUBLE_EQ(estimator.getRatioBound(), 0.99);
  EXPECT_DOUBLE_EQ(estimator.getNormalAngle(), kPi / 6);
  EXPECT_DOUBLE_EQ(estimator.getCoconeAngle(), kPi / 8);
  EXPECT_EQ(estimator.getBoundaryBandRings(), 0u);

  estimator.setRatioBound(0.5);
  estimator.setNormalAngle(0.3);
  estimator.setCoconeAngle(0.2);
  estimator.setBoundaryBandRings(3);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  testing::internal::CaptureStderr();
  estimator.setRatioBound(-1);
  estimator.setRatioBound(nan);
  estimator.setNormalAngle(2);
  estimator.setNormalAngle(nan);
  estimator.setCoconeAngle(0);
  estimator.setCoconeAngle(kPi / 2);
  estimator.setBoundaryBandRings(100);
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(printed.empty()) << "out-of-range values should be reported";

  EXPECT_DOUBLE_EQ(estimator.getRatioBound(), 0.5);
  EXPECT_DOUBLE_EQ(estimator.getNormalAngle(), 0.3);
  EXPECT_DOUBLE_EQ(estimator.getCoconeAngle(), 0.2);
  EXPECT_EQ(estimator.getBoundaryBandRings(), 3u);
}

TEST(BoundarySampleEstimation, SearchSurfaceIsNotSupported)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere);
  const auto cloud = toCloud(shape.points);
  std::vector<Eigen::Vector3d> half(shape.points.begin(),
                                    shape.points.begin() + shape.points.size() / 2);
  const auto other = toCloud(half);

  pcl::BoundarySampleEstimation<pcl::PointXYZ> estimator;
  estimator.setInputCloud(cloud);
  estimator.setSearchSurface(other);
  pcl::PointCloud<pcl::Boundary> output;
  testing::internal::CaptureStderr();
  estimator.compute(output);
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_EQ(output.size(), 0u);
  EXPECT_NE(printed.find("BoundarySampleEstimation"), std::string::npos) << printed;
}

// ---------------------------------------------------------------------------------
// Point types

template <typename PointT>
const char* pointTypeName();
template <>
const char*
pointTypeName<pcl::PointXYZ>()
{
  return "PointXYZ";
}
template <>
const char*
pointTypeName<pcl::PointXYZRGB>()
{
  return "PointXYZRGB";
}
template <>
const char*
pointTypeName<pcl::PointNormal>()
{
  return "PointNormal";
}

template <typename PointT>
class BoundarySampleEstimationTyped : public testing::Test
{};

using PointTypes = testing::Types<pcl::PointXYZ, pcl::PointXYZRGB, pcl::PointNormal>;
TYPED_TEST_SUITE(BoundarySampleEstimationTyped, PointTypes);

TYPED_TEST(BoundarySampleEstimationTyped, HemisphereRim)
{
  const SampledShape& shape = cachedShape("hemisphere", shapes::sampleHemisphere, 4000);
  const auto cloud = toCloud<TypeParam>(shape.points);
  const BoundaryRun run = runBoundary<TypeParam>(cloud);
  ASSERT_EQ(run.rows, shape.points.size());
  const RimMetrics m = measureRim(shape, run.flags);
  printMetrics(shape.name + " as " + pointTypeName<TypeParam>(), m);
  EXPECT_GE(m.precision, 0.95);
  EXPECT_GE(m.coverage, 0.95);
}

} // namespace
