// SPDX-License-Identifier: GPL-3.0-or-later
#include "voronoi/delaunay.h"

#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <new>
#include <numeric>
#include <sstream>
#include <utility>

namespace pcl {
namespace cocone {

const char*
toString(Status status)
{
  switch (status) {
  case Status::ok:
    return "ok";
  case Status::not_computed:
    return "not_computed";
  case Status::too_few_points:
    return "too_few_points";
  case Status::non_finite_input:
    return "non_finite_input";
  case Status::degenerate_dimension:
    return "degenerate_dimension";
  case Status::too_many_points:
    return "too_many_points";
  case Status::invalid_parameter:
    return "invalid_parameter";
  case Status::internal_error:
    return "internal_error";
  }
  return "unknown";
}

namespace {

/** Spreads the low 21 bits of \a x to every third bit (bit k goes to bit 3k). */
std::uint64_t
spreadBits(std::uint64_t x)
{
  x &= 0x1fffffu;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

} // namespace

std::vector<SampleIndex>
spatialOrder(const std::vector<Eigen::Vector3d>& points, unsigned threads)
{
  const std::size_t n = points.size();
  if (n >= kNoSample)
    return {};
  Eigen::Vector3d low =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite()) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  // One scale for all axes keeps the cells cubes; a flat cloud then uses fewer levels
  // of one axis, which costs nothing.
  const double extent = (high - low).maxCoeff();
  constexpr double kLevels = double((1u << 21) - 1);
  const double scale = extent > 0 ? kLevels / extent : 0;
  // Sorting (key, position) pairs breaks ties by position: the order is stable.
  std::vector<std::pair<std::uint64_t, SampleIndex> > keyed(n);
  detail::runInArena(threads, [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Eigen::Vector3d& p = points[i];
            std::uint64_t key = std::numeric_limits<std::uint64_t>::max();
            if (p.allFinite()) {
              const Eigen::Vector3d cell =
                  ((p - low) * scale).cwiseMin(kLevels).cwiseMax(0.0);
              key = spreadBits(static_cast<std::uint64_t>(cell.x())) |
                    spreadBits(static_cast<std::uint64_t>(cell.y())) << 1 |
                    spreadBits(static_cast<std::uint64_t>(cell.z())) << 2;
            }
            keyed[i] = {key, static_cast<SampleIndex>(i)};
          }
        });
    tbb::parallel_sort(keyed.begin(), keyed.end());
  });
  std::vector<SampleIndex> order(n);
  for (std::size_t k = 0; k < n; ++k)
    order[k] = keyed[k].second;
  return order;
}

namespace detail {

// ---------------------------------------------------------------------------------
namespace {

ConeSide
classify(const Eigen::Vector3d& x, const Eigen::Vector3d& axis, double sin_theta)
{
  const double along = x.dot(axis);
  const double limit = sin_theta * x.norm();
  if (along > limit)
    return ConeSide::upper;
  if (along < -limit)
    return ConeSide::lower;
  return ConeSide::inside;
}

} // namespace

EdgeInCocone
clipVoronoiEdge(const Eigen::Vector3d& start,
                const Eigen::Vector3d& direction,
                bool is_ray,
                const Eigen::Vector3d& axis,
                double sin_theta)
{
  EdgeInCocone result;
  const ConeSide side_start = classify(start, axis, sin_theta);
  // A ray's far end is classified by its direction.
  const ConeSide side_end =
      classify(is_ray ? direction : Eigen::Vector3d(start + direction), axis, sin_theta);
  // Each nappe of the double cone is convex: a segment with both ends in the same nappe
  // stays in it; otherwise it crosses the cocone.
  result.meets = side_start == ConeSide::inside || side_end == ConeSide::inside ||
                 side_start != side_end;
  if (!result.meets)
    return result;
  if (is_ray && side_end == ConeSide::inside) {
    result.unbounded = true;
    return result;
  }
  // Points x(t) = start + t direction inside the cocone satisfy
  //   f(t) = (x.axis)^2 - sin^2 |x|^2 <= 0,
  // a quadratic a t^2 + 2 b t + c. |x(t)| is convex in t, so its maximum over the
  // feasible part sits at an end of a feasible interval: an end of the edge that is
  // inside, or a root of f.
  const double s2 = sin_theta * sin_theta;
  const double sv = start.dot(axis);
  const double dv = direction.dot(axis);
  const double a = dv * dv - s2 * direction.squaredNorm();
  const double b = sv * dv - s2 * start.dot(direction);
  const double c = sv * sv - s2 * start.squaredNorm();
  const double t_max = is_ray ? std::numeric_limits<double>::infinity() : 1.0;
  double best = 0;
  const auto consider = [&](double t) {
    if (t >= 0 && t <= t_max)
      best = std::max(best, (start + t * direction).squaredNorm());
  };
  if (side_start == ConeSide::inside)
    consider(0);
  if (!is_ray && side_end == ConeSide::inside)
    consider(1);
  const double scale = std::abs(a) + std::abs(b) + std::abs(c);
  if (std::abs(a) > 1e-14 * scale) {
    const double disc = b * b - a * c;
    if (disc >= 0) {
      // Numerically stable roots of a t^2 + 2 b t + c.
      const double q = -(b + std::copysign(std::sqrt(disc), b));
      consider(q / a);
      if (q != 0)
        consider(c / q);
    }
    else {
      consider(-b / a); // rounding hid a tangency: take the closest approach
    }
  }
  else if (b != 0) {
    consider(-c / (2 * b));
  }
  result.max_distance2 = best;
  return result;
}

} // namespace detail

// ---------------------------------------------------------------------------------
using namespace detail;

VoronoiCocone::VoronoiCocone() : impl_(new Impl), cocone_angle_(M_PI / 8) {}
VoronoiCocone::~VoronoiCocone() = default;
VoronoiCocone::VoronoiCocone(VoronoiCocone&&) noexcept = default;
VoronoiCocone&
VoronoiCocone::operator=(VoronoiCocone&&) noexcept = default;

Status
VoronoiCocone::setCoconeAngle(double theta)
{
  if (!kCoconeAngleRange.contains(theta))
    return Status::invalid_parameter;
  cocone_angle_ = theta;
  return Status::ok;
}

double
VoronoiCocone::getCoconeAngle() const
{
  return cocone_angle_;
}

void
VoronoiCocone::setNumberOfThreads(unsigned threads)
{
  threads_ = threads;
}

unsigned
VoronoiCocone::getNumberOfThreads() const
{
  return threads_;
}

const VoronoiCocone::Timings&
VoronoiCocone::timings() const
{
  return impl_->timings;
}

Status
VoronoiCocone::status() const
{
  return impl_->status;
}

const std::string&
VoronoiCocone::errorMessage() const
{
  return impl_->message;
}

std::size_t
VoronoiCocone::size() const
{
  return impl_->representative.size();
}

std::size_t
VoronoiCocone::numUniqueSamples() const
{
  return impl_->unique_count;
}

SampleIndex
VoronoiCocone::representative(SampleIndex i) const
{
  return impl_->representative[i];
}

const std::vector<Eigen::Vector3d>&
VoronoiCocone::centeredPoints() const
{
  return impl_->centered;
}

const Eigen::Vector3d&
VoronoiCocone::offset() const
{
  return impl_->offset;
}

const Eigen::Vector3d&
VoronoiCocone::poleVector(SampleIndex i) const
{
  return impl_->pole_vector[impl_->representative[i]];
}

bool
VoronoiCocone::positivePoleAtInfinity(SampleIndex i) const
{
  return impl_->unbounded[impl_->representative[i]] != 0;
}

Eigen::Vector3d
VoronoiCocone::positivePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (impl_->unbounded[r])
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  return impl_->positive_pole[r] + impl_->offset;
}

Eigen::Vector3d
VoronoiCocone::negativePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (!(impl_->height[r] > 0))
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return impl_->negative_pole[r] + impl_->offset;
}

double
VoronoiCocone::height(SampleIndex i) const
{
  return impl_->height[impl_->representative[i]];
}

double
VoronoiCocone::coconeRadius(SampleIndex i) const
{
  return impl_->radius[impl_->representative[i]];
}

double
VoronoiCocone::ratio(SampleIndex i) const
{
  return impl_->ratio(impl_->representative[i]);
}

const std::vector<MarkedTriangle>&
VoronoiCocone::markedTriangles() const
{
  return impl_->triangles;
}

IndexRange
VoronoiCocone::trianglesAround(SampleIndex i) const
{
  if (impl_->triangle_offsets.empty())
    return {};
  const SampleIndex r = impl_->representative[i];
  const std::uint32_t* base = impl_->triangle_ids.data();
  return {base + impl_->triangle_offsets[r], base + impl_->triangle_offsets[r + 1]};
}

void
VoronoiCocone::coconeNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  const SampleIndex r = impl_->representative[i];
  for (const std::uint32_t t : trianglesAround(r)) {
    const MarkedTriangle& triangle = impl_->triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (triangle.vertex[k] != r || !triangle.isMarkedBy(k))
        continue;
      for (int other = 0; other < 3; ++other)
        if (other != k)
          neighbours.push_back(triangle.vertex[other]);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
}

void
VoronoiCocone::delaunayNeighbours(SampleIndex i, std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  if (impl_->stars.empty())
    return;
  // Several threads may ask at once: per-thread scratch, which stops allocating after
  // a thread's first calls.
  thread_local SampleMarks seen;
  impl_->stars.appendNeighbours(impl_->representative[i], seen, neighbours);
  std::sort(neighbours.begin(), neighbours.end());
}

void
VoronoiCocone::delaunayTrianglesAmong(
    const std::vector<SampleIndex>& samples,
    std::vector<std::array<SampleIndex, 3>>& triangles) const
{
  triangles.clear();
  const DelaunayStars& stars = impl_->stars;
  if (stars.empty())
    return;
  // Several threads may ask at once (one hole each): per-thread scratch.
  thread_local SampleMarks is_member;
  thread_local std::vector<SampleIndex> members;
  members.clear();
  is_member.clear();
  for (const SampleIndex s : samples)
    if (is_member.mark(impl_->representative[s]))
      members.push_back(impl_->representative[s]);
  // kNoSample (the infinite vertex) is never marked.
  for (const SampleIndex s : members) {
    for (std::uint32_t k = stars.offsets[s]; k < stars.offsets[s + 1]; ++k) {
      const std::array<SampleIndex, 4>& cell = stars.cell_samples[stars.cells[k]];
      // Most cells at a hole's rim have only s and one other member: no facet of
      // three members, told without looking at the facets.
      int in_cell = 0;
      for (const SampleIndex w : cell)
        in_cell += is_member.isMarked(w);
      if (in_cell < 3)
        continue;
      for (int i = 0; i < 4; ++i) {
        if (cell[i] == s)
          continue; // the facet opposite s does not contain it
        std::array<SampleIndex, 3> t;
        int m = 0;
        bool keep = true;
        for (int j = 0; j < 4 && keep; ++j) {
          if (j == i)
            continue;
          if (!is_member.isMarked(cell[j]))
            keep = false;
          else
            t[m++] = cell[j];
        }
        // Report each triangle from its smallest vertex; it lies in two cells, so the
        // repeats go after sorting.
        if (!keep)
          continue;
        std::sort(t.begin(), t.end());
        if (t[0] == s)
          triangles.push_back(t);
      }
    }
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
}

// ---------------------------------------------------------------------------------
namespace {

/** The circumcenter of a finite cell (its Voronoi vertex). */
Eigen::Vector3d
circumcenter(CellHandle c)
{
  const Point center = CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                                          c->vertex(2)->point(), c->vertex(3)->point());
  return {center.x(), center.y(), center.z()};
}

/** The triangulation as flat arrays by cell number, finite cells first and the
 * infinite ones after them. The per-sample pass reads these instead of CGAL's cells,
 * which lie scattered in memory: cache misses on cell handles dominated the pass. */
struct CellTable
{
  std::vector<std::array<SampleIndex, 4> > samples; // kNoSample: the infinite vertex
  std::vector<std::array<std::uint32_t, 4> > neighbours; // the cell across facet i
  std::vector<Eigen::Vector3d> centers; // circumcenters of the finite cells
  std::size_t finite = 0;

  bool isFinite(std::uint32_t k) const { return k < finite; }

  /** The position of sample \a s (or kNoSample) in cell \a k; the cell has it. */
  int indexOf(std::uint32_t k, SampleIndex s) const
  {
    const std::array<SampleIndex, 4>& v = samples[k];
    assert(v[0] == s || v[1] == s || v[2] == s || v[3] == s);
    return v[0] == s ? 0 : v[1] == s ? 1 : v[2] == s ? 2 : 3;
  }

  /** The facet of cell \a k shared with its neighbour \a n. */
  int facetTowards(std::uint32_t k, std::uint32_t n) const
  {
    const std::array<std::uint32_t, 4>& c = neighbours[k];
    assert(c[0] == n || c[1] == n || c[2] == n || c[3] == n);
    return c[0] == n ? 0 : c[1] == n ? 1 : c[2] == n ? 2 : 3;
  }
};

/** What one pass over a vertex's Voronoi cell produces. */
struct CellGeometry
{
  Eigen::Vector3d pole_vector = Eigen::Vector3d::Zero();
  Eigen::Vector3d positive_pole = Eigen::Vector3d::Zero(); // centered frame
  Eigen::Vector3d negative_pole = Eigen::Vector3d::Zero(); // centered frame
  bool unbounded = false;
  double height = 0; // NaN without a negative pole
};

/** Unit outward normal of the convex-hull facet i of the finite cell k, whose
 * neighbour across it is infinite. */
Eigen::Vector3d
hullFacetNormal(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
                std::uint32_t k, int i)
{
  const std::array<SampleIndex, 4>& v = cells.samples[k];
  const Eigen::Vector3d& a = points[v[(i + 1) & 3]];
  const Eigen::Vector3d& b = points[v[(i + 2) & 3]];
  const Eigen::Vector3d& d = points[v[(i + 3) & 3]];
  Eigen::Vector3d normal = (b - a).cross(d - a);
  // Outward: away from the vertex of k opposite the facet.
  if (normal.dot(points[v[i]] - a) > 0)
    normal = -normal;
  const double length = normal.norm();
  return length > 0 ? Eigen::Vector3d(normal / length) : normal;
}

/** The poles, pole vector and height of the cell of sample \a s, from the cells of its
 * star. */
void
computePoles(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
             SampleIndex s, const std::uint32_t* star_begin,
             const std::uint32_t* star_end, CellGeometry& geometry)
{
  const Eigen::Vector3d& p = points[s];
  Eigen::Vector3d hull_normal_sum = Eigen::Vector3d::Zero();
  double farthest2 = -1;
  geometry.unbounded = false;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c)) {
      // The finite facet of an infinite cell is a convex-hull triangle at p.
      geometry.unbounded = true;
      const std::uint32_t inside = cells.neighbours[*c][cells.indexOf(*c, kNoSample)];
      hull_normal_sum +=
          hullFacetNormal(cells, points, inside, cells.facetTowards(inside, *c));
      continue;
    }
    const double d2 = (cells.centers[*c] - p).squaredNorm();
    if (d2 > farthest2) {
      farthest2 = d2;
      geometry.positive_pole = cells.centers[*c];
    }
  }
  if (geometry.unbounded) {
    const double length = hull_normal_sum.norm();
    if (length > 1e-12)
      geometry.pole_vector = hull_normal_sum / length;
    else if (farthest2 > 0) // opposite hull normals cancel: fall back to the far vertex
      geometry.pole_vector = (geometry.positive_pole - p).normalized();
    else
      geometry.pole_vector = Eigen::Vector3d::UnitZ();
    geometry.positive_pole.setConstant(std::numeric_limits<double>::infinity());
  }
  else {
    geometry.pole_vector = (geometry.positive_pole - p).normalized();
  }

  double negative2 = -1;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c))
      continue;
    const Eigen::Vector3d to_center = cells.centers[*c] - p;
    if (to_center.dot(geometry.pole_vector) >= 0)
      continue;
    const double d2 = to_center.squaredNorm();
    if (d2 > negative2) {
      negative2 = d2;
      geometry.negative_pole = to_center + p;
    }
  }
  // The geometry is reused from sample to sample: leave no stale pole behind.
  if (!(negative2 > 0))
    geometry.negative_pole.setConstant(std::numeric_limits<double>::quiet_NaN());
  geometry.height =
      negative2 > 0 ? std::sqrt(negative2) : std::numeric_limits<double>::quiet_NaN();
}

/** The cocone radius of sample \a s for the unit axis \a axis. Every Voronoi edge of
 * its cell is the dual of a Delaunay facet (c, i) of the star; each is visited once,
 * from its finite cell or from the cell of lower number (not address: the edge is
 * clipped from that side, and the rounding must not change from run to run). An edge
 * that meets the cocone marks the facet: bit i of marks[c][position of s in c]. */
double
computeCoconeRadius(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
                    SampleIndex s, const std::uint32_t* star_begin,
                    const std::uint32_t* star_end, const Eigen::Vector3d& axis,
                    double sin_theta, std::vector<std::array<std::uint8_t, 4> >& marks)
{
  const Eigen::Vector3d& p = points[s];
  double radius2 = 0;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c))
      continue; // its finite facet at s is visited from the finite side
    const int self = cells.indexOf(*c, s);
    for (int i = 0; i < 4; ++i) {
      if (i == self)
        continue; // the facet opposite s does not contain s
      const std::uint32_t n = cells.neighbours[*c][i];
      const bool ray = !cells.isFinite(n);
      if (!ray && n < *c)
        continue; // visited from n
      const Eigen::Vector3d start = cells.centers[*c] - p;
      const Eigen::Vector3d direction =
          ray ? hullFacetNormal(cells, points, *c, i)
              : Eigen::Vector3d(cells.centers[n] - p - start);
      const EdgeInCocone clip = clipVoronoiEdge(start, direction, ray, axis, sin_theta);
      if (!clip.meets)
        continue;
      marks[*c][self] |= static_cast<std::uint8_t>(1u << i);
      if (clip.unbounded)
        radius2 = std::numeric_limits<double>::infinity();
      else if (clip.max_distance2 > radius2)
        radius2 = clip.max_distance2;
    }
  }
  return std::sqrt(radius2);
}

/** Circumcenters, poles, heights, radii and cocone marks of every sample, and the
 * marked triangles with their incidence lists. Clears \a dt once its cells are read. */
void
computeGeometry(Delaunay& dt, VoronoiCocone::Impl& d, double sin_theta)
{
  const std::size_t n = d.representative.size();

  // Number the cells: the finite ones in container order, then the infinite ones.
  // One pass: touching every cell is what costs at a million points.
  std::vector<CellHandle> all_cells, infinite_cells;
  all_cells.reserve(dt.number_of_cells());
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    if (dt.is_infinite(c)) {
      infinite_cells.push_back(c);
      continue;
    }
    c->cellIndex() = static_cast<std::uint32_t>(all_cells.size());
    all_cells.push_back(c);
  }
  const std::size_t finite_cells = all_cells.size();
  for (const CellHandle c : infinite_cells) {
    c->cellIndex() = static_cast<std::uint32_t>(all_cells.size());
    all_cells.push_back(c);
  }
  std::vector<CellHandle>().swap(infinite_cells);

  // The samples in the triangulation's vertex order, which is its insertion order, a
  // spatial one: neighbouring samples share the cells of their stars.
  std::vector<SampleIndex> samples_in_order;
  samples_in_order.reserve(d.unique_count);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    samples_in_order.push_back(v->info());

  // The star of every vertex at once (cells by sample, infinite cells after the
  // finite ones): passes over the cells instead of a search per vertex, which measured
  // twice as slow. The samples, neighbours and circumcenter of every cell are read
  // once, in parallel, so that these passes and the per-sample one scan flat arrays.
  CellTable cells;
  cells.finite = finite_cells;
  cells.centers.resize(finite_cells);
  cells.samples.resize(all_cells.size());
  cells.neighbours.resize(all_cells.size());
  const VertexHandle infinite = dt.infinite_vertex();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, all_cells.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const CellHandle c = all_cells[k];
                        for (int j = 0; j < 4; ++j) {
                          const VertexHandle v = c->vertex(j);
                          cells.samples[k][j] = v == infinite ? kNoSample : v->info();
                          cells.neighbours[k][j] = c->neighbor(j)->cellIndex();
                        }
                        if (k < finite_cells)
                          cells.centers[k] = circumcenter(c);
                      }
                    });
  // The table holds all that is read from here on: CGAL's triangulation, the largest
  // structure of the whole run, goes before the star lists are made.
  std::vector<CellHandle>().swap(all_cells);
  dt.clear();
  // Star lists in cell order, filled by a few blocks of cells at once: each block
  // counts its cells per sample, so it knows where in each list its own cells go.
  constexpr std::size_t kBlocks = 4;
  const std::size_t block_size = (cells.samples.size() + kBlocks - 1) / kBlocks;
  // Block b of the cells [0, count).
  const auto blockRange = [&](std::size_t b, std::size_t count) {
    return std::make_pair(std::min(b * block_size, count),
                          std::min((b + 1) * block_size, count));
  };
  std::vector<std::vector<std::uint32_t> > cursor(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    cursor[b].assign(n, 0);
    const auto [first, last] = blockRange(b, cells.samples.size());
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : cells.samples[k])
        if (s != kNoSample)
          ++cursor[b][s];
  });
  std::vector<std::uint32_t> star_offsets(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t at = star_offsets[i];
    for (std::size_t b = 0; b < kBlocks; ++b) // counts -> where block b starts
      at += std::exchange(cursor[b][i], at);
    star_offsets[i + 1] = at;
  }
  std::vector<std::uint32_t> star_cells(star_offsets[n]);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    const auto [first, last] = blockRange(b, cells.samples.size());
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : cells.samples[k])
        if (s != kNoSample)
          star_cells[cursor[b][s]++] = static_cast<std::uint32_t>(k);
  });
  std::vector<std::vector<std::uint32_t> >().swap(cursor);

  d.pole_vector.assign(n, Eigen::Vector3d::Zero());
  d.positive_pole.assign(n, Eigen::Vector3d::Zero());
  d.negative_pole.assign(n, Eigen::Vector3d::Zero());
  d.height.assign(n, std::numeric_limits<double>::quiet_NaN());
  d.radius.assign(n, std::numeric_limits<double>::quiet_NaN());
  d.unbounded.assign(n, 0);

  // marks[c][j] bit i: vertex j of cell c marks facet i of c. Only the thread handling
  // vertex j writes that byte, so no synchronisation is needed.
  std::vector<std::array<std::uint8_t, 4> > marks(finite_cells, {0, 0, 0, 0});
  const std::vector<Eigen::Vector3d>& points = d.centered; // the vertices' coordinates
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, samples_in_order.size(), 512),
      [&](const tbb::blocked_range<std::size_t>& range) {
        CellGeometry geometry;
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const SampleIndex s = samples_in_order[k];
          const std::uint32_t* star_begin = star_cells.data() + star_offsets[s];
          const std::uint32_t* star_end = star_cells.data() + star_offsets[s + 1];
          computePoles(cells, points, s, star_begin, star_end, geometry);
          d.pole_vector[s] = geometry.pole_vector;
          d.positive_pole[s] = geometry.positive_pole;
          d.negative_pole[s] = geometry.negative_pole;
          d.height[s] = geometry.height;
          d.unbounded[s] = geometry.unbounded ? 1 : 0;
          d.radius[s] = computeCoconeRadius(cells, points, s, star_begin, star_end,
                                            geometry.pole_vector, sin_theta, marks);
        }
      });

  // Collect the marked triangles, each from the cell that owns its facet (the same
  // rule computeCoconeRadius uses), in cell order: deterministic.
  // Most facets are marked by none of their vertices: those are skipped on the marks
  // alone, before their neighbouring cell is looked up. Blocks of cells in parallel,
  // joined in cell order.
  std::vector<std::vector<MarkedTriangle> > found(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    const auto [first, last] = blockRange(b, finite_cells);
    for (std::size_t k = first; k < last; ++k)
      for (int i = 0; i < 4; ++i) {
        MarkedTriangle triangle;
        triangle.marked_by = 0;
        for (int m = 0; m < 3; ++m) {
          const int j = (i + 1 + m) & 3;
          triangle.vertex[m] = cells.samples[k][j];
          if ((marks[k][j] >> i) & 1u)
            triangle.marked_by |= static_cast<std::uint8_t>(1u << m);
        }
        if (triangle.marked_by == 0)
          continue;
        const std::uint32_t nb = cells.neighbours[k][i];
        if (cells.isFinite(nb) && nb < k)
          continue;
        found[b].push_back(triangle);
      }
  });
  d.triangles.clear();
  std::size_t total = 0;
  for (const std::vector<MarkedTriangle>& block : found)
    total += block.size();
  d.triangles.reserve(total);
  for (std::vector<MarkedTriangle>& block : found) {
    d.triangles.insert(d.triangles.end(), block.begin(), block.end());
    std::vector<MarkedTriangle>().swap(block);
  }

  // Stitching and decimation ask the triangulation for neighbours later: they get the
  // cells' samples and the stars, not the rest of the table.
  std::vector<std::array<std::uint32_t, 4> >().swap(cells.neighbours);
  std::vector<Eigen::Vector3d>().swap(cells.centers);
  std::vector<std::array<std::uint8_t, 4> >().swap(marks);
  d.stars.cell_samples = std::move(cells.samples);
  d.stars.offsets = std::move(star_offsets);
  d.stars.cells = std::move(star_cells);

  // Incidence lists (CSR by sample).
  d.triangle_offsets.assign(n + 1, 0);
  for (const MarkedTriangle& t : d.triangles)
    for (const SampleIndex s : t.vertex)
      ++d.triangle_offsets[s + 1];
  for (std::size_t i = 0; i < n; ++i)
    d.triangle_offsets[i + 1] += d.triangle_offsets[i];
  d.triangle_ids.resize(d.triangle_offsets[n]);
  std::vector<std::uint32_t> fill(d.triangle_offsets.begin(), d.triangle_offsets.end() - 1);
  for (std::size_t t = 0; t < d.triangles.size(); ++t)
    for (const SampleIndex s : d.triangles[t].vertex)
      d.triangle_ids[fill[s]++] = static_cast<std::uint32_t>(t);
}

} // namespace

Status
VoronoiCocone::compute(const std::vector<Eigen::Vector3d>& points)
{
  Impl& d = *impl_;
  d = Impl();
  const auto fail = [&](Status status, const std::string& message) {
    Impl fresh;
    fresh.status = status;
    fresh.message = message;
    d = std::move(fresh);
    return status;
  };

  const std::size_t n = points.size();
  if (n >= static_cast<std::size_t>(kNoSample))
    return fail(Status::too_many_points, "more points than 32-bit sample indices address");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      std::ostringstream message;
      message << "point " << i << " has a non-finite coordinate";
      return fail(Status::non_finite_input, message.str());
    }
    sum += points[i];
  }
  if (n < 4)
    return fail(Status::too_few_points,
                "need at least 4 points for a 3D Voronoi diagram, got " + std::to_string(n));
  // Decide the dimension on the points as given, with exact predicates: translating
  // them to their centroid rounds each coordinate, which can lift exactly coplanar
  // points off their plane by 1e-15 and hide the degeneracy from the triangulation.
  {
    const auto at = [&](std::size_t i) {
      return Point(points[i].x(), points[i].y(), points[i].z());
    };
    std::size_t second = 1, third = 0, fourth = 0;
    while (second < n && at(second) == at(0))
      ++second;
    for (std::size_t i = second + 1; i < n && third == 0; ++i)
      if (!CGAL::collinear(at(0), at(second), at(i)))
        third = i;
    for (std::size_t i = third + 1; third != 0 && i < n && fourth == 0; ++i)
      if (CGAL::orientation(at(0), at(second), at(third), at(i)) != CGAL::COPLANAR)
        fourth = i;
    if (second == n)
      return fail(Status::too_few_points, "need at least 4 distinct points, got 1");
    if (third == 0)
      return fail(Status::degenerate_dimension,
                  "all points are collinear: no 3D Voronoi cell to measure");
    if (fourth == 0)
      return fail(Status::degenerate_dimension,
                  "all points are coplanar: no 3D Voronoi cell to measure");
  }

  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const Clock::time_point start = Clock::now();
  // The triangulation lives only through compute(): the geometry keeps what the
  // queries after it read (Impl::stars) and frees it.
  Delaunay dt;
  try {
    runInArena(threads_, [&] {
      d.offset = sum / static_cast<double>(n);
      d.centered.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        d.centered[i] = points[i] - d.offset;

      // Insert in CGAL's spatial order (a Hilbert curve on random rounds), far faster
      // than input order. This is CGAL's own bulk insertion of points with info, with
      // the sort run on every core: the same order, hence the same triangulation.
      {
        std::vector<Point> input(n);
        for (std::size_t i = 0; i < n; ++i)
          input[i] = Point(d.centered[i].x(), d.centered[i].y(), d.centered[i].z());
        std::vector<std::size_t> order(n);
        std::iota(order.begin(), order.end(), std::size_t(0));
        using SortTraits = CGAL::Spatial_sort_traits_adapter_3<
            Kernel, CGAL::Pointer_property_map<Point>::type>;
        CGAL::spatial_sort<CGAL::Parallel_if_available_tag>(
            order.begin(), order.end(), SortTraits(CGAL::make_property_map(input)));
        VertexHandle hint;
        for (const std::size_t i : order) {
          hint = dt.insert(input[i], hint);
          if (hint != VertexHandle())
            hint->info() = static_cast<SampleIndex>(i);
        }
      }

      // Identical points collapse into one vertex. Map every input point to the
      // smallest index of its group, so nothing is lost or renumbered.
      std::vector<VertexHandle> owner(n);
      for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        owner[v->info()] = v;
      d.unique_count = dt.number_of_vertices();
      Delaunay::Cell_handle hint;
      for (std::size_t i = 0; i < n; ++i) {
        if (owner[i] != VertexHandle())
          continue;
        Delaunay::Locate_type type;
        int li, lj;
        const Point query(d.centered[i].x(), d.centered[i].y(), d.centered[i].z());
        hint = dt.locate(query, type, li, lj, hint);
        if (type != Delaunay::VERTEX)
          throw std::runtime_error("a point missing from the triangulation is no vertex");
        owner[i] = hint->vertex(li);
        // CGAL kept whichever copy its spatial sort met first; name the group after
        // its smallest index instead.
        owner[i]->info() = std::min<SampleIndex>(owner[i]->info(), static_cast<SampleIndex>(i));
      }
      d.representative.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        d.representative[i] = owner[i]->info();
    });
  }
  catch (const std::bad_alloc&) {
    return fail(Status::internal_error, "out of memory while building the Delaunay triangulation");
  }
  catch (const std::exception& e) {
    return fail(Status::internal_error, std::string("Delaunay triangulation failed: ") + e.what());
  }

  if (d.unique_count < 4)
    return fail(Status::too_few_points,
                "need at least 4 distinct points, got " + std::to_string(d.unique_count));
  if (dt.dimension() < 3) {
    const int dim = dt.dimension();
    return fail(Status::degenerate_dimension,
                std::string("all points are ") + (dim == 2 ? "coplanar" : "collinear") +
                    ": no 3D Voronoi cell to measure");
  }

  d.timings.delaunay = seconds_since(start);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] Delaunay triangulation of %zu samples (%zu "
            "distinct): %.3f s\n",
            n, d.unique_count, d.timings.delaunay);
  const Clock::time_point geometry_start = Clock::now();
  try {
    runInArena(threads_, [&] { computeGeometry(dt, d, std::sin(cocone_angle_)); });
  }
  catch (const std::bad_alloc&) {
    return fail(Status::internal_error, "out of memory while computing Voronoi geometry");
  }
  catch (const std::exception& e) {
    return fail(Status::internal_error, std::string("Voronoi geometry failed: ") + e.what());
  }
  d.timings.geometry = seconds_since(geometry_start);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] poles, radii and cocone marks: %.3f s, %zu "
            "marked triangles\n",
            d.timings.geometry, d.triangles.size());
  d.status = Status::ok;
  d.message.clear();
  return Status::ok;
}

} // namespace cocone
} // namespace pcl
