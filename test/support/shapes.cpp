// SPDX-License-Identifier: GPL-3.0-or-later
//
// Blue-noise samples of analytic surfaces. Every generator draws about 5 n candidates
// uniformly by area (or by a prescribed density) and thins them to exactly n points
// with weighted sample elimination (C. Yuksel, "Sample Elimination for Generating
// Poisson Disk Sample Sets", Computer Graphics Forum 34(2), 2015). sampleRandom keeps
// the draws themselves instead, n of them, as a scanner's samples are spread: close
// pairs and wide gaps (sampleRandomly).
#include "support/shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

namespace pcl {
namespace cocone {
namespace test {

double
SampledShape::spacing() const
{
  if (points.empty())
    return std::numeric_limits<double>::infinity();
  return std::sqrt(area / static_cast<double>(points.size()));
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------
// Random numbers. std::mt19937 is specified bit for bit by the standard, the
// distributions are not, so the mapping to doubles is done here.
class Random
{
public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}

  /** Uniform in [0, 1) with 53 random bits. */
  double
  uniform()
  {
    const std::uint64_t high = engine_() >> 5; // 27 bits
    const std::uint64_t low = engine_() >> 6;  // 26 bits
    return static_cast<double>((high << 26) | low) * (1.0 / 9007199254740992.0);
  }

  double
  uniform(double lo, double hi)
  {
    return lo + (hi - lo) * uniform();
  }

  /** Uniform index in [0, n). */
  std::size_t
  index(std::size_t n)
  {
    return std::min(n - 1,
                    static_cast<std::size_t>(uniform() * static_cast<double>(n)));
  }

private:
  std::mt19937 engine_;
};

// ---------------------------------------------------------------------------------
// Uniform grid hash. The points are stored sorted along a Morton curve of their cells,
// so the points of a cell are contiguous and neighbouring cells mostly close in memory;
// the occupied cells are found through an open-addressing table, so memory follows
// their number (the points lie on a surface: most cells of the bounding box are empty).
class GridHash
{
public:
  GridHash(const std::vector<Eigen::Vector3d>& points, double cell_size)
    : inverse_cell_(1.0 / cell_size)
  {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      keyed[i] = {keyOf(cellOf(points[i])), static_cast<std::uint32_t>(i)};
    std::sort(keyed.begin(), keyed.end());
    points_.resize(points.size());
    original_.resize(points.size());
    for (std::size_t k = 0; k < keyed.size(); ++k) {
      original_[k] = keyed[k].second;
      points_[k] = points[keyed[k].second];
    }

    // Occupied cells in Morton order, found again through an open-addressing table
    // to link each cell to its occupied neighbours once (CSR), instead of hashing 27
    // cells for every query.
    std::vector<std::uint64_t> cell_keys;
    for (std::size_t k = 0; k < keyed.size(); ++k) {
      if (k == 0 || keyed[k].first != keyed[k - 1].first) {
        cell_keys.push_back(keyed[k].first);
        cell_begin_.push_back(static_cast<std::uint32_t>(k));
      }
      cell_of_.push_back(static_cast<std::uint32_t>(cell_keys.size() - 1));
    }
    cell_begin_.push_back(static_cast<std::uint32_t>(keyed.size()));

    std::size_t capacity = 16;
    while (capacity < 2 * cell_keys.size())
      capacity *= 2;
    const std::size_t mask = capacity - 1;
    auto hash = [mask](std::uint64_t key) {
      return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & mask;
    };
    constexpr std::uint32_t kEmpty = ~std::uint32_t(0);
    std::vector<std::uint32_t> slots(capacity, kEmpty);
    for (std::size_t c = 0; c < cell_keys.size(); ++c) {
      std::size_t s = hash(cell_keys[c]);
      while (slots[s] != kEmpty)
        s = (s + 1) & mask;
      slots[s] = static_cast<std::uint32_t>(c);
    }
    neighbour_begin_.push_back(0);
    for (std::size_t c = 0; c < cell_keys.size(); ++c) {
      const std::array<std::int64_t, 3> centre = cellOf(points_[cell_begin_[c]]);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const std::uint64_t key =
                keyOf({centre[0] + dx, centre[1] + dy, centre[2] + dz});
            for (std::size_t s = hash(key); slots[s] != kEmpty; s = (s + 1) & mask)
              if (cell_keys[slots[s]] == key) {
                neighbours_.push_back(slots[s]);
                break;
              }
          }
      neighbour_begin_.push_back(static_cast<std::uint32_t>(neighbours_.size()));
    }
  }

  std::size_t
  size() const
  {
    return points_.size();
  }

  /** The point stored at position k (positions follow the Morton order). */
  const Eigen::Vector3d&
  point(std::size_t k) const
  {
    return points_[k];
  }

  /** The index, in the constructor's input, of the point at position k. */
  std::uint32_t
  original(std::size_t k) const
  {
    return original_[k];
  }

  /** Calls visit(j) for the position j of every point in the 27 cells around the
   * point at position k (k included): all points within one cell size of it, and
   * some farther ones. */
  template <typename Visit>
  void
  visitNear(std::size_t k, Visit&& visit) const
  {
    const std::uint32_t c = cell_of_[k];
    for (std::uint32_t n = neighbour_begin_[c]; n < neighbour_begin_[c + 1]; ++n) {
      const std::uint32_t cell = neighbours_[n];
      for (std::uint32_t j = cell_begin_[cell]; j < cell_begin_[cell + 1]; ++j)
        visit(j);
    }
  }

private:
  std::array<std::int64_t, 3>
  cellOf(const Eigen::Vector3d& p) const
  {
    return {static_cast<std::int64_t>(std::floor(p.x() * inverse_cell_)),
            static_cast<std::int64_t>(std::floor(p.y() * inverse_cell_)),
            static_cast<std::int64_t>(std::floor(p.z() * inverse_cell_))};
  }

  /** Spreads the low 21 bits of x to every third bit. */
  static std::uint64_t
  spread(std::uint64_t x)
  {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
  }

  /** Morton code of a cell (coordinates wrap modulo 2^21, far beyond the extents). */
  static std::uint64_t
  keyOf(const std::array<std::int64_t, 3>& c)
  {
    const std::int64_t offset = std::int64_t(1) << 20;
    return spread(static_cast<std::uint64_t>(c[0] + offset)) << 2 |
           spread(static_cast<std::uint64_t>(c[1] + offset)) << 1 |
           spread(static_cast<std::uint64_t>(c[2] + offset));
  }

  double inverse_cell_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::uint32_t> original_;
  std::vector<std::uint32_t> cell_of_;         // position -> cell
  std::vector<std::uint32_t> cell_begin_;      // cell -> first position (CSR)
  std::vector<std::uint32_t> neighbour_begin_; // cell -> first neighbour (CSR)
  std::vector<std::uint32_t> neighbours_;      // occupied cells of the 3x3x3 block
};

// ---------------------------------------------------------------------------------
// Weighted sample elimination.

/** Max-heap of samples keyed by weight, with every sample's place in it so that a
 * weight can be lowered in place. Four children per node and the keys stored in the
 * nodes: fewer levels and fewer cache misses than a binary heap of indices. Ties go
 * to the smaller index: deterministic. */
class EliminationHeap
{
public:
  explicit EliminationHeap(const std::vector<double>& weight)
    : nodes_(weight.size()), place_(weight.size())
  {
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      nodes_[i] = Node{weight[i], static_cast<std::uint32_t>(i)};
    for (std::size_t i = nodes_.size(); i-- > 0;)
      siftDown(i);
  }

  std::uint32_t
  pop()
  {
    const std::uint32_t top = nodes_.front().sample;
    nodes_.front() = nodes_.back();
    nodes_.pop_back();
    if (!nodes_.empty())
      siftDown(0);
    return top;
  }

  /** Lowers the weight of \a sample to \a weight. */
  void
  lower(std::uint32_t sample, double weight)
  {
    const std::size_t at = place_[sample];
    nodes_[at].weight = weight;
    siftDown(at);
  }

private:
  struct Node
  {
    double weight;
    std::uint32_t sample;
  };

  static bool
  above(const Node& a, const Node& b)
  {
    return a.weight > b.weight || (a.weight == b.weight && a.sample < b.sample);
  }

  void
  siftDown(std::size_t at)
  {
    const Node moving = nodes_[at];
    const std::size_t size = nodes_.size();
    for (;;) {
      const std::size_t first = 4 * at + 1;
      if (first >= size)
        break;
      std::size_t best = first;
      const std::size_t last = std::min(first + 4, size);
      for (std::size_t c = first + 1; c < last; ++c)
        if (above(nodes_[c], nodes_[best]))
          best = c;
      if (!above(nodes_[best], moving))
        break;
      nodes_[at] = nodes_[best];
      place_[nodes_[at].sample] = static_cast<std::uint32_t>(at);
      at = best;
    }
    nodes_[at] = moving;
    place_[moving.sample] = static_cast<std::uint32_t>(at);
  }

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> place_;
};

/** Indices (ascending) of the \a n candidates kept by weighted sample elimination.
 * \a radius holds each candidate's r_max: the Poisson disc radius of a hexagonal
 * packing at the target density there. A pair interacts within twice the smaller of
 * the two radii, so that a dense region does not erode its sparser neighbour. */
std::vector<std::uint32_t>
eliminateSamples(const std::vector<Eigen::Vector3d>& candidates,
                 const std::vector<double>& radius, std::size_t n)
{
  const std::size_t m = candidates.size();
  std::vector<std::uint32_t> kept;
  if (n >= m) {
    for (std::size_t i = 0; i < m; ++i)
      kept.push_back(static_cast<std::uint32_t>(i));
    return kept;
  }
  // Yuksel's weight limit: distances below 2 r_min weigh as 2 r_min, which keeps the
  // elimination from spending itself on the few very close pairs of the candidates.
  const double min_ratio =
      0.65 * (1.0 - std::pow(static_cast<double>(n) / static_cast<double>(m), 1.5));
  const double max_radius = *std::max_element(radius.begin(), radius.end());
  // Everything below works on grid positions, for memory locality.
  const GridHash grid(candidates, 2 * max_radius);
  std::vector<double> r(m);
  for (std::size_t k = 0; k < m; ++k)
    r[k] = radius[grid.original(k)];

  // w_ij = (1 - d_ij / (2 r))^alpha with the paper's alpha = 8.
  auto pairWeight = [&](std::size_t i, std::size_t j) {
    const double reach = 2 * std::min(r[i], r[j]);
    const double squared = (grid.point(i) - grid.point(j)).squaredNorm();
    if (squared >= reach * reach)
      return 0.0;
    const double t = 1.0 - std::max(std::sqrt(squared), reach * min_ratio) / reach;
    const double t2 = t * t, t4 = t2 * t2;
    return t4 * t4;
  };

  std::vector<double> weight(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    double sum = 0;
    grid.visitNear(i, [&](std::size_t j) {
      if (j != i)
        sum += pairWeight(i, j);
    });
    weight[i] = sum;
  }

  std::vector<std::uint8_t> alive(m, 1);
  EliminationHeap heap(weight);
  for (std::size_t remaining = m; remaining > n; --remaining) {
    const std::uint32_t i = heap.pop();
    alive[i] = 0;
    grid.visitNear(i, [&](std::size_t j) {
      if (!alive[j])
        return;
      const double w = pairWeight(i, j);
      if (w > 0)
        heap.lower(static_cast<std::uint32_t>(j), weight[j] -= w);
    });
  }
  for (std::size_t k = 0; k < m; ++k)
    if (alive[k])
      kept.push_back(grid.original(k));
  std::sort(kept.begin(), kept.end());
  return kept;
}

/** Draws one candidate point with its unit normal. */
using Draw = std::function<void(Random&, Eigen::Vector3d&, Eigen::Vector3d&)>;

/** Fills shape.points and shape.normals: 5 n candidates from \a draw (distributed with
 * density proportional to \a density, uniform when empty), weighted sample elimination
 * down to n, normal jitter. \a weighted_area is the integral of the density over the
 * surface (the area when uniform). */
/** How a generator spreads its points (see shapes.h). */
struct Spread
{
  bool random = false;       ///< area-uniform random; blue noise otherwise
  bool density_ramp = false; ///< (random only) density 1 to 8 along x
};

constexpr double kRampRatio = 8; ///< densest over sparsest, with density_ramp

/** Fills shape.points and shape.normals with n independent draws, each kept with
 * probability proportional to the density ramp when it is on, and the normal jitter
 * of random samples. */
void
sampleRandomly(SampledShape& shape, std::size_t n, std::uint32_t seed,
               const Spread& spread, const Draw& draw)
{
  Random random(seed);
  Eigen::Vector3d p, normal;
  // The ramp runs along x over the shape's extent, measured on a pilot draw (its ends
  // may fall a little short of the true extent: the density is clamped there).
  double lo_x = 0, hi_x = 1;
  if (spread.density_ramp) {
    lo_x = std::numeric_limits<double>::infinity();
    hi_x = -lo_x;
    for (int k = 0; k < 4096; ++k) {
      draw(random, p, normal);
      lo_x = std::min(lo_x, p.x());
      hi_x = std::max(hi_x, p.x());
    }
  }
  const auto keep = [&](const Eigen::Vector3d& q) {
    if (!spread.density_ramp)
      return true;
    const double t = std::clamp((q.x() - lo_x) / (hi_x - lo_x), 0.0, 1.0);
    // density 8^t, relative to its largest value 8
    return random.uniform() < std::pow(kRampRatio, t - 1);
  };
  std::vector<Eigen::Vector3d> normals;
  shape.points.reserve(n);
  normals.reserve(n);
  while (shape.points.size() < n) {
    draw(random, p, normal);
    if (!keep(p))
      continue;
    shape.points.push_back(p);
    normals.push_back(normal);
  }
  Eigen::Vector3d lo = shape.points.front(), hi = lo;
  for (const Eigen::Vector3d& q : shape.points) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  // Exact samples of an analytic surface are nearly co-spherical in many places, which
  // makes Delaunay slow; a jitter of 1e-5 of the diagonal (a scanner's noise is larger)
  // is enough. Random samples come close to each other anyway, so the blue-noise
  // bound on the jitter (against moving deep Voronoi vertices) has nothing to protect.
  const double jitter = 1e-5 * (hi - lo).norm();
  for (std::size_t i = 0; i < n; ++i)
    shape.points[i] += random.uniform(-jitter, jitter) * normals[i];
  shape.normals = std::move(normals);
}

void
sampleSurface(SampledShape& shape, std::size_t n, std::uint32_t seed,
              const Spread& spread, const Draw& draw, double weighted_area,
              const std::function<double(const Eigen::Vector3d&)>& density = {})
{
  shape.points.clear();
  shape.normals.clear();
  if (n == 0)
    return;
  if (spread.random) {
    sampleRandomly(shape, n, seed, spread, draw);
    return;
  }
  Random random(seed);
  const std::size_t m = 5 * n;
  std::vector<Eigen::Vector3d> points(m), normals(m);
  for (std::size_t i = 0; i < m; ++i)
    draw(random, points[i], normals[i]);

  const double base_radius =
      std::sqrt(weighted_area / (2.0 * std::sqrt(3.0) * static_cast<double>(n)));
  std::vector<double> radius(m, base_radius);
  if (density)
    for (std::size_t i = 0; i < m; ++i)
      radius[i] = base_radius / std::sqrt(density(points[i]));

  const std::vector<std::uint32_t> kept = eliminateSamples(points, radius, n);
  Eigen::Vector3d lo = points[kept.front()], hi = lo;
  for (const std::uint32_t i : kept) {
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  // Voronoi vertices deep inside a shape sit where many bisector planes meet at small
  // angles, so a jitter e moves them by about e * diagonal / spacing^2: keep that
  // small (it would otherwise bias the heights the tests compare with the feature
  // size), while still far above rounding so that no four points are co-spherical.
  const double diagonal = (hi - lo).norm();
  const double spacing = std::sqrt(weighted_area / static_cast<double>(n));
  const double jitter = std::min(1e-5 * diagonal, 1e-3 * spacing * spacing / diagonal);
  shape.points.reserve(n);
  shape.normals.reserve(n);
  for (const std::uint32_t i : kept) {
    shape.points.push_back(points[i] + random.uniform(-jitter, jitter) * normals[i]);
    shape.normals.push_back(normals[i]);
  }
}

/** Number of points for a rim curve of length at most \a length: spacing / 4 apart. */
std::size_t
rimCount(double length, const SampledShape& shape)
{
  const double step = 0.25 * shape.spacing();
  if (!std::isfinite(step) || step <= 0)
    return 64;
  return std::max<std::size_t>(64, static_cast<std::size_t>(std::ceil(length / step)));
}

void
addCircle(std::vector<Eigen::Vector3d>& rim, double radius, double z, std::size_t count)
{
  for (std::size_t k = 0; k < count; ++k) {
    const double a = 2 * kPi * static_cast<double>(k) / static_cast<double>(count);
    rim.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
  }
}

/** Points stored coordinate by coordinate, for a cache-friendly brute-force nearest
 * search over a few hundred points. */
class PointTable
{
public:
  void
  add(const Eigen::Vector3d& p)
  {
    x_.push_back(p.x());
    y_.push_back(p.y());
    z_.push_back(p.z());
  }

  std::size_t
  size() const
  {
    return x_.size();
  }

  /** Index of the point nearest to \a q (the table must not be empty). */
  std::size_t
  nearest(const Eigen::Vector3d& q, double& squared_distance) const
  {
    std::size_t best = 0;
    double best_squared = kInfinity;
    const double qx = q.x(), qy = q.y(), qz = q.z();
    for (std::size_t k = 0; k < x_.size(); ++k) {
      const double dx = x_[k] - qx, dy = y_[k] - qy, dz = z_[k] - qz;
      const double s = dx * dx + dy * dy + dz * dz;
      if (s < best_squared) {
        best_squared = s;
        best = k;
      }
    }
    squared_distance = best_squared;
    return best;
  }

private:
  std::vector<double> x_, y_, z_;
};

/** A point of a parametric curve with its first two derivatives. */
struct CurvePoint
{
  Eigen::Vector3d p, d1, d2;
};

/** Distance from points of space to a closed parametric curve c(t), t in [0, 2 pi):
 * nearest vertex of a dense polygon, then Newton steps on (c(t) - x).c'(t) = 0 kept
 * between the vertex's neighbours (bisection where Newton would leave them). Where two
 * arcs are almost equally near, the polygon may pick the farther one; the error is then
 * below the polygon's sagitta. */
class CurveDistance
{
public:
  CurveDistance(CurvePoint (*curve)(double), std::size_t samples)
    : curve_(curve), step_(2 * kPi / static_cast<double>(samples))
  {
    for (std::size_t k = 0; k < samples; ++k)
      polygon_.add(curve_(step_ * static_cast<double>(k)).p);
  }

  double
  operator()(const Eigen::Vector3d& x) const
  {
    double best_squared;
    const double t0 = step_ * static_cast<double>(polygon_.nearest(x, best_squared));
    // g(t) = (c(t) - x).c'(t) is the half derivative of the squared distance.
    double lo = t0 - step_, hi = t0 + step_, t = t0;
    auto g = [&](double u) {
      const CurvePoint c = curve_(u);
      return (c.p - x).dot(c.d1);
    };
    const double g_lo = g(lo), g_hi = g(hi);
    if (g_lo < 0 && g_hi > 0) {
      for (int it = 0; it < 40; ++it) {
        const CurvePoint c = curve_(t);
        const double value = (c.p - x).dot(c.d1);
        if (value < 0)
          lo = t;
        else
          hi = t;
        const double slope = c.d1.squaredNorm() + (c.p - x).dot(c.d2);
        double next = slope > 0 ? t - value / slope : 0.5 * (lo + hi);
        if (!(next > lo && next < hi))
          next = 0.5 * (lo + hi);
        const bool done = std::abs(next - t) < 1e-14 || hi - lo < 1e-14;
        t = next;
        if (done)
          break;
      }
    }
    else
      t = g_lo >= 0 ? lo : hi; // the minimum is at an end of the bracket
    return std::sqrt(std::min(best_squared, (curve_(t).p - x).squaredNorm()));
  }

private:
  CurvePoint (*curve_)(double);
  double step_;
  PointTable polygon_;
};

// ---------------------------------------------------------------------------------
// Trefoil knot tube.

constexpr double kKnotRadius = 0.25;

Eigen::Vector3d
trefoil(double t)
{
  return {std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t),
          -std::sin(3 * t)};
}

Eigen::Vector3d
trefoilD1(double t)
{
  return {std::cos(t) + 4 * std::cos(2 * t), -std::sin(t) + 4 * std::sin(2 * t),
          -3 * std::cos(3 * t)};
}

Eigen::Vector3d
trefoilD2(double t)
{
  return {-std::sin(t) - 8 * std::sin(2 * t), -std::cos(t) + 8 * std::cos(2 * t),
          9 * std::sin(3 * t)};
}

CurvePoint
trefoilWithDerivatives(double t)
{
  const double s1 = std::sin(t), c1 = std::cos(t), s2 = std::sin(2 * t),
               c2 = std::cos(2 * t), s3 = std::sin(3 * t), c3 = std::cos(3 * t);
  return {{s1 + 2 * s2, c1 - 2 * c2, -s3},
          {c1 + 4 * c2, -s1 + 4 * s2, -3 * c3},
          {-s1 - 8 * s2, -c1 + 8 * c2, 9 * s3}};
}

// ---------------------------------------------------------------------------------
// Genus-3 slab: the boundary of the set of points within kSlabR of a planar region P
// (z = 0): a stadium (segment [-L, L] x {0} widened by W) minus three discs of radius
// rho centred on the segment. The offset surface of P is smooth as long as kSlabR is
// below P's reach, here the hole radius rho; its genus is the number of holes. Its
// feature size is min(R, rho - R) = 0.25: the half thickness and the hole's waist.

constexpr double kSlabR = 0.25;    // half thickness
constexpr double kSlabL = 1.1;     // half length of the stadium's core segment
constexpr double kSlabW = 0.6;     // stadium half width (in the plane)
constexpr double kSlabRho = 0.5;   // hole radius at the flat faces
constexpr double kSlabHoleX = 1.1; // hole centres at -kSlabHoleX, 0, kSlabHoleX

/** Distance in the plane from (x, y) to P; 0 inside. Exact: the holes are disjoint
 * and lie inside the stadium. */
double
planarDistanceToSlab(double x, double y)
{
  const double to_segment = std::hypot(std::max(std::abs(x) - kSlabL, 0.0), y);
  if (to_segment > kSlabW)
    return to_segment - kSlabW;
  for (const double cx : {-kSlabHoleX, 0.0, kSlabHoleX}) {
    const double to_centre = std::hypot(x - cx, y);
    if (to_centre < kSlabRho)
      return kSlabRho - to_centre;
  }
  return 0;
}

// ---------------------------------------------------------------------------------
// Unit sphere: whole, with a dense cap, and the upper half.

/** The point of the unit sphere at height \a z and azimuth \a a (also its outward
 * normal). */
Eigen::Vector3d
unitSpherePoint(double z, double a)
{
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return Eigen::Vector3d(s * std::cos(a), s * std::sin(a), z);
}

/** No rim, and the medial axis is the centre alone. */
void
setWholeUnitSphereFacts(SampledShape& shape)
{
  shape.distance_to_rim = [](const Eigen::Vector3d&) { return kInfinity; };
  shape.local_feature_size = [](const Eigen::Vector3d&) { return 1.0; };
  shape.distance_to_surface = [](const Eigen::Vector3d& x) {
    return std::abs(x.norm() - 1);
  };
}

} // namespace

// ---------------------------------------------------------------------------------

SampledShape
spreadSphere(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  SampledShape shape;
  shape.name = "sphere";
  shape.area = 4 * kPi;
  // Archimedes: z uniform in [-1, 1] is uniform by area on the sphere.
  sampleSurface(
      shape, n, seed, spread,
      [](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const double z = random.uniform(-1, 1);
        const double a = random.uniform(0, 2 * kPi);
        p = unitSpherePoint(z, a);
        normal = p;
      },
      shape.area);
  setWholeUnitSphereFacts(shape);
  return shape;
}

SampledShape
spreadSphereWithDenseCap(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  SampledShape shape;
  shape.name = "sphere_dense_cap";
  shape.area = 4 * kPi;
  const double cap_z = std::cos(40 * kPi / 180);
  const double density = 8;
  const double cap_area = 2 * kPi * (1 - cap_z);
  const double rest_area = 2 * kPi * (1 + cap_z);
  const double weighted_area = density * cap_area + rest_area;
  const double cap_share = density * cap_area / weighted_area;
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const bool cap = random.uniform() < cap_share;
        const double z = cap ? random.uniform(cap_z, 1) : random.uniform(-1, cap_z);
        const double a = random.uniform(0, 2 * kPi);
        p = unitSpherePoint(z, a);
        normal = p;
      },
      weighted_area,
      [=](const Eigen::Vector3d& p) { return p.z() >= cap_z ? density : 1.0; });
  setWholeUnitSphereFacts(shape);
  return shape;
}

SampledShape
spreadTorus(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  const double big = 1.0, small = 0.35;
  SampledShape shape;
  shape.name = "torus";
  shape.genus = 1;
  shape.area = 4 * kPi * kPi * big * small;
  // The area element is small * (big + small cos v) du dv: v by rejection.
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        double v;
        do
          v = random.uniform(0, 2 * kPi);
        while (random.uniform() * (big + small) > big + small * std::cos(v));
        const double u = random.uniform(0, 2 * kPi);
        normal = Eigen::Vector3d(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u),
                                 std::sin(v));
        p = Eigen::Vector3d(big * std::cos(u), big * std::sin(u), 0) + small * normal;
      },
      shape.area);
  shape.distance_to_rim = [](const Eigen::Vector3d&) { return kInfinity; };
  // The inner medial axis is the core circle, at distance `small` from every point;
  // the outer one (the z axis) is farther, big - small > small.
  shape.local_feature_size = [=](const Eigen::Vector3d&) { return small; };
  shape.distance_to_surface = [=](const Eigen::Vector3d& x) {
    return std::abs(std::hypot(std::hypot(x.x(), x.y()) - big, x.z()) - small);
  };
  return shape;
}

SampledShape
spreadTrefoilKnot(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  const double r = kKnotRadius;
  SampledShape shape;
  shape.name = "trefoil_knot";
  shape.genus = 1;

  // Tube X(t, phi) = c(t) + r n(phi) with n a unit normal of the curve. Its area
  // element is r |c'| (1 - r n.c'' / |c'|^2) whatever normal frame is used, and it
  // integrates over phi to 2 pi r |c'|: the area is 2 pi r times the length (trapezoid
  // rule, spectrally accurate for a periodic integrand).
  const int quadrature = 4096;
  double length = 0, bound = 0;
  for (int k = 0; k < quadrature; ++k) {
    const double t = 2 * kPi * k / quadrature;
    const double speed = trefoilD1(t).norm();
    length += speed;
    bound = std::max(bound, speed + r * trefoilD2(t).norm() / speed);
  }
  length *= 2 * kPi / quadrature;
  bound *= 1.05;
  shape.area = 2 * kPi * r * length;

  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        for (;;) {
          const double t = random.uniform(0, 2 * kPi);
          const double phi = random.uniform(0, 2 * kPi);
          const Eigen::Vector3d d1 = trefoilD1(t);
          const double speed = d1.norm();
          const Eigen::Vector3d tangent = d1 / speed;
          // Any normal frame does: the frame only shifts phi at each t.
          const Eigen::Vector3d helper = std::abs(tangent.z()) < 0.9
                                             ? Eigen::Vector3d::UnitZ()
                                             : Eigen::Vector3d::UnitX();
          const Eigen::Vector3d e1 =
              (helper - helper.dot(tangent) * tangent).normalized();
          const Eigen::Vector3d e2 = tangent.cross(e1);
          const Eigen::Vector3d dir = std::cos(phi) * e1 + std::sin(phi) * e2;
          const double element = speed - r * dir.dot(trefoilD2(t)) / speed;
          if (random.uniform() * bound <= element) {
            p = trefoil(t) + r * dir;
            normal = dir;
            return;
          }
        }
      },
      shape.area);

  auto core = std::make_shared<const CurveDistance>(trefoilWithDerivatives, 512);
  shape.distance_to_rim = [](const Eigen::Vector3d&) { return kInfinity; };
  shape.distance_to_surface = [core, r](const Eigen::Vector3d& x) {
    return std::abs((*core)(x)-r);
  };
  return shape;
}

SampledShape
spreadGenus3(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  const double R = kSlabR, L = kSlabL, W = kSlabW, rho = kSlabRho;
  SampledShape shape;
  shape.name = "genus3";
  shape.genus = 3;

  // Pieces of the surface and their areas: the two flat faces (P itself), the tubes
  // of radius R around the two straight sides, the two end arcs and the three holes.
  // A tube around a boundary arc of curvature k has the area element
  // R (1 + k R cos theta) ds dtheta, theta in [-pi/2, pi/2].
  const double plane_area = 4 * L * W + kPi * W * W - 3 * kPi * rho * rho;
  const double side_area = 2 * kPi * R * L;
  const double end_area = kPi * R * (kPi * W + 2 * R);
  const double hole_area = 2 * kPi * R * (kPi * rho - 2 * R);
  const std::array<double, 4> piece_area = {2 * plane_area, 2 * side_area, 2 * end_area,
                                            3 * hole_area};
  shape.area = piece_area[0] + piece_area[1] + piece_area[2] + piece_area[3];
  std::array<double, 4> cumulative{};
  double sum = 0;
  for (std::size_t i = 0; i < 4; ++i)
    cumulative[i] = (sum += piece_area[i]) / shape.area;

  const double area = shape.area;
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const double pick = random.uniform();
        const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
        if (pick < cumulative[0]) {
          double x, y;
          do {
            x = random.uniform(-L - W, L + W);
            y = random.uniform(-W, W);
          } while (planarDistanceToSlab(x, y) > 0);
          const double side = random.uniform() < 0.5 ? -1.0 : 1.0;
          p = Eigen::Vector3d(x, y, side * R);
          normal = side * up;
        }
        else if (pick < cumulative[1]) {
          const double side = random.uniform() < 0.5 ? -1.0 : 1.0;
          const double s = random.uniform(-L, L);
          const double theta = random.uniform(-0.5 * kPi, 0.5 * kPi);
          normal = Eigen::Vector3d(0, side * std::cos(theta), std::sin(theta));
          p = Eigen::Vector3d(s, side * W, 0) + R * normal;
        }
        else if (pick < cumulative[2]) {
          const double side = random.uniform() < 0.5 ? -1.0 : 1.0;
          double theta;
          do
            theta = random.uniform(-0.5 * kPi, 0.5 * kPi);
          while (random.uniform() * (W + R) > W + R * std::cos(theta));
          const double a = random.uniform(-0.5 * kPi, 0.5 * kPi);
          const Eigen::Vector3d out(side * std::cos(a), std::sin(a), 0);
          normal = std::cos(theta) * out + std::sin(theta) * up;
          p = Eigen::Vector3d(side * L, 0, 0) + W * out + R * normal;
        }
        else {
          const double cx = (static_cast<double>(random.index(3)) - 1.0) * kSlabHoleX;
          double theta;
          do
            theta = random.uniform(-0.5 * kPi, 0.5 * kPi);
          while (random.uniform() * rho > rho - R * std::cos(theta));
          const double a = random.uniform(0, 2 * kPi);
          const Eigen::Vector3d radial(std::cos(a), std::sin(a), 0);
          // Out of P at the hole's edge is towards the hole's axis.
          normal = -std::cos(theta) * radial + std::sin(theta) * up;
          p = Eigen::Vector3d(cx, 0, 0) + rho * radial + R * normal;
        }
      },
      area);

  shape.distance_to_rim = [](const Eigen::Vector3d&) { return kInfinity; };
  // Exact below the reach rho > R of P, i.e. for every point of space nearer to P than
  // rho, and beyond it for points outside.
  shape.distance_to_surface = [R](const Eigen::Vector3d& x) {
    return std::abs(std::hypot(planarDistanceToSlab(x.x(), x.y()), x.z()) - R);
  };
  return shape;
}

SampledShape
spreadHemisphere(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  SampledShape shape;
  shape.name = "hemisphere";
  shape.area = 2 * kPi;
  shape.closed = false;
  shape.boundary_loops = 1;
  sampleSurface(
      shape, n, seed, spread,
      [](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const double z = random.uniform(0, 1);
        const double a = random.uniform(0, 2 * kPi);
        p = unitSpherePoint(z, a);
        normal = p;
      },
      shape.area);
  addCircle(shape.rim, 1, 0, rimCount(2 * kPi, shape));
  shape.distance_to_rim = [](const Eigen::Vector3d& x) {
    return std::hypot(std::hypot(x.x(), x.y()) - 1, x.z());
  };
  // Above the equator plane the nearest point is radial; below it, on the equator.
  shape.distance_to_surface = [](const Eigen::Vector3d& x) {
    if (x.z() >= 0)
      return std::abs(x.norm() - 1);
    return std::hypot(std::hypot(x.x(), x.y()) - 1, x.z());
  };
  return shape;
}

namespace {

double
saddleHeight(double x, double y)
{
  return x * x * x - 3 * x * y * y;
}

Eigen::Vector3d
saddleRim(double t)
{
  return {std::cos(t), std::sin(t), std::cos(3 * t)};
}

CurvePoint
saddleRimWithDerivatives(double t)
{
  const double c = std::cos(t), s = std::sin(t), c3 = std::cos(3 * t),
               s3 = std::sin(3 * t);
  return {{c, s, c3}, {-s, c, -3 * s3}, {-c, -s, -9 * c3}};
}

/** Distance from points of space to the monkey saddle patch over the unit disc: the
 * nearest of a coarse grid of the patch, refined by Newton steps on the squared
 * distance in the parameters, against the distance to the rim curve. */
class SaddleDistance
{
public:
  SaddleDistance() : rim_(saddleRimWithDerivatives, 256)
  {
    const int rings = 8, sectors = 32;
    grid_.emplace_back(0, 0);
    for (int i = 1; i <= rings; ++i)
      for (int j = 0; j < sectors; ++j) {
        const double rr = static_cast<double>(i) / rings;
        const double a = 2 * kPi * (j + 0.5 * (i % 2)) / sectors;
        grid_.emplace_back(rr * std::cos(a), rr * std::sin(a));
      }
    for (const Eigen::Vector2d& g : grid_)
      table_.add(Eigen::Vector3d(g.x(), g.y(), saddleHeight(g.x(), g.y())));
  }

  double
  operator()(const Eigen::Vector3d& x) const
  {
    // Two starts: the vertical projection and the nearest grid point (which may lie
    // on another fold of the saddle).
    Eigen::Vector2d below(x.x(), x.y());
    if (below.squaredNorm() > 1)
      below.normalize();
    double nearest_squared;
    const Eigen::Vector2d nearest = grid_[table_.nearest(x, nearest_squared)];
    const double best = std::min(descend(x, below), descend(x, nearest));
    return std::min(rim_(x), std::sqrt(best));
  }

private:
  static double
  squaredDistance(const Eigen::Vector3d& x, const Eigen::Vector2d& uv)
  {
    return (Eigen::Vector3d(uv.x(), uv.y(), saddleHeight(uv.x(), uv.y())) - x)
        .squaredNorm();
  }

  /** Projected Newton descent of f(u, v) = |X(u, v) - x|^2 / 2 over the closed unit
   * disc, with step halving to keep descending. Every iterate is a point of the patch,
   * so the result is never below the true squared distance. */
  static double
  descend(const Eigen::Vector3d& x, Eigen::Vector2d uv)
  {
    double current = squaredDistance(x, uv);
    for (int it = 0; it < 60; ++it) {
      const double u = uv.x(), v = uv.y();
      const double e = saddleHeight(u, v) - x.z();
      const double hu = 3 * u * u - 3 * v * v, hv = -6 * u * v;
      const Eigen::Vector2d gradient(u - x.x() + e * hu, v - x.y() + e * hv);
      Eigen::Matrix2d hessian;
      hessian << 1 + hu * hu + e * 6 * u, hu * hv - e * 6 * v, hu * hv - e * 6 * v,
          1 + hv * hv - e * 6 * u;
      Eigen::Vector2d step = -gradient;
      if (hessian.determinant() > 1e-12 && hessian.trace() > 0) {
        const Eigen::Vector2d newton = -hessian.inverse() * gradient;
        if (newton.dot(gradient) < 0)
          step = newton;
      }
      Eigen::Vector2d trial;
      double value = kInfinity;
      double scale = 1;
      for (; scale > 1e-7; scale *= 0.5) {
        trial = uv + scale * step;
        if (trial.squaredNorm() > 1)
          trial.normalize();
        value = squaredDistance(x, trial);
        if (value <= current)
          break;
      }
      if (value > current)
        break;
      const double moved = (trial - uv).norm();
      uv = trial;
      current = value;
      if (moved < 1e-13)
        break;
    }
    return current;
  }

private:
  CurveDistance rim_;
  std::vector<Eigen::Vector2d> grid_;
  PointTable table_; // the grid's points on the saddle
};

} // namespace

SampledShape
spreadMonkeySaddle(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  SampledShape shape;
  shape.name = "monkey_saddle";
  shape.closed = false;
  shape.boundary_loops = 1;
  // |grad h| = 3 rho^2, so the area is 2 pi int_0^1 sqrt(1 + 9 rho^4) rho d rho
  //   = pi int_0^1 sqrt(1 + 9 u^2) du = pi (sqrt(10) / 2 + asinh(3) / 6).
  shape.area = kPi * (std::sqrt(10.0) / 2 + std::asinh(3.0) / 6);
  const double max_element = std::sqrt(10.0);
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        double x, y, rr;
        do {
          rr = std::sqrt(random.uniform());
          const double a = random.uniform(0, 2 * kPi);
          x = rr * std::cos(a);
          y = rr * std::sin(a);
        } while (random.uniform() * max_element > std::sqrt(1 + 9 * rr * rr * rr * rr));
        p = Eigen::Vector3d(x, y, saddleHeight(x, y));
        normal = Eigen::Vector3d(-(3 * x * x - 3 * y * y), 6 * x * y, 1).normalized();
      },
      shape.area);

  // |rim'(t)| <= sqrt(10).
  const std::size_t count = rimCount(2 * kPi * std::sqrt(10.0), shape);
  for (std::size_t k = 0; k < count; ++k)
    shape.rim.push_back(
        saddleRim(2 * kPi * static_cast<double>(k) / static_cast<double>(count)));
  auto rim = std::make_shared<const CurveDistance>(saddleRimWithDerivatives, 1024);
  shape.distance_to_rim = [rim](const Eigen::Vector3d& x) { return (*rim)(x); };
  auto surface = std::make_shared<const SaddleDistance>();
  shape.distance_to_surface = [surface](const Eigen::Vector3d& x) {
    return (*surface)(x);
  };
  return shape;
}

SampledShape
spreadOpenCylinder(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  const double radius = 0.5, half_height = 1;
  SampledShape shape;
  shape.name = "open_cylinder";
  shape.closed = false;
  shape.boundary_loops = 2;
  shape.area = 2 * kPi * radius * 2 * half_height;
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const double z = random.uniform(-half_height, half_height);
        const double a = random.uniform(0, 2 * kPi);
        normal = Eigen::Vector3d(std::cos(a), std::sin(a), 0);
        p = radius * normal + Eigen::Vector3d(0, 0, z);
      },
      shape.area);
  const std::size_t count = rimCount(2 * kPi * radius, shape);
  addCircle(shape.rim, radius, -half_height, count);
  addCircle(shape.rim, radius, half_height, count);
  shape.distance_to_rim = [=](const Eigen::Vector3d& x) {
    return std::hypot(std::hypot(x.x(), x.y()) - radius, std::abs(x.z()) - half_height);
  };
  shape.distance_to_surface = [=](const Eigen::Vector3d& x) {
    const double radial = std::hypot(x.x(), x.y()) - radius;
    const double beyond = std::max(0.0, std::abs(x.z()) - half_height);
    return std::hypot(radial, beyond);
  };
  return shape;
}

namespace {

/** Distance from \a x to the segment from \a a to \a b. */
double
distanceToSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b)
{
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

} // namespace

SampledShape
spreadHalfCylinder(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  const double radius = 0.5, half_height = 1;
  SampledShape shape;
  shape.name = "half_cylinder";
  shape.closed = false;
  shape.boundary_loops = 1;
  shape.area = kPi * radius * 2 * half_height;
  sampleSurface(
      shape, n, seed, spread,
      [=](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const double z = random.uniform(-half_height, half_height);
        const double a = random.uniform(0, kPi);
        normal = Eigen::Vector3d(std::cos(a), std::sin(a), 0);
        p = radius * normal + Eigen::Vector3d(0, 0, z);
      },
      shape.area);
  // The rim: two half circles joined by the two straight edges at y = 0, x = +-radius
  // (four corners of 90 degrees).
  const std::size_t arc_count = rimCount(kPi * radius, shape);
  for (const double z : {-half_height, half_height})
    for (std::size_t k = 0; k <= arc_count; ++k) {
      const double a = kPi * static_cast<double>(k) / static_cast<double>(arc_count);
      shape.rim.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  const std::size_t line_count = rimCount(2 * half_height, shape);
  for (const double x : {-radius, radius})
    for (std::size_t k = 1; k < line_count; ++k)
      shape.rim.emplace_back(
          x, 0, -half_height + 2 * half_height * static_cast<double>(k) / line_count);
  const Eigen::Vector3d left_low(-radius, 0, -half_height),
      left_high(-radius, 0, half_height);
  const Eigen::Vector3d right_low(radius, 0, -half_height),
      right_high(radius, 0, half_height);
  const auto to_edges = [=](const Eigen::Vector3d& x) {
    return std::min(distanceToSegment(x, left_low, left_high),
                    distanceToSegment(x, right_low, right_high));
  };
  shape.distance_to_rim = [=](const Eigen::Vector3d& x) {
    // The nearest point of an arc is the radial one when x lies over the arc (y >= 0),
    // an end of the arc (on the straight edges) otherwise.
    double arcs = kInfinity;
    if (x.y() >= 0)
      arcs =
          std::hypot(std::hypot(x.x(), x.y()) - radius, std::abs(x.z()) - half_height);
    return std::min(arcs, to_edges(x));
  };
  shape.distance_to_surface = [=](const Eigen::Vector3d& x) {
    if (x.y() < 0) // over a in [0, pi], x.(cos a, sin a) peaks at a = 0 or pi
      return to_edges(x);
    const double radial = std::hypot(x.x(), x.y()) - radius;
    const double beyond = std::max(0.0, std::abs(x.z()) - half_height);
    return std::hypot(radial, beyond);
  };
  return shape;
}

SampledShape
spreadCube(std::size_t n, std::uint32_t seed, const Spread& spread)
{
  SampledShape shape;
  shape.name = "cube";
  shape.area = 24;
  sampleSurface(
      shape, n, seed, spread,
      [](Random& random, Eigen::Vector3d& p, Eigen::Vector3d& normal) {
        const std::size_t face = random.index(6);
        const int axis = static_cast<int>(face / 2);
        const double side = face % 2 ? 1.0 : -1.0;
        p = Eigen::Vector3d(random.uniform(-1, 1), random.uniform(-1, 1),
                            random.uniform(-1, 1));
        p[axis] = side;
        normal = Eigen::Vector3d::Zero();
        normal[axis] = side;
      },
      shape.area);

  const std::size_t count = rimCount(2, shape);
  for (int axis = 0; axis < 3; ++axis)
    for (const double a : {-1.0, 1.0})
      for (const double b : {-1.0, 1.0})
        for (std::size_t k = 0; k <= count; ++k) {
          Eigen::Vector3d p;
          p[axis] = -1 + 2 * static_cast<double>(k) / static_cast<double>(count);
          p[(axis + 1) % 3] = a;
          p[(axis + 2) % 3] = b;
          shape.rim.push_back(p);
        }
  // The edge along `axis` nearest to x: the other two coordinates at +-1 with the
  // signs of x's, `axis` clamped to the edge.
  shape.distance_to_rim = [](const Eigen::Vector3d& x) {
    double best = kInfinity;
    for (int axis = 0; axis < 3; ++axis) {
      const double along = std::max(0.0, std::abs(x[axis]) - 1);
      const double a = std::abs(x[(axis + 1) % 3]) - 1;
      const double b = std::abs(x[(axis + 2) % 3]) - 1;
      best = std::min(best, std::sqrt(along * along + a * a + b * b));
    }
    return best;
  };
  shape.distance_to_surface = [](const Eigen::Vector3d& x) {
    const Eigen::Vector3d excess = (x.cwiseAbs().array() - 1.0).matrix();
    if (excess.maxCoeff() > 0)
      return excess.cwiseMax(0.0).norm();
    return -excess.maxCoeff();
  };
  return shape;
}

// ---------------------------------------------------------------------------------

namespace {

constexpr Spread kBlueNoise{};

} // namespace

SampledShape
sampleSphere(std::size_t n, std::uint32_t seed)
{
  return spreadSphere(n, seed, kBlueNoise);
}

SampledShape
sampleSphereWithDenseCap(std::size_t n, std::uint32_t seed)
{
  return spreadSphereWithDenseCap(n, seed, kBlueNoise);
}

SampledShape
sampleTorus(std::size_t n, std::uint32_t seed)
{
  return spreadTorus(n, seed, kBlueNoise);
}

SampledShape
sampleTrefoilKnot(std::size_t n, std::uint32_t seed)
{
  return spreadTrefoilKnot(n, seed, kBlueNoise);
}

SampledShape
sampleGenus3(std::size_t n, std::uint32_t seed)
{
  return spreadGenus3(n, seed, kBlueNoise);
}

SampledShape
sampleHemisphere(std::size_t n, std::uint32_t seed)
{
  return spreadHemisphere(n, seed, kBlueNoise);
}

SampledShape
sampleMonkeySaddle(std::size_t n, std::uint32_t seed)
{
  return spreadMonkeySaddle(n, seed, kBlueNoise);
}

SampledShape
sampleOpenCylinder(std::size_t n, std::uint32_t seed)
{
  return spreadOpenCylinder(n, seed, kBlueNoise);
}

SampledShape
sampleHalfCylinder(std::size_t n, std::uint32_t seed)
{
  return spreadHalfCylinder(n, seed, kBlueNoise);
}

SampledShape
sampleCube(std::size_t n, std::uint32_t seed)
{
  return spreadCube(n, seed, kBlueNoise);
}

const std::vector<Shape>&
allShapes()
{
  static const std::vector<Shape> shapes = {
      Shape::sphere,        Shape::torus,         Shape::trefoil_knot,
      Shape::genus3,        Shape::cube,          Shape::hemisphere,
      Shape::open_cylinder, Shape::half_cylinder, Shape::monkey_saddle};
  return shapes;
}

const char*
shapeName(Shape shape)
{
  switch (shape) {
  case Shape::sphere:
    return "sphere";
  case Shape::torus:
    return "torus";
  case Shape::trefoil_knot:
    return "knot";
  case Shape::genus3:
    return "genus3";
  case Shape::cube:
    return "cube";
  case Shape::hemisphere:
    return "hemisphere";
  case Shape::open_cylinder:
    return "open_cylinder";
  case Shape::half_cylinder:
    return "half_cylinder";
  case Shape::monkey_saddle:
    return "monkey_saddle";
  }
  return "?";
}

SampledShape
sampleRandom(Shape shape, std::size_t n, std::uint32_t seed, bool density_ramp)
{
  Spread spread;
  spread.random = true;
  spread.density_ramp = density_ramp;
  switch (shape) {
  case Shape::sphere:
    return spreadSphere(n, seed, spread);
  case Shape::torus:
    return spreadTorus(n, seed, spread);
  case Shape::trefoil_knot:
    return spreadTrefoilKnot(n, seed, spread);
  case Shape::genus3:
    return spreadGenus3(n, seed, spread);
  case Shape::cube:
    return spreadCube(n, seed, spread);
  case Shape::hemisphere:
    return spreadHemisphere(n, seed, spread);
  case Shape::open_cylinder:
    return spreadOpenCylinder(n, seed, spread);
  case Shape::half_cylinder:
    return spreadHalfCylinder(n, seed, spread);
  case Shape::monkey_saddle:
    return spreadMonkeySaddle(n, seed, spread);
  }
  return {};
}

} // namespace test
} // namespace cocone
} // namespace pcl
