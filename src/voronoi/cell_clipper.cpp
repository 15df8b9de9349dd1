// SPDX-License-Identifier: GPL-3.0-or-later
#include "voronoi/cell_clipper.h"

#include "voronoi/cocone_edge.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

// The box is spanned by the frame (t1, t2, axis). Corner c has signs
// (c & 1, c & 2, c & 4) on (t1, t2, axis). Faces list their corners counter-clockwise
// seen from outside.
constexpr std::array<std::array<int, 4>, 6> kBoxFaces = {{
    {4, 5, 7, 6}, // +axis
    {0, 2, 3, 1}, // -axis
    {1, 3, 7, 5}, // +t1
    {0, 4, 6, 2}, // -t1
    {2, 6, 7, 3}, // +t2
    {0, 1, 5, 4}, // -t2
}};

int
boxFacePlane(int face)
{
  return -1 - face;
}

// For each face and corner slot, the box face across the edge starting there.
std::array<std::array<int, 4>, 6>
makeBoxAcross()
{
  std::array<std::array<int, 4>, 6> across{};
  for (int f = 0; f < 6; ++f)
    for (int k = 0; k < 4; ++k) {
      const int a = kBoxFaces[f][k];
      const int b = kBoxFaces[f][(k + 1) % 4];
      for (int g = 0; g < 6; ++g)
        for (int m = 0; m < 4; ++m)
          if (kBoxFaces[g][m] == b && kBoxFaces[g][(m + 1) % 4] == a)
            across[f][k] = boxFacePlane(g);
    }
  return across;
}

const std::array<std::array<int, 4>, 6> kBoxAcross = makeBoxAcross();

bool
lexicographicLess(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  if (a.x() != b.x())
    return a.x() < b.x();
  if (a.y() != b.y())
    return a.y() < b.y();
  return a.z() < b.z();
}

// The same point whichever face computes it: the two faces sharing an edge traverse it
// in opposite directions, so order the ends first.
Eigen::Vector3d
crossing(Eigen::Vector3d a, double da, Eigen::Vector3d b, double db)
{
  if (lexicographicLess(b, a)) {
    std::swap(a, b);
    std::swap(da, db);
  }
  return a + (da / (da - db)) * (b - a);
}

} // namespace

void
CoconeCellClipper::resetToBox(const Eigen::Vector3d& axis, double half_width,
                              double half_height)
{
  const Eigen::Vector3d t1 = axis.unitOrthogonal();
  const Eigen::Vector3d t2 = axis.cross(t1);
  std::array<Eigen::Vector3d, 8> corner;
  for (int c = 0; c < 8; ++c)
    corner[c] = ((c & 1) ? half_width : -half_width) * t1 +
                ((c & 2) ? half_width : -half_width) * t2 +
                ((c & 4) ? half_height : -half_height) * axis;
  corners_.clear();
  faces_.clear();
  for (int f = 0; f < 6; ++f) {
    faces_.push_back({boxFacePlane(f), static_cast<std::uint32_t>(corners_.size()), 4});
    for (int k = 0; k < 4; ++k)
      corners_.push_back({corner[kBoxFaces[f][k]], kBoxAcross[f][k]});
  }
  max_corner_norm2_ = corner[0].squaredNorm();
}

void
CoconeCellClipper::clip(const Eigen::Vector3d& normal, double offset, int plane)
{
  // Corners within a relative 1e-12 of the plane count as on it (kept), so that a
  // plane through a corner does not create slivers of rounding size.
  const double tolerance =
      1e-12 * (std::abs(offset) + normal.norm() * std::sqrt(max_corner_norm2_));
  distance_.resize(corners_.size());
  bool any_outside = false;
  for (std::size_t k = 0; k < corners_.size(); ++k) {
    double d = normal.dot(corners_[k].position) - offset;
    if (std::abs(d) <= tolerance)
      d = 0;
    distance_[k] = d;
    any_outside |= d > 0;
  }
  if (!any_outside)
    return;

  next_corners_.clear();
  next_faces_.clear();
  cuts_.clear();
  for (const Face& face : faces_) {
    const std::uint32_t first = static_cast<std::uint32_t>(next_corners_.size());
    Eigen::Vector3d exit_point = Eigen::Vector3d::Zero();
    Eigen::Vector3d entry_point = Eigen::Vector3d::Zero();
    bool has_exit = false, has_entry = false;
    for (std::uint32_t k = 0; k < face.count; ++k) {
      const std::uint32_t ia = face.first + k;
      const std::uint32_t ib = face.first + (k + 1) % face.count;
      const Corner& a = corners_[ia];
      const double da = distance_[ia];
      const double db = distance_[ib];
      const bool a_in = da <= 0;
      const bool b_in = db <= 0;
      if (a_in) {
        if (b_in || da == 0) {
          // The whole edge stays, or it leaves from a corner on the plane: then the
          // corner itself is where the face is left.
          next_corners_.push_back({a.position, (b_in ? a.across : plane)});
          if (!b_in) {
            exit_point = a.position;
            has_exit = true;
          }
        }
        else {
          next_corners_.push_back(a);
          exit_point = crossing(a.position, da, corners_[ib].position, db);
          has_exit = true;
          next_corners_.push_back({exit_point, plane});
        }
      }
      else if (b_in) {
        entry_point = db == 0 ? corners_[ib].position
                              : crossing(a.position, da, corners_[ib].position, db);
        has_entry = true;
        if (db != 0)
          next_corners_.push_back({entry_point, a.across});
      }
    }
    const std::uint32_t count =
        static_cast<std::uint32_t>(next_corners_.size()) - first;
    if (count >= 3)
      next_faces_.push_back({face.plane, first, count});
    else
      next_corners_.resize(first);
    if (has_exit && has_entry && count >= 3 &&
        (exit_point - entry_point).squaredNorm() > tolerance * tolerance)
      cuts_.push_back({entry_point, exit_point, face.plane});
  }

  // The new face: face F's cut edge runs from where F is left (to) to where it is
  // entered again (from); the new face walks it the other way, from -> to, with F
  // across. The next edge starts where this one ends.
  if (cuts_.size() >= 3) {
    const std::uint32_t first = static_cast<std::uint32_t>(next_corners_.size());
    std::size_t remaining = cuts_.size();
    std::size_t current = 0;
    while (true) {
      const Cut cut = cuts_[current];
      next_corners_.push_back({cut.from, cut.plane});
      std::swap(cuts_[current], cuts_[--remaining]); // set it aside
      if (remaining == 0)
        break;
      std::size_t best = 0;
      double best_distance = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < remaining; ++j) {
        const double distance = (cuts_[j].from - cut.to).squaredNorm();
        if (distance < best_distance) {
          best_distance = distance;
          best = j;
        }
      }
      current = best;
    }
    next_faces_.push_back(
        {plane, first, static_cast<std::uint32_t>(next_corners_.size()) - first});
  }
  std::swap(corners_, next_corners_);
  std::swap(faces_, next_faces_);
  max_corner_norm2_ = 0;
  for (const Corner& c : corners_)
    max_corner_norm2_ = std::max(max_corner_norm2_, c.position.squaredNorm());
}

void
CoconeCellClipper::clipAll(const std::vector<Eigen::Vector3d>& offsets)
{
  order_.clear();
  for (std::size_t k = 0; k < offsets.size(); ++k)
    order_.emplace_back(offsets[k].squaredNorm(), static_cast<int>(k));
  std::sort(order_.begin(), order_.end());
  for (const auto& [norm2, k] : order_) {
    // A bisector at distance |d| / 2 cannot cut a cell whose corners are all closer.
    if (norm2 > 4 * max_corner_norm2_)
      break;
    clip(offsets[k], 0.5 * norm2, k);
  }
}

CoconeCellClipper::Result
CoconeCellClipper::measureRadius(const Eigen::Vector3d& axis, double sin_theta,
                                 double limit) const
{
  double radius2 = 0;
  for (const Face& face : faces_) {
    if (face.plane < 0)
      continue;
    for (std::uint32_t k = 0; k < face.count; ++k) {
      const Corner& a = corners_[face.first + k];
      // A Voronoi edge lies between two bisector faces; visit it from the lower one.
      if (a.across < 0 || a.across < face.plane)
        continue;
      const Corner& b = corners_[face.first + (k + 1) % face.count];
      const EdgeInCocone piece =
          clipVoronoiEdge(a.position, b.position - a.position, false, axis, sin_theta);
      if (piece.meets)
        radius2 = std::max(radius2, piece.max_distance2);
    }
  }
  Result result;
  result.radius = std::sqrt(radius2);
  result.reached_limit = result.radius >= limit * (1 - 1e-9);
  return result;
}

void
CoconeCellClipper::clipBox(const Eigen::Vector3d& axis, double half_width,
                           double half_height,
                           const std::vector<Eigen::Vector3d>& offsets,
                           std::vector<int>* neighbours, const Eigen::Vector3d* cut)
{
  resetToBox(axis, half_width, half_height);
  if (cut)
    clip(*cut, 0, kCutPlane);
  clipAll(offsets);
  if (neighbours) {
    neighbours->clear();
    for (const Face& face : faces_)
      if (face.plane >= 0 && face.plane != kCutPlane)
        neighbours->push_back(face.plane);
  }
}

CoconeCellClipper::Result
CoconeCellClipper::coconeRadius(const Eigen::Vector3d& axis, double sin_theta,
                                double limit, double margin,
                                const std::vector<Eigen::Vector3d>& offsets,
                                std::vector<int>* neighbours,
                                const Eigen::Vector3d* cut)
{
  // Every point of the cocone closer than `limit` lies in this box: |y.axis| <=
  // sin(theta) |y| <= sin(theta) limit.
  const double half_width = std::max(1.0, margin) * limit;
  clipBox(axis, half_width, half_width * sin_theta * (1 + 1e-9), offsets, neighbours,
          cut);
  return measureRadius(axis, sin_theta, limit);
}

CoconeCellClipper::Result
CoconeCellClipper::fullCell(const Eigen::Vector3d& axis, double sin_theta,
                            double extent, const std::vector<Eigen::Vector3d>& offsets,
                            std::vector<int>& neighbours, const Eigen::Vector3d* cut)
{
  clipBox(axis, extent, extent, offsets, &neighbours, cut);
  // The cube is no cocone-shaped box: an edge reaching it is a ray to infinity, and a
  // cocone point on it lies at least `extent` away.
  return measureRadius(axis, sin_theta, extent);
}

} // namespace detail
} // namespace cocone
} // namespace pcl
