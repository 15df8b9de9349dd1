// SPDX-License-Identifier: GPL-3.0-or-later
// The analytic test shapes: counts, determinism, points on the surface, normals,
// blue-noise quality, areas and volumes against estimates made here independently;
// the random sampler's shares of equal areas, density ramp and neighbour distances.
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <iostream>
#include <random>

namespace {

using pcl::cocone::test::SampledShape;
namespace shapes = pcl::cocone::test;

constexpr double kPi = 3.14159265358979323846;

struct ShapeCase
{
  const char* name;
  SampledShape (*generate)(std::size_t, std::uint32_t);
  bool closed;
  int genus;
  int boundary_loops;
  bool uniform; ///< same density everywhere (blue noise checked in spacings)
  bool has_rim; ///< open shapes and the cube's edges
  bool has_lfs;
};

const ShapeCase kCases[] = {
    {"sphere", shapes::sampleSphere, true, 0, 0, true, false, true},
    {"sphere_dense_cap", shapes::sampleSphereWithDenseCap, true, 0, 0, false, false,
     true},
    {"torus", shapes::sampleTorus, true, 1, 0, true, false, true},
    {"trefoil_knot", shapes::sampleTrefoilKnot, true, 1, 0, true, false, false},
    {"genus3", shapes::sampleGenus3, true, 3, 0, true, false, false},
    {"hemisphere", shapes::sampleHemisphere, false, 0, 1, true, true, false},
    {"monkey_saddle", shapes::sampleMonkeySaddle, false, 0, 1, true, true, false},
    {"open_cylinder", shapes::sampleOpenCylinder, false, 0, 2, true, true, false},
    {"half_cylinder", shapes::sampleHalfCylinder, false, 0, 1, true, true, false},
    {"cube", shapes::sampleCube, true, 0, 0, true, true, false},
};

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

void
boundingBox(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& lo,
            Eigen::Vector3d& hi)
{
  lo = hi = points.front();
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

double
diagonal(const SampledShape& shape)
{
  Eigen::Vector3d lo, hi;
  boundingBox(shape.points, lo, hi);
  return (hi - lo).norm();
}

/** Nearest-neighbour search by brute force over a coarse grid: enough for the few
 * thousand points of these tests, and independent of the generators' own grid. */
class Nearest
{
public:
  Nearest(const std::vector<Eigen::Vector3d>& points, double cell)
    : points_(points), cell_(cell)
  {
    boundingBox(points, lo_, hi_);
    dims_ = ((hi_ - lo_) / cell_).array().floor().cast<int>() + 1;
    buckets_.resize(static_cast<std::size_t>(dims_.prod()));
    for (std::size_t i = 0; i < points.size(); ++i)
      buckets_[index(clampedCell(points[i]))].push_back(i);
  }

  /** Distance from q to the nearest point other than \a skip. */
  double
  distance(const Eigen::Vector3d& q,
           std::size_t skip = static_cast<std::size_t>(-1)) const
  {
    const Eigen::Vector3i c = clampedCell(q);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0;; ++ring) {
      for (int x = c.x() - ring; x <= c.x() + ring; ++x)
        for (int y = c.y() - ring; y <= c.y() + ring; ++y)
          for (int z = c.z() - ring; z <= c.z() + ring; ++z) {
            if (std::max({std::abs(x - c.x()), std::abs(y - c.y()),
                          std::abs(z - c.z())}) != ring)
              continue;
            if (x < 0 || y < 0 || z < 0 || x >= dims_.x() || y >= dims_.y() ||
                z >= dims_.z())
              continue;
            for (const std::size_t i : buckets_[index({x, y, z})])
              if (i != skip)
                best = std::min(best, (points_[i] - q).norm());
          }
      // Cells of this ring cover everything within `ring` cells of q's cell.
      const double outside = std::max(0.0, (q - lo_).cwiseMax(hi_ - q).maxCoeff());
      if (best <= ring * cell_ ||
          ring > dims_.maxCoeff() + static_cast<int>(outside / cell_) + 1)
        return best;
    }
  }

private:
  Eigen::Vector3i
  clampedCell(const Eigen::Vector3d& p) const
  {
    Eigen::Vector3i c = ((p - lo_) / cell_).array().floor().cast<int>();
    return c.cwiseMax(0).cwiseMin(dims_ - Eigen::Vector3i::Ones());
  }
  std::size_t
  index(const Eigen::Vector3i& c) const
  {
    return static_cast<std::size_t>((c.x() * dims_.y() + c.y()) * dims_.z() + c.z());
  }

  const std::vector<Eigen::Vector3d>& points_;
  double cell_;
  Eigen::Vector3d lo_, hi_;
  Eigen::Vector3i dims_;
  std::vector<std::vector<std::size_t>> buckets_;
};

class Shapes : public ::testing::TestWithParam<ShapeCase>
{};

std::string
caseName(const ::testing::TestParamInfo<ShapeCase>& info)
{
  return info.param.name;
}

TEST_P(Shapes, CountsAndFacts)
{
  const ShapeCase& c = GetParam();
  for (const std::size_t n : {std::size_t(1), std::size_t(10), std::size_t(1234)}) {
    const SampledShape s = c.generate(n, 3);
    EXPECT_EQ(s.points.size(), n);
    EXPECT_EQ(s.normals.size(), n);
  }
  const SampledShape s = c.generate(500, 1);
  EXPECT_EQ(s.name, c.name);
  EXPECT_EQ(s.closed, c.closed);
  EXPECT_EQ(s.genus, c.genus);
  EXPECT_EQ(s.boundary_loops, c.boundary_loops);
  EXPECT_GT(s.area, 0);
  EXPECT_NEAR(s.spacing(), std::sqrt(s.area / 500), 1e-12);
  EXPECT_EQ(!s.rim.empty(), c.has_rim);
  EXPECT_EQ(static_cast<bool>(s.local_feature_size), c.has_lfs);
  ASSERT_TRUE(s.distance_to_surface);
  ASSERT_TRUE(s.distance_to_rim);
  EXPECT_TRUE(c.generate(0, 1).points.empty());
}

TEST_P(Shapes, Deterministic)
{
  const ShapeCase& c = GetParam();
  const SampledShape a = c.generate(2000, 7), b = c.generate(2000, 7);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.normals, b.normals);
  const SampledShape other = c.generate(2000, 8);
  EXPECT_NE(a.points, other.points);
}

TEST_P(Shapes, PointsLieOnTheSurface)
{
  const ShapeCase& c = GetParam();
  const SampledShape s = c.generate(5000, 2);
  const double tolerance = 1e-4 * diagonal(s);
  double worst = 0, sum = 0;
  for (const Eigen::Vector3d& p : s.points) {
    const double d = s.distance_to_surface(p);
    worst = std::max(worst, d);
    sum += d;
  }
  EXPECT_LE(worst, tolerance);
  // The jitter is there: points are not exactly on the surface (its amplitude is
  // documented in shapes.h; uniform, so the mean distance is about half of it).
  const double amplitude =
      std::min(1e-5 * diagonal(s), 1e-3 * s.spacing() * s.spacing() / diagonal(s));
  EXPECT_GT(sum / s.points.size(), 0.1 * amplitude);
}

TEST_P(Shapes, NormalsAreUnitAndNormal)
{
  const ShapeCase& c = GetParam();
  const SampledShape s = c.generate(3000, 4);
  const double jitter = 1.01e-5 * diagonal(s);
  // Stepping off along an exact normal moves exactly `step` away (for a step below the
  // feature size); a normal tilted by an angle b gives about step cos b.
  const double step = 0.02;
  double worst_tilt = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    ASSERT_NEAR(s.normals[i].norm(), 1.0, 1e-12);
    const double d = s.distance_to_surface(s.points[i] + step * s.normals[i]);
    worst_tilt = std::max(worst_tilt, std::abs(d - step) - jitter);
  }
  EXPECT_LE(worst_tilt, 1e-3 * step);
}

/** The shapes sampled with the same density everywhere. */
class UniformShapes : public Shapes
{};

std::vector<ShapeCase>
uniformCases()
{
  std::vector<ShapeCase> result;
  for (const ShapeCase& c : kCases)
    if (c.uniform)
      result.push_back(c);
  return result;
}

TEST_P(UniformShapes, BlueNoise)
{
  const ShapeCase& c = GetParam();
  const std::size_t n = 4000;
  const SampledShape s = c.generate(n, 5);
  const double spacing = s.spacing();
  const Nearest nearest(s.points, spacing);

  double min_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    min_distance = std::min(min_distance, nearest.distance(s.points[i], i));

  // Largest gap: probe points drawn uniformly in a thin shell around the surface (by
  // distance_to_surface alone, so that a region the generator misses is found too).
  Eigen::Vector3d lo, hi;
  boundingBox(s.points, lo, hi);
  const double shell = 0.25 * spacing;
  lo.array() -= shell;
  hi.array() += shell;
  Uniform uniform(99);
  double largest_gap = 0;
  std::size_t probes = 0;
  for (std::size_t tries = 0; tries < 3000000 && probes < 20000; ++tries) {
    const Eigen::Vector3d q(uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y()),
                            uniform(lo.z(), hi.z()));
    const double off = s.distance_to_surface(q);
    if (off > shell)
      continue;
    ++probes;
    largest_gap = std::max(largest_gap, nearest.distance(q) - off);
  }
  std::cout << "[ quality  ] " << c.name << ": min distance " << min_distance / spacing
            << " spacing, largest gap " << largest_gap / spacing << " spacing ("
            << probes << " probes)" << std::endl;
  EXPECT_GE(min_distance, 0.5 * spacing);
  EXPECT_GT(probes, 5000u);
  EXPECT_LE(largest_gap, 1.5 * spacing);
}

TEST_P(Shapes, RimAndDistanceToRim)
{
  const ShapeCase& c = GetParam();
  const SampledShape s = c.generate(3000, 6);
  const double spacing = s.spacing();
  if (!c.has_rim) {
    EXPECT_TRUE(std::isinf(s.distance_to_rim(s.points.front())));
    return;
  }
  for (const Eigen::Vector3d& r : s.rim) {
    EXPECT_LT(s.distance_to_rim(r), 1e-9);
    EXPECT_LT(s.distance_to_surface(r), 1e-9);
  }
  // Brute force: the rim is a curve, a poor fit for the grid of Nearest.
  auto nearestRim = [&](const Eigen::Vector3d& q, std::size_t skip) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < s.rim.size(); ++j)
      if (j != skip)
        best = std::min(best, (s.rim[j] - q).norm());
    return best;
  };
  const std::size_t none = s.rim.size();
  for (std::size_t i = 0; i < s.rim.size(); i += 7)
    EXPECT_LE(nearestRim(s.rim[i], i), 0.25 * spacing);
  // Against the rim points: never farther than the rim itself, and at most half the rim
  // step closer.
  for (std::size_t i = 0; i < s.points.size(); i += 5) {
    const double exact = s.distance_to_rim(s.points[i]);
    const double sampled = nearestRim(s.points[i], none);
    EXPECT_LE(exact, sampled + 1e-9);
    EXPECT_GE(exact, sampled - 0.125 * spacing - 1e-9);
  }
}

/** Area of a thin shell {d < h} divided by its thickness 2 h: the area of a closed
 * smooth surface up to O(h^2) (Steiner's formula), estimated by Monte Carlo. */
double
shellArea(const SampledShape& s, double h, std::size_t tries)
{
  Eigen::Vector3d lo, hi;
  boundingBox(s.points, lo, hi);
  lo.array() -= 2 * h;
  hi.array() += 2 * h;
  Uniform uniform(4242);
  std::size_t inside = 0;
  for (std::size_t i = 0; i < tries; ++i) {
    const Eigen::Vector3d q(uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y()),
                            uniform(lo.z(), hi.z()));
    inside += s.distance_to_surface(q) < h;
  }
  return (hi - lo).prod() * static_cast<double>(inside) / static_cast<double>(tries) /
         (2 * h);
}

TEST(ShapeArea, ClosedForms)
{
  EXPECT_NEAR(shapes::sampleSphere(10).area, 4 * kPi, 1e-12);
  EXPECT_NEAR(shapes::sampleSphereWithDenseCap(10).area, 4 * kPi, 1e-12);
  EXPECT_NEAR(shapes::sampleTorus(10).area, 4 * kPi * kPi * 0.35, 1e-12);
  EXPECT_NEAR(shapes::sampleHemisphere(10).area, 2 * kPi, 1e-12);
  EXPECT_NEAR(shapes::sampleOpenCylinder(10).area, 2 * kPi * 0.5 * 2, 1e-12);
  EXPECT_NEAR(shapes::sampleCube(10).area, 24, 1e-12);
}

TEST(ShapeArea, MonkeySaddleByQuadrature)
{
  // Midpoint rule in polar coordinates with the area element from finite differences.
  auto height = [](double x, double y) { return x * x * x - 3 * x * y * y; };
  const int nr = 600, na = 600;
  const double e = 1e-6;
  double area = 0;
  for (int i = 0; i < nr; ++i)
    for (int j = 0; j < na; ++j) {
      const double r = (i + 0.5) / nr, a = 2 * kPi * (j + 0.5) / na;
      const double x = r * std::cos(a), y = r * std::sin(a);
      const double hx = (height(x + e, y) - height(x - e, y)) / (2 * e);
      const double hy = (height(x, y + e) - height(x, y - e)) / (2 * e);
      area += std::sqrt(1 + hx * hx + hy * hy) * r * (1.0 / nr) * (2 * kPi / na);
    }
  EXPECT_NEAR(shapes::sampleMonkeySaddle(10).area / area, 1.0, 1e-3);
}

TEST(ShapeArea, TrefoilKnotByQuadrature)
{
  // The tube around the curve with the frame (z projected off the tangent; the tangent
  // is never vertical), area element |X_t x X_phi| by finite differences.
  auto curve = [](double t) {
    return Eigen::Vector3d(std::sin(t) + 2 * std::sin(2 * t),
                           std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t));
  };
  auto tube = [&](double t, double phi) {
    const Eigen::Vector3d tangent = (curve(t + 1e-6) - curve(t - 1e-6)).normalized();
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d e1 = (z - z.dot(tangent) * tangent).normalized();
    const Eigen::Vector3d e2 = tangent.cross(e1);
    return Eigen::Vector3d(curve(t) + 0.25 * (std::cos(phi) * e1 + std::sin(phi) * e2));
  };
  const int nt = 2000, np = 64;
  const double e = 1e-5;
  double area = 0;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      const double t = 2 * kPi * i / nt, phi = 2 * kPi * j / np;
      const Eigen::Vector3d xt = (tube(t + e, phi) - tube(t - e, phi)) / (2 * e);
      const Eigen::Vector3d xp = (tube(t, phi + e) - tube(t, phi - e)) / (2 * e);
      area += xt.cross(xp).norm() * (2 * kPi / nt) * (2 * kPi / np);
    }
  EXPECT_NEAR(shapes::sampleTrefoilKnot(10).area / area, 1.0, 1e-3);
}

TEST(ShapeArea, Genus3ByShellVolume)
{
  const SampledShape s = shapes::sampleGenus3(2000);
  const double estimate = shellArea(s, 0.05, 2000000);
  EXPECT_NEAR(s.area / estimate, 1.0, 0.01);
  // Cross-check of the estimator on a shape with a closed form.
  const SampledShape torus = shapes::sampleTorus(2000);
  EXPECT_NEAR(shellArea(torus, 0.05, 1000000) / torus.area, 1.0, 0.01);
}

TEST(ShapeVolume, DivergenceTheoremOnTheSamples)
{
  // For a uniform sample of a closed surface, area / n * sum p.n estimates
  // int p.n dA = 3 V: checks that normals point outward and that the sample covers the
  // surface evenly.
  auto volume = [](const SampledShape& s) {
    double sum = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i)
      sum += s.points[i].dot(s.normals[i]);
    return s.area / static_cast<double>(s.points.size()) * sum / 3;
  };
  const std::size_t n = 20000;
  EXPECT_NEAR(volume(shapes::sampleSphere(n)) / (4 * kPi / 3), 1.0, 0.01);
  EXPECT_NEAR(volume(shapes::sampleTorus(n)) / (2 * kPi * kPi * 0.35 * 0.35), 1.0,
              0.01);
  EXPECT_NEAR(volume(shapes::sampleCube(n)) / 8, 1.0, 0.01);

  // Knot: a tube of radius r around a curve of length L encloses pi r^2 L.
  double length = 0;
  for (int i = 0; i < 20000; ++i) {
    const double t = 2 * kPi * i / 20000;
    length += Eigen::Vector3d(std::cos(t) + 4 * std::cos(2 * t),
                              -std::sin(t) + 4 * std::sin(2 * t), -3 * std::cos(3 * t))
                  .norm() *
              (2 * kPi / 20000);
  }
  EXPECT_NEAR(volume(shapes::sampleTrefoilKnot(n)) / (kPi * 0.0625 * length), 1.0,
              0.01);

  // Genus 3: a slab of thickness 2 R over the planar region P, plus a half round of
  // radius R along P's boundary (Pappus: its centroid is 4 R / (3 pi) out, so the
  // boundary's total curvature, 2 pi - 3 * 2 pi, enters).
  const double R = 0.25, L = 1.1, W = 0.6, rho = 0.5;
  const double plane = 4 * L * W + kPi * W * W - 3 * kPi * rho * rho;
  const double perimeter = 4 * L + 2 * kPi * W + 3 * 2 * kPi * rho;
  const double slab = 2 * R * plane + 0.5 * kPi * R * R * perimeter +
                      0.5 * kPi * R * R * (4 * R / (3 * kPi)) * (2 * kPi - 6 * kPi);
  EXPECT_NEAR(volume(shapes::sampleGenus3(n)) / slab, 1.0, 0.01);
}

TEST(ShapeTopology, Genus3HasThreeOpenHoles)
{
  // The vertical axis of each hole stays clear of the surface, while the surface passes
  // all around it: the sample has points in every direction from the axis.
  const SampledShape s = shapes::sampleGenus3(5000);
  for (const double cx : {-1.1, 0.0, 1.1}) {
    for (double z = -1; z <= 1; z += 0.05)
      EXPECT_GT(s.distance_to_surface(Eigen::Vector3d(cx, 0, z)), 0.24);
    std::vector<int> sectors(8, 0);
    for (const Eigen::Vector3d& p : s.points) {
      const double r = std::hypot(p.x() - cx, p.y());
      EXPECT_GT(r, 0.24);
      if (r < 0.5 && std::abs(p.z()) < 0.06) {
        const double a = std::atan2(p.y(), p.x() - cx) + kPi;
        ++sectors[std::min(7, static_cast<int>(a / (2 * kPi) * 8))];
      }
    }
    for (const int count : sectors)
      EXPECT_GT(count, 0) << "hole at x = " << cx;
  }
}

TEST(ShapeDensity, DenseCapIsEightTimesDenser)
{
  const SampledShape s = shapes::sampleSphereWithDenseCap(20000);
  // Away from the cap's edge at 40 degrees, where the density jumps.
  const double inner = std::cos(35 * kPi / 180), outer = std::cos(45 * kPi / 180);
  std::size_t cap = 0, rest = 0;
  for (const Eigen::Vector3d& p : s.points) {
    const double z = p.z() / p.norm();
    cap += z > inner;
    rest += z < outer;
  }
  const double cap_area = 2 * kPi * (1 - inner), rest_area = 2 * kPi * (1 + outer);
  const double ratio = (cap / cap_area) / (rest / rest_area);
  std::cout << "[ quality  ] dense cap: density ratio " << ratio << std::endl;
  EXPECT_NEAR(ratio, 8.0, 2.0);
}

TEST(ShapeDensity, DenseCapIsBlueNoiseOnBothSides)
{
  // Each side measured in its own spacing: the area per point at its density.
  const std::size_t n = 6000;
  const SampledShape s = shapes::sampleSphereWithDenseCap(n, 5);
  const double edge = std::cos(40 * kPi / 180);
  const double weighted_area = 8 * 2 * kPi * (1 - edge) + 2 * kPi * (1 + edge);
  const double sparse = std::sqrt(weighted_area / n), dense = sparse / std::sqrt(8.0);
  const Nearest nearest(s.points, dense);
  double cap_min = std::numeric_limits<double>::infinity(), rest_min = cap_min;
  for (std::size_t i = 0; i < n; ++i) {
    const double z = s.points[i].z() / s.points[i].norm();
    const double d = nearest.distance(s.points[i], i);
    if (z > std::cos(35 * kPi / 180))
      cap_min = std::min(cap_min, d);
    else if (z < std::cos(45 * kPi / 180))
      rest_min = std::min(rest_min, d);
  }
  // Largest gaps, probed on a grid of directions (the exact sphere).
  double cap_gap = 0, rest_gap = 0;
  const int rings = 200, sectors = 400;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double z = -1 + 2 * (i + 0.5) / rings, a = 2 * kPi * (j + 0.5) / sectors;
      const double r = std::sqrt(1 - z * z);
      const double d =
          nearest.distance(Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z));
      if (z > std::cos(35 * kPi / 180))
        cap_gap = std::max(cap_gap, d);
      else if (z < std::cos(45 * kPi / 180))
        rest_gap = std::max(rest_gap, d);
    }
  std::cout << "[ quality  ] dense cap: min distance " << cap_min / dense << " / "
            << rest_min / sparse << " local spacing (cap / rest), largest gap "
            << cap_gap / dense << " / " << rest_gap / sparse << std::endl;
  EXPECT_GE(cap_min, 0.5 * dense);
  EXPECT_GE(rest_min, 0.5 * sparse);
  EXPECT_LE(cap_gap, 1.5 * dense);
  EXPECT_LE(rest_gap, 1.5 * sparse);
}

TEST(ShapeFeatureSize, SphereAndTorus)
{
  const SampledShape sphere = shapes::sampleSphere(100);
  const SampledShape torus = shapes::sampleTorus(100);
  for (const Eigen::Vector3d& p : sphere.points)
    EXPECT_NEAR(sphere.local_feature_size(p), 1.0, 1e-12);
  // Every torus point is 0.35 from the core circle (its medial axis inside) and at
  // least 0.65 from the z axis (the medial axis outside).
  for (const Eigen::Vector3d& p : torus.points) {
    const double to_core = std::hypot(std::hypot(p.x(), p.y()) - 1, p.z());
    const double to_axis = std::hypot(p.x(), p.y());
    EXPECT_NEAR(torus.local_feature_size(p), std::min(to_core, to_axis), 1e-4);
  }
}

// --- Area-uniform random samples (sampleRandom) -----------------------------------

/** Whether \a count of \a n independent draws is within 5 standard deviations of the
 * binomial mean for probability \a p. */
::testing::AssertionResult
binomialCountFits(std::size_t count, std::size_t n, double p)
{
  const double mean = p * static_cast<double>(n);
  const double sigma = std::sqrt(mean * (1 - p));
  if (std::abs(static_cast<double>(count) - mean) <= 5 * sigma)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << count << " of " << n << ", expected " << mean << " +- 5 x " << sigma;
}

TEST(RandomShapes, CountsDeterminismAndPointsOnTheSurface)
{
  for (const shapes::Shape which : shapes::allShapes()) {
    const SampledShape shape = shapes::sampleRandom(which, 3000, 4);
    SCOPED_TRACE(shape.name);
    ASSERT_EQ(shape.points.size(), 3000u);
    ASSERT_EQ(shape.normals.size(), 3000u);
    const SampledShape again = shapes::sampleRandom(which, 3000, 4);
    EXPECT_EQ(again.points, shape.points);
    EXPECT_NE(shapes::sampleRandom(which, 3000, 5).points, shape.points);
    // The facts are those of the blue-noise generator.
    const SampledShape blue = [&] {
      switch (which) {
      case shapes::Shape::sphere:
        return shapes::sampleSphere(10);
      case shapes::Shape::torus:
        return shapes::sampleTorus(10);
      case shapes::Shape::trefoil_knot:
        return shapes::sampleTrefoilKnot(10);
      case shapes::Shape::genus3:
        return shapes::sampleGenus3(10);
      case shapes::Shape::cube:
        return shapes::sampleCube(10);
      case shapes::Shape::hemisphere:
        return shapes::sampleHemisphere(10);
      case shapes::Shape::open_cylinder:
        return shapes::sampleOpenCylinder(10);
      case shapes::Shape::half_cylinder:
        return shapes::sampleHalfCylinder(10);
      case shapes::Shape::monkey_saddle:
        return shapes::sampleMonkeySaddle(10);
      }
      return SampledShape();
    }();
    EXPECT_EQ(shape.name, blue.name);
    EXPECT_EQ(shape.area, blue.area);
    EXPECT_EQ(shape.closed, blue.closed);
    EXPECT_EQ(shape.genus, blue.genus);
    EXPECT_EQ(shape.boundary_loops, blue.boundary_loops);
    // On the surface up to the jitter: 1e-5 of a diagonal below 7.
    double worst = 0, worst_normal = 0;
    for (std::size_t i = 0; i < shape.points.size(); ++i) {
      worst = std::max(worst, shape.distance_to_surface(shape.points[i]));
      worst_normal = std::max(worst_normal, std::abs(shape.normals[i].norm() - 1));
    }
    EXPECT_LT(worst, 1e-4);
    EXPECT_LT(worst_normal, 1e-9);
  }
}

// Sets of equal area get binomial shares of the points: slabs of equal height on the
// sphere (Archimedes) and on the cylinders, the outer and inner halves of the torus
// (their areas differ by the curvature term), the faces of the cube.
TEST(RandomShapes, AreEqualAreasGetEqualShares)
{
  const std::size_t n = 100000;
  constexpr int kSlabs = 10;
  const SampledShape sphere = shapes::sampleRandom(shapes::Shape::sphere, n, 7);
  std::vector<std::size_t> slab(kSlabs, 0);
  for (const Eigen::Vector3d& p : sphere.points)
    ++slab[std::min(kSlabs - 1, static_cast<int>((p.z() + 1) / 2 * kSlabs))];
  for (int k = 0; k < kSlabs; ++k)
    EXPECT_TRUE(binomialCountFits(slab[k], n, 1.0 / kSlabs)) << "sphere slab " << k;

  for (const shapes::Shape which :
       {shapes::Shape::open_cylinder, shapes::Shape::half_cylinder}) {
    const SampledShape cylinder = shapes::sampleRandom(which, n, 8);
    std::vector<std::size_t> by_height(kSlabs, 0), by_angle(kSlabs, 0);
    const double sector = which == shapes::Shape::open_cylinder ? 2 * kPi : kPi;
    for (const Eigen::Vector3d& p : cylinder.points) {
      ++by_height[std::min(kSlabs - 1, static_cast<int>((p.z() + 1) / 2 * kSlabs))];
      double angle = std::atan2(p.y(), p.x());
      if (angle < 0)
        angle += 2 * kPi;
      ++by_angle[std::min(kSlabs - 1, static_cast<int>(angle / sector * kSlabs))];
    }
    for (int k = 0; k < kSlabs; ++k) {
      EXPECT_TRUE(binomialCountFits(by_height[k], n, 1.0 / kSlabs)) << cylinder.name;
      EXPECT_TRUE(binomialCountFits(by_angle[k], n, 1.0 / kSlabs)) << cylinder.name;
    }
  }

  // Torus (R = 1, r = 0.35): the outer half (cos v > 0) has the share
  // (pi R + 2 r) / (2 pi R).
  const SampledShape torus = shapes::sampleRandom(shapes::Shape::torus, n, 9);
  std::size_t outer = 0;
  for (const Eigen::Vector3d& p : torus.points)
    outer += std::hypot(p.x(), p.y()) > 1;
  EXPECT_TRUE(binomialCountFits(outer, n, (kPi + 2 * 0.35) / (2 * kPi)));

  const SampledShape cube = shapes::sampleRandom(shapes::Shape::cube, n, 10);
  std::vector<std::size_t> faces(6, 0);
  for (const Eigen::Vector3d& p : cube.points) {
    int axis;
    p.cwiseAbs().maxCoeff(&axis);
    ++faces[2 * axis + (p[axis] > 0)];
  }
  for (int f = 0; f < 6; ++f)
    EXPECT_TRUE(binomialCountFits(faces[f], n, 1.0 / 6)) << "cube face " << f;
}

// The density ramp: density 8^t along x. On the sphere every slab of x has the same
// area, so the last tenth of the x extent holds 8^0.9 times the points of the first.
TEST(RandomShapes, DensityRampIsEightfoldAcrossTheSurface)
{
  const std::size_t n = 100000;
  const SampledShape sphere = shapes::sampleRandom(shapes::Shape::sphere, n, 11, true);
  ASSERT_EQ(sphere.points.size(), n);
  std::size_t first = 0, last = 0;
  for (const Eigen::Vector3d& p : sphere.points) {
    first += p.x() < -0.8;
    last += p.x() > 0.8;
  }
  const double ratio = static_cast<double>(last) / static_cast<double>(first);
  std::cout << "[ random   ] density ramp: last / first tenth of x = " << ratio
            << " (expected 8^0.9 = " << std::pow(8.0, 0.9) << ")" << std::endl;
  EXPECT_NEAR(ratio, std::pow(8.0, 0.9), 0.1 * std::pow(8.0, 0.9));
  // The share of the first tenth: int_0^0.1 8^t dt / int_0^1 8^t dt.
  const double share = (std::pow(8.0, 0.1) - 1) / 7;
  EXPECT_TRUE(binomialCountFits(first, n, share));
}

// Random samples are not blue noise: their nearest neighbours are about half a
// spacing away on average (a planar Poisson process: 1 / (2 sqrt(density))), where
// blue noise keeps them near one spacing.
TEST(RandomShapes, NearestNeighboursAreThoseOfAPoissonSample)
{
  const std::size_t n = 20000;
  const SampledShape cylinder =
      shapes::sampleRandom(shapes::Shape::open_cylinder, n, 12);
  // Sorted by z, the nearest neighbour is found within a window of z.
  std::vector<Eigen::Vector3d> points = cylinder.points;
  std::sort(
      points.begin(), points.end(),
      [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.z() < b.z(); });
  const double spacing = cylinder.spacing();
  double sum = 0;
  std::size_t counted = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Away from the rims, whose samples have neighbours on one side only.
    if (std::abs(points[i].z()) > 1 - 5 * spacing)
      continue;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = i + 1;
         j < points.size() && points[j].z() - points[i].z() < best; ++j)
      best = std::min(best, (points[j] - points[i]).norm());
    for (std::size_t j = i; j-- > 0 && points[i].z() - points[j].z() < best;)
      best = std::min(best, (points[j] - points[i]).norm());
    sum += best;
    ++counted;
  }
  const double mean = sum / static_cast<double>(counted) / spacing;
  std::cout << "[ random   ] mean nearest-neighbour distance: " << mean << " spacing"
            << std::endl;
  EXPECT_NEAR(mean, 0.5, 0.02);
}

INSTANTIATE_TEST_SUITE_P(All, Shapes, ::testing::ValuesIn(kCases), caseName);
INSTANTIATE_TEST_SUITE_P(All, UniformShapes, ::testing::ValuesIn(uniformCases()),
                         caseName);

} // namespace
