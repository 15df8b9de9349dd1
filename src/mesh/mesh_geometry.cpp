// SPDX-License-Identifier: GPL-3.0-or-later
#include <pcl/cocone/core/mesh_geometry.h>

#include "common/parallel.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcl {
namespace cocone {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

/** Whether two non-degenerate triangles meet other than in the vertices and the edge
 * they share (by index). The predicates are exact (filtered), so a touching pair
 * counts as intersecting. */
bool
intersectBeyondSharedFeatures(const Point* p, const TriangleIndices& a,
                              const TriangleIndices& b)
{
  int shared = 0;
  int ia = -1, ib = -1; // positions of the (last) shared vertex in a and b
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        ++shared;
        ia = i;
        ib = j;
      }
  const Triangle ta(p[a[0]], p[a[1]], p[a[2]]);
  const Triangle tb(p[b[0]], p[b[1]], p[b[2]]);
  switch (shared) {
  case 0:
    return CGAL::do_intersect(ta, tb);
  case 1: {
    // The two triangles are convex and contain the common vertex v: if they share more
    // than v, a segment from v through a second common point leaves the first of them
    // through its edge opposite to v, at a point of the other one. And that opposite
    // edge does not contain v, so meeting it means meeting beyond v.
    const Segment opposite_a(p[a[(ia + 1) % 3]], p[a[(ia + 2) % 3]]);
    const Segment opposite_b(p[b[(ib + 1) % 3]], p[b[(ib + 2) % 3]]);
    return CGAL::do_intersect(opposite_a, tb) || CGAL::do_intersect(opposite_b, ta);
  }
  case 2: {
    // Not coplanar: the planes meet in the line of the shared edge, and the triangles
    // in the edge itself. Coplanar: they overlap iff the far vertices are on the same
    // side of the edge.
    std::uint32_t u = kNoVertex, v = kNoVertex, x = kNoVertex, y = kNoVertex;
    for (int i = 0; i < 3; ++i) {
      const bool in_b = a[i] == b[0] || a[i] == b[1] || a[i] == b[2];
      if (!in_b)
        x = a[i];
      else if (u == kNoVertex)
        u = a[i];
      else
        v = a[i];
      const bool in_a = b[i] == a[0] || b[i] == a[1] || b[i] == a[2];
      if (!in_a)
        y = b[i];
    }
    return CGAL::coplanar(p[u], p[v], p[x], p[y]) &&
           CGAL::coplanar_orientation(p[u], p[v], p[x], p[y]) == CGAL::POSITIVE;
  }
  default:
    return true; // the same triangle twice
  }
}

/** Whether the corners of \a q not marked in \a on_t (at least one) lie strictly on one
 * side of the plane of the triangle \a t, where double arithmetic is certain of it. The
 * computed orientation (t1 - t0) x (t2 - t0) . (q - t0) is off by less than 1e-14 of
 * the product of the max-norms of its three vectors (each difference of two doubles is
 * rounded once, relative to itself), so a value beyond 1e-12 of that product has the
 * sign of the exact one; anything closer is left to the exact predicates. So is
 * anything the bound does not cover: an overflow (non-finite side) or an underflow
 * (a margin below the smallest normal double, where rounding is no longer relative). */
bool
strictlyOnOneSide(const Eigen::Vector3d* const t[3], const Eigen::Vector3d* const q[3],
                  const bool on_t[3])
{
  const auto max_abs = [](double x, double y, double z) {
    return std::max({std::abs(x), std::abs(y), std::abs(z)});
  };
  const Eigen::Vector3d& p = *t[0];
  const double e1x = (*t[1])[0] - p[0], e1y = (*t[1])[1] - p[1],
               e1z = (*t[1])[2] - p[2];
  const double e2x = (*t[2])[0] - p[0], e2y = (*t[2])[1] - p[1],
               e2z = (*t[2])[2] - p[2];
  const double nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z,
               nz = e1x * e2y - e1y * e2x;
  const double scale = 1e-12 * max_abs(e1x, e1y, e1z) * max_abs(e2x, e2y, e2z);
  if (!(scale >= std::numeric_limits<double>::min()))
    return false; // tiny edges: the normal may be subnormal, its error not relative
  int sign = 0;
  for (int k = 0; k < 3; ++k) {
    if (on_t[k])
      continue;
    const double rx = (*q[k])[0] - p[0], ry = (*q[k])[1] - p[1], rz = (*q[k])[2] - p[2];
    const double side = nx * rx + ny * ry + nz * rz;
    const double margin = scale * max_abs(rx, ry, rz);
    if (!std::isfinite(side) || !(margin >= std::numeric_limits<double>::min()))
      return false;
    const int here = side > margin ? 1 : side < -margin ? -1 : 0;
    if (here == 0 || (sign != 0 && here != sign))
      return false;
    sign = here;
  }
  return sign != 0;
}

Point
toCgal(const Eigen::Vector3d& p)
{
  return Point(p.x(), p.y(), p.z());
}

/** Whether two non-degenerate triangles of \a points meet beyond the vertices and the
 * edge they share: the exact answer, with the cheap certain cases first. */
bool
crossBeyondSharedFeatures(const std::vector<Eigen::Vector3d>& points,
                          const TriangleIndices& a, const TriangleIndices& b)
{
  const Eigen::Vector3d* const pa[3] = {&points[a[0]], &points[a[1]], &points[a[2]]};
  const Eigen::Vector3d* const pb[3] = {&points[b[0]], &points[b[1]], &points[b[2]]};
  // If the corners of one that are not corners of the other lie strictly on one side of
  // the other's plane, they meet at most in their shared vertices or edge (which lie in
  // that plane): most pairs whose boxes overlap end here.
  bool b_on_a[3], a_on_b[3];
  for (int k = 0; k < 3; ++k) {
    b_on_a[k] = b[k] == a[0] || b[k] == a[1] || b[k] == a[2];
    a_on_b[k] = a[k] == b[0] || a[k] == b[1] || a[k] == b[2];
  }
  if (strictlyOnOneSide(pa, pb, b_on_a) || strictlyOnOneSide(pb, pa, a_on_b))
    return false;
  // Local copies, indexed like the points, only for the (at most six) corners used.
  std::array<Point, 6> corners;
  TriangleIndices la{}, lb{};
  std::array<std::uint32_t, 6> global{};
  int used = 0;
  const auto local = [&](std::uint32_t v) {
    for (int k = 0; k < used; ++k)
      if (global[k] == v)
        return static_cast<std::uint32_t>(k);
    global[used] = v;
    corners[used] = toCgal(points[v]);
    return static_cast<std::uint32_t>(used++);
  };
  for (int k = 0; k < 3; ++k)
    la[k] = local(a[k]);
  for (int k = 0; k < 3; ++k)
    lb[k] = local(b[k]);
  return intersectBeyondSharedFeatures(corners.data(), la, lb);
}

/** The closed bounding box of one triangle of a mesh. */
struct TriangleBox
{
  Eigen::Vector3d lo, hi;
  std::size_t triangle;

  bool
  overlaps(const TriangleBox& other) const
  {
    return (lo.array() <= other.hi.array()).all() &&
           (other.lo.array() <= hi.array()).all();
  }
};

/** Calls \a report(a, b) once for each pair of \a boxes that overlap (closed boxes:
 * touching counts), with their triangles' positions.
 *
 * A mesh's triangles are small against the mesh and alike in size, so a uniform grid
 * of cells twice the median box's largest side finds the pairs with a few box tests
 * per triangle: each box goes into the cells it covers, the boxes of one cell are
 * tested against each other, and a pair is reported only in the cell that holds the
 * lowest corner of the two boxes' intersection. On the 100k torus's 200k triangles this
 * is 4 times faster than CGAL's box_self_intersection_d. Where the grid would not pay
 * (boxes spread over too many cells, or too many boxes in some cells, for instance a
 * few huge triangles over a dense mesh), CGAL's segment tree does the work instead:
 * its O(T log^3 T) bound holds for any mesh.
 *
 * The grid's cells are tested on up to \a threads threads (0: every core), so
 * \a report may be called from several threads at once; the segment tree calls it
 * from one. */
template <typename Report>
void
forEachOverlappingPair(const std::vector<TriangleBox>& boxes, unsigned threads,
                       Report&& report)
{
  const auto withCgal = [&] {
    using Box = CGAL::Box_intersection_d::Box_with_info_d<
        double, 3, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
    std::vector<Box> cgal;
    cgal.reserve(boxes.size());
    for (const TriangleBox& b : boxes)
      cgal.emplace_back(
          CGAL::Bbox_3(b.lo.x(), b.lo.y(), b.lo.z(), b.hi.x(), b.hi.y(), b.hi.z()),
          b.triangle);
    CGAL::box_self_intersection_d(
        cgal.begin(), cgal.end(),
        [&](const Box& a, const Box& b) { report(a.info(), b.info()); });
  };
  if (boxes.size() < 2)
    return;
  // The cell: twice the median largest side (a side of 0 everywhere: no grid).
  std::vector<double> sides(boxes.size());
  Eigen::Vector3d origin = boxes.front().lo, top = boxes.front().hi;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    sides[i] = (boxes[i].hi - boxes[i].lo).maxCoeff();
    origin = origin.cwiseMin(boxes[i].lo);
    top = top.cwiseMax(boxes[i].hi);
  }
  const auto median = sides.begin() + static_cast<std::ptrdiff_t>(sides.size() / 2);
  std::nth_element(sides.begin(), median, sides.end());
  // 2^20 cells along an axis at most, so that a cell's three coordinates fit one key.
  constexpr double kMaxCellsPerAxis = 1 << 20;
  const double cell =
      std::max(2 * *median, (top - origin).maxCoeff() / kMaxCellsPerAxis);
  // Multiplying by the reciprocal is cheaper than dividing. Like the division, it is
  // one monotone function for every box and every overlap's corner, so that an
  // overlap's cell is among the cells of both its boxes. A subnormal cell (a mesh
  // narrower than about 1e-302) would make the reciprocal infinite.
  const double per_cell = 1 / cell;
  if (!(cell > 0) || !std::isfinite(cell) || !std::isfinite(per_cell))
    return withCgal();
  const auto cellOf = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d c = ((x - origin) * per_cell).array().floor();
    return Eigen::Array<std::uint64_t, 3, 1>(
        std::min(static_cast<std::uint64_t>(c.x()), std::uint64_t(kMaxCellsPerAxis)),
        std::min(static_cast<std::uint64_t>(c.y()), std::uint64_t(kMaxCellsPerAxis)),
        std::min(static_cast<std::uint64_t>(c.z()), std::uint64_t(kMaxCellsPerAxis)));
  };
  const auto keyOf = [](std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    return (x << 42) | (y << 21) | z;
  };
  // Budgets: 8 cells per box on average, and 128 box tests per box (about 30 on an
  // even mesh); beyond either, the grid is no better than the segment tree.
  const std::size_t max_entries = 8 * boxes.size(), max_tests = 128 * boxes.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
  entries.reserve(2 * boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const auto low = cellOf(boxes[i].lo), high = cellOf(boxes[i].hi);
    const std::uint64_t covered =
        (high - low + 1).prod(); // at most (2^20 + 1)^3: no overflow in 64 bits
    if (covered > max_entries || entries.size() + covered > max_entries)
      return withCgal();
    for (std::uint64_t x = low.x(); x <= high.x(); ++x)
      for (std::uint64_t y = low.y(); y <= high.y(); ++y)
        for (std::uint64_t z = low.z(); z <= high.z(); ++z)
          entries.emplace_back(keyOf(x, y, z), static_cast<std::uint32_t>(i));
  }
  // (cell, box) pairs are distinct: any sort gives the one order.
  detail::runInArena(threads,
                     [&] { tbb::parallel_sort(entries.begin(), entries.end()); });
  // Where each cell's boxes begin in entries, and the end.
  std::vector<std::size_t> cell_begin;
  std::size_t tests = 0;
  for (std::size_t begin = 0, end = 0; begin < entries.size(); begin = end) {
    while (end < entries.size() && entries[end].first == entries[begin].first)
      ++end;
    const std::size_t in_cell = end - begin;
    tests += in_cell * (in_cell - 1) / 2;
    if (tests > max_tests)
      return withCgal(); // nothing reported yet: the pairs are all found there
    cell_begin.push_back(begin);
  }
  cell_begin.push_back(entries.size());
  const auto testCell = [&](std::size_t c) {
    const std::size_t begin = cell_begin[c], end = cell_begin[c + 1];
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t j = i + 1; j < end; ++j) {
        const TriangleBox& a = boxes[entries[i].second];
        const TriangleBox& b = boxes[entries[j].second];
        if (!a.overlaps(b))
          continue;
        // Once per pair: in the cell that holds the low corner of the overlap.
        const auto first = cellOf(a.lo.cwiseMax(b.lo));
        if (keyOf(first.x(), first.y(), first.z()) == entries[begin].first)
          report(a.triangle, b.triangle);
      }
  };
  detail::runInArena(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cell_begin.size() - 1, 256),
                      [&](const tbb::blocked_range<std::size_t>& cells) {
                        for (std::size_t c = cells.begin(); c != cells.end(); ++c)
                          testCell(c);
                      });
  });
}

} // namespace

bool
trianglesIntersect(const std::vector<Eigen::Vector3d>& points, const TriangleIndices& a,
                   const TriangleIndices& b)
{
  for (int k = 0; k < 3; ++k)
    if (a[k] >= points.size() || b[k] >= points.size())
      throw std::out_of_range("triangle vertex index " +
                              std::to_string(std::max(a[k], b[k])) + " out of range (" +
                              std::to_string(points.size()) + " points)");
  // Separated bounding boxes: no contact (strict comparison, so touching boxes go on to
  // the exact test).
  for (int axis = 0; axis < 3; ++axis) {
    const double a0 = points[a[0]][axis], a1 = points[a[1]][axis],
                 a2 = points[a[2]][axis];
    const double b0 = points[b[0]][axis], b1 = points[b[1]][axis],
                 b2 = points[b[2]][axis];
    if (std::max({a0, a1, a2}) < std::min({b0, b1, b2}) ||
        std::max({b0, b1, b2}) < std::min({a0, a1, a2}))
      return false;
  }
  for (int k = 0; k < 3; ++k)
    if (!points[a[k]].allFinite() || !points[b[k]].allFinite())
      return false; // no geometry to meet
  if (CGAL::collinear(toCgal(points[a[0]]), toCgal(points[a[1]]),
                      toCgal(points[a[2]])) ||
      CGAL::collinear(toCgal(points[b[0]]), toCgal(points[b[1]]), toCgal(points[b[2]])))
    return false; // no interior to intersect
  return crossBeyondSharedFeatures(points, a, b);
}

bool
segmentCrossesTriangle(const std::vector<Eigen::Vector3d>& points, std::uint32_t a,
                       std::uint32_t b, const TriangleIndices& t)
{
  const Point pa = toCgal(points.at(a)), pb = toCgal(points.at(b));
  const Point p0 = toCgal(points.at(t[0])), p1 = toCgal(points.at(t[1])),
              p2 = toCgal(points.at(t[2]));
  if (CGAL::collinear(p0, p1, p2))
    return false; // no area to meet
  const auto slot = [&](std::uint32_t v) {
    for (int k = 0; k < 3; ++k)
      if (t[k] == v)
        return k;
    return -1;
  };
  const int slot_a = slot(a), slot_b = slot(b);
  if (slot_a >= 0 && slot_b >= 0)
    return false; // an edge of t
  if (slot_a < 0 && slot_b < 0)
    return CGAL::do_intersect(Segment(pa, pb), Triangle(p0, p1, p2));
  // One shared vertex s; the segment leaves it towards the other end q. Off the plane
  // of t, it meets that plane only at s. In the plane, it enters t exactly when q lies
  // in the closed angle of t at s (along an edge it runs over that edge).
  const int shared = slot_a >= 0 ? slot_a : slot_b;
  const Point& s = shared == 0 ? p0 : shared == 1 ? p1 : p2;
  const Point& q = slot_a >= 0 ? pb : pa;
  const Point& x = shared == 0 ? p1 : p0;
  const Point& y = shared == 2 ? p1 : p2;
  if (!CGAL::coplanar(s, x, y, q))
    return false;
  return CGAL::coplanar_orientation(s, x, y, q) != CGAL::NEGATIVE &&
         CGAL::coplanar_orientation(s, y, x, q) != CGAL::NEGATIVE;
}

std::vector<std::pair<std::size_t, std::size_t>>
findSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                      const std::vector<TriangleIndices>& triangles, unsigned threads)
{
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t)
      if (v >= points.size())
        throw std::out_of_range("triangle vertex index " + std::to_string(v) +
                                " out of range (" + std::to_string(points.size()) +
                                " points)");
  std::vector<TriangleBox> boxes;
  boxes.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const TriangleIndices& tri = triangles[t];
    const Eigen::Vector3d &a = points[tri[0]], &b = points[tri[1]], &c = points[tri[2]];
    // A triangle without area (repeated index or collinear corners) has no interior to
    // intersect; analyzeTriangleMesh reports the combinatorial ones. One with a
    // non-finite corner has no geometry at all.
    if (!a.allFinite() || !b.allFinite() || !c.allFinite() ||
        CGAL::collinear(toCgal(a), toCgal(b), toCgal(c)))
      continue;
    boxes.push_back({a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), t});
  }
  using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;
  tbb::enumerable_thread_specific<Pairs> found;
  forEachOverlappingPair(boxes, threads, [&](std::size_t a, std::size_t b) {
    if (crossBeyondSharedFeatures(points, triangles[a], triangles[b]))
      found.local().emplace_back(std::min(a, b), std::max(a, b));
  });
  // The pairs are met in an order of the boxes' and the threads' choosing.
  Pairs pairs;
  for (const Pairs& some : found)
    pairs.insert(pairs.end(), some.begin(), some.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::size_t
countSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<TriangleIndices>& triangles, unsigned threads)
{
  return findSelfIntersections(points, triangles, threads).size();
}

} // namespace cocone
} // namespace pcl
