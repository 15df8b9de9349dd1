// SPDX-License-Identifier: GPL-3.0-or-later
#include <pcl/cocone/core/mesh_geometry.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
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
 * sign of the exact one; anything closer is left to the exact predicates. */
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
  int sign = 0;
  for (int k = 0; k < 3; ++k) {
    if (on_t[k])
      continue;
    const double rx = (*q[k])[0] - p[0], ry = (*q[k])[1] - p[1], rz = (*q[k])[2] - p[2];
    const double side = nx * rx + ny * ry + nz * rz;
    const double margin = scale * max_abs(rx, ry, rz);
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
  const Eigen::Vector3d* const pa[3] = {&points[a[0]], &points[a[1]], &points[a[2]]};
  const Eigen::Vector3d* const pb[3] = {&points[b[0]], &points[b[1]], &points[b[2]]};
  // Separated bounding boxes: no contact (strict comparison, so touching boxes go on to
  // the exact test).
  for (int axis = 0; axis < 3; ++axis) {
    const double a0 = (*pa[0])[axis], a1 = (*pa[1])[axis], a2 = (*pa[2])[axis];
    const double b0 = (*pb[0])[axis], b1 = (*pb[1])[axis], b2 = (*pb[2])[axis];
    if (std::max({a0, a1, a2}) < std::min({b0, b1, b2}) ||
        std::max({b0, b1, b2}) < std::min({a0, a1, a2}))
      return false;
  }
  // If the corners of one that are not corners of the other lie strictly on one side of
  // the other's plane, they meet at most in their shared vertices or edge (which lie in
  // that plane): most pairs that pass the boxes end here.
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
  if (CGAL::collinear(corners[la[0]], corners[la[1]], corners[la[2]]) ||
      CGAL::collinear(corners[lb[0]], corners[lb[1]], corners[lb[2]]))
    return false; // no interior to intersect
  return intersectBeyondSharedFeatures(corners.data(), la, lb);
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
                      const std::vector<TriangleIndices>& triangles)
{
  for (const TriangleIndices& t : triangles)
    for (const std::uint32_t v : t)
      if (v >= points.size())
        throw std::out_of_range("triangle vertex index " + std::to_string(v) +
                                " out of range (" + std::to_string(points.size()) +
                                " points)");
  std::vector<Point> p;
  p.reserve(points.size());
  for (const Eigen::Vector3d& q : points)
    p.push_back(toCgal(q));
  using Box =
      CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t,
                                                CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const TriangleIndices& tri = triangles[t];
    // A triangle without area (repeated index or collinear corners) has no interior to
    // intersect; analyzeTriangleMesh reports the combinatorial ones.
    if (CGAL::collinear(p[tri[0]], p[tri[1]], p[tri[2]]))
      continue;
    boxes.emplace_back(p[tri[0]].bbox() + p[tri[1]].bbox() + p[tri[2]].bbox(), t);
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
        if (intersectBeyondSharedFeatures(p.data(), triangles[a.info()],
                                          triangles[b.info()]))
          pairs.emplace_back(std::min(a.info(), b.info()),
                             std::max(a.info(), b.info()));
      });
  // CGAL meets the boxes in an order of its choosing.
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::size_t
countSelfIntersections(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<TriangleIndices>& triangles)
{
  return findSelfIntersections(points, triangles).size();
}

} // namespace cocone
} // namespace pcl
