// SPDX-License-Identifier: GPL-3.0-or-later
#include "denoise/restore.h"

#include "reconstruction/least_area_fill.h"

#include <pcl/cocone/core/mesh_geometry.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <numeric>
#include <set>
#include <cstdint>
#include <unordered_set>
#include <utility>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

std::uint64_t
edgeKey(std::uint32_t a, std::uint32_t b)
{
  if (a > b)
    std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}

/** The bounding box of triangle \a t of \a points. */
Eigen::AlignedBox3d
triangleBox(const std::vector<Eigen::Vector3d>& points, const TriangleIndices& t)
{
  Eigen::AlignedBox3d box(points[t[0]]);
  box.extend(points[t[1]]);
  box.extend(points[t[2]]);
  return box;
}

/** The triangles at each vertex, in triangle order (a counting sort by vertex: sorting
 * (vertex, triangle) pairs took 3 s at 4M samples): those at v are incident[offsets[v]]
 * to incident[offsets[v + 1]] (exclusive). */
struct VertexIncidence
{
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> incident;

  VertexIncidence(const std::vector<TriangleIndices>& triangles, std::size_t vertices)
    : offsets(vertices + 1, 0)
  {
    for (const TriangleIndices& t : triangles)
      for (const std::uint32_t v : t)
        ++offsets[v + 1];
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    incident.resize(offsets.back());
    std::vector<std::size_t> cursor(offsets.begin(), offsets.end() - 1);
    for (std::uint32_t t = 0; t < triangles.size(); ++t)
      for (const std::uint32_t v : triangles[t])
        incident[cursor[v]++] = t;
  }

  const std::uint32_t*
  begin(std::uint32_t v) const
  {
    return incident.data() + offsets[v];
  }
  const std::uint32_t*
  end(std::uint32_t v) const
  {
    return incident.data() + offsets[v + 1];
  }
};

/** Fills the holes of \a triangles through a vertex flagged in \a touched; returns the
 * number of triangles added. */
std::size_t
fillHoles(const std::vector<Eigen::Vector3d>& points,
          const std::vector<std::uint8_t>& touched,
          std::vector<TriangleIndices>& triangles)
{
  const MeshTopology topology = analyzeTriangleMesh(triangles);
  // The holes to fill: loops through a touched vertex, small enough to fill.
  std::vector<const std::vector<std::uint32_t>*> holes;
  std::vector<std::uint8_t> on_hole(points.size(), 0);
  for (const std::vector<std::uint32_t>& loop : topology.boundary_loops) {
    if (loop.size() > kMaxRestoreLoop ||
        std::none_of(loop.begin(), loop.end(),
                     [&](std::uint32_t v) { return touched[v] != 0; }))
      continue;
    holes.push_back(&loop);
    for (const std::uint32_t v : loop)
      on_hole[v] = 1;
  }
  // A fill asks whether two of its loop's vertices are joined by an edge, and must not
  // repeat a triangle of the mesh, all of whose vertices would then be on the loop: the
  // boundary of a triangle left alone is a loop whose least-area fill is the triangle
  // itself. So the sets hold only the edges and triangles among the holes' vertices
  // (sets of the whole mesh took 8 s at 4M samples).
  const auto on_holes = [&](const TriangleIndices& t) {
    return on_hole[t[0]] && on_hole[t[1]] && on_hole[t[2]];
  };
  std::unordered_set<std::uint64_t> edges;
  for (const TriangleIndices& t : triangles)
    for (int k = 0; k < 3; ++k)
      if (on_hole[t[k]] && on_hole[t[(k + 1) % 3]])
        edges.insert(edgeKey(t[k], t[(k + 1) % 3]));
  const auto is_edge = [&](std::uint32_t a, std::uint32_t b) {
    return edges.count(edgeKey(a, b)) > 0;
  };
  std::set<std::array<std::uint32_t, 3>> present;
  const auto sorted = [](TriangleIndices t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  for (const TriangleIndices& t : triangles)
    if (on_holes(t))
      present.insert(sorted(t));
  std::size_t added = 0;
  LeastAreaFillScratch scratch;
  std::vector<TriangleIndices> obstacles, fill;
  std::vector<std::uint32_t> blockers;
  for (const std::vector<std::uint32_t>* hole : holes) {
    const std::vector<std::uint32_t>& loop = *hole;
    Eigen::AlignedBox3d box;
    for (const std::uint32_t v : loop)
      box.extend(points[v]);
    // The fill stays near its loop: the triangles whose box meets the loop's, grown
    // by its own size, are the ones it could cross.
    box.extend(box.max() + box.diagonal());
    box.extend(box.min() - box.diagonal());
    obstacles.clear();
    for (const TriangleIndices& t : triangles) {
      if (triangleBox(points, t).intersects(box))
        obstacles.push_back(t);
    }
    if (!fillLoopByLeastArea(points, loop, is_edge, obstacles, fill, blockers,
                             scratch) ||
        std::any_of(fill.begin(), fill.end(), [&](const TriangleIndices& t) {
          return present.count(sorted(t)) > 0;
        }))
      continue;
    for (const TriangleIndices& t : fill) {
      present.insert(sorted(t));
      triangles.push_back(t);
      for (int k = 0; k < 3; ++k)
        edges.insert(edgeKey(t[k], t[(k + 1) % 3]));
    }
    added += fill.size();
  }
  return added;
}

/** Removes the triangles flagged in \a removed (one flag per triangle), keeping the
 * order of the others, and flags their vertices in \a touched; returns how many went.
 */
std::size_t
removeFlagged(std::vector<TriangleIndices>& triangles,
              const std::vector<std::uint8_t>& removed,
              std::vector<std::uint8_t>& touched)
{
  std::size_t kept = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (removed[t]) {
      for (const std::uint32_t v : triangles[t])
        touched[v] = 1;
      continue;
    }
    triangles[kept++] = triangles[t];
  }
  const std::size_t gone = triangles.size() - kept;
  triangles.resize(kept);
  return gone;
}

/** Removes, at every vertex where the triangles of \a triangles form more than one fan
 * (triangles joined through edges at the vertex), every fan but the one with the most
 * triangles (ties: the one holding the earliest triangle), until every vertex has one
 * fan: removing crossing triangles can pinch the mesh there. Flags the vertices of the
 * removed triangles in \a touched, which has an entry for every vertex; returns how
 * many were removed. \a at is the incidence of \a triangles, rebuilt whenever some go:
 * on return, that of the triangles left (the scrap search reads it next). */
std::size_t
removePinches(std::vector<TriangleIndices>& triangles,
              std::vector<std::uint8_t>& touched, VertexIncidence& at)
{
  std::size_t removed_total = 0;
  for (;;) {
    std::vector<std::uint8_t> removed(triangles.size(), 0);
    std::size_t removed_now = 0;
    std::vector<std::uint32_t> around, fan_of, size_of;
    for (std::uint32_t v = 0; v < touched.size(); ++v) {
      if (at.begin(v) == at.end(v))
        continue;
      around.assign(at.begin(v), at.end(v));
      // Fans by union of the triangles at v that share an edge at v (a second vertex).
      const std::size_t m = around.size();
      fan_of.assign(m, 0);
      for (std::size_t i = 0; i < m; ++i)
        fan_of[i] = static_cast<std::uint32_t>(i);
      const auto root = [&](std::uint32_t i) {
        while (fan_of[i] != i)
          i = fan_of[i] = fan_of[fan_of[i]];
        return i;
      };
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = i + 1; j < m; ++j) {
          int shared = 0;
          for (const std::uint32_t a : triangles[around[i]])
            for (const std::uint32_t b : triangles[around[j]])
              shared += a == b;
          if (shared >= 2) // v and one more vertex: an edge at v
            fan_of[root(static_cast<std::uint32_t>(i))] =
                root(static_cast<std::uint32_t>(j));
        }
      size_of.assign(m, 0);
      for (std::size_t i = 0; i < m; ++i)
        ++size_of[root(static_cast<std::uint32_t>(i))];
      std::uint32_t keep = root(0);
      for (std::size_t i = 0; i < m; ++i)
        if (size_of[root(static_cast<std::uint32_t>(i))] > size_of[keep])
          keep = root(static_cast<std::uint32_t>(i));
      for (std::size_t i = 0; i < m; ++i)
        if (root(static_cast<std::uint32_t>(i)) != keep && !removed[around[i]]) {
          removed[around[i]] = 1;
          ++removed_now;
        }
    }
    if (removed_now == 0)
      return removed_total;
    removed_total += removeFlagged(triangles, removed, touched);
    at = VertexIncidence(triangles, touched.size());
  }
}

/** Removes the components of \a triangles (joined through edges) of at most
 * kMaxRestoreScrap triangles whose boundary vertices were all \a repaired (and at
 * least one vertex): scraps the repair cut off, such as a lone triangle whose
 * neighbours crossed others and whose own loop no fill can close (its least-area fill
 * is itself), or a small fan around an untouched vertex. A small piece the mesher made
 * on its own keeps some boundary vertex the repair did not touch, and stays. Returns
 * how many triangles were removed.
 *
 * Such a piece holds a repaired vertex, so only the pieces at repaired vertices are
 * explored, each until it is whole or larger than a scrap (the same decision as over
 * every piece of the mesh: a union-find over every edge took 2.8 s at 4M samples).
 * \a at is the incidence of \a triangles (removePinches leaves it so). */
std::size_t
removeRepairScraps(std::vector<TriangleIndices>& triangles,
                   const std::vector<std::uint8_t>& repaired, const VertexIncidence& at)
{
  enum : std::uint8_t
  {
    kUnseen,
    kInPiece, // of the piece being explored
    kSmall,   // of a whole piece of at most kMaxRestoreScrap triangles, kept
    kScrap,   // of such a piece whose rim the repair made: removed
    kLarge    // of a piece larger than kMaxRestoreScrap triangles
  };
  std::vector<std::uint8_t> state(triangles.size(), kUnseen);
  std::vector<std::uint32_t> piece;
  for (std::uint32_t v = 0; v < repaired.size(); ++v) {
    if (!repaired[v])
      continue;
    for (const std::uint32_t* seed = at.begin(v); seed != at.end(v); ++seed) {
      if (state[*seed] != kUnseen)
        continue;
      piece.assign(1, *seed);
      state[*seed] = kInPiece;
      bool large = false, rim_repaired = true;
      for (std::size_t i = 0; i < piece.size() && !large; ++i) {
        const TriangleIndices& t = triangles[piece[i]];
        for (int k = 0; k < 3 && !large; ++k) {
          const std::uint32_t a = t[k], b = t[(k + 1) % 3];
          // The triangles on edge a b, this one included: those at the end with fewer
          // that hold the other end (a fan's hub may hold thousands).
          const bool from_a = at.end(a) - at.begin(a) <= at.end(b) - at.begin(b);
          const std::uint32_t scanned = from_a ? a : b, other = from_a ? b : a;
          std::size_t on_edge = 0;
          for (const std::uint32_t* u = at.begin(scanned);
               u != at.end(scanned) && !large; ++u) {
            const TriangleIndices& o = triangles[*u];
            if (o[0] != other && o[1] != other && o[2] != other)
              continue;
            ++on_edge;
            if (state[*u] == kLarge ||
                (state[*u] == kUnseen && piece.size() >= kMaxRestoreScrap)) {
              large = true;
            }
            else if (state[*u] == kUnseen) {
              state[*u] = kInPiece;
              piece.push_back(*u);
            }
          }
          // A side on one triangle alone is on the boundary of its piece.
          if (on_edge == 1 && (!repaired[a] || !repaired[b]))
            rim_repaired = false;
        }
      }
      for (const std::uint32_t u : piece)
        state[u] = large ? kLarge : rim_repaired ? kScrap : kSmall;
    }
  }
  std::size_t kept = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (state[t] != kScrap)
      triangles[kept++] = triangles[t];
  const std::size_t removed = triangles.size() - kept;
  triangles.resize(kept);
  return removed;
}

/** The intersecting pairs of \a triangles (as findSelfIntersections gives them) when
 * those before \a first_new intersect none of one another: the repair removed every
 * pair they formed. Each pair then holds a triangle from \a first_new on (a fill's),
 * so only the triangles whose boxes meet a fill triangle's are checked. More than
 * kMaxFillsCheckedAlone fill triangles: the whole mesh. */
std::vector<std::pair<std::size_t, std::size_t>>
crossingsOfFills(const std::vector<Eigen::Vector3d>& points,
                 const std::vector<TriangleIndices>& triangles, std::size_t first_new,
                 unsigned threads)
{
  constexpr std::size_t kMaxFillsCheckedAlone = 64; // fill triangles
  if (first_new == triangles.size())
    return {};
  if (triangles.size() - first_new > kMaxFillsCheckedAlone)
    return findSelfIntersections(points, triangles, threads);
  std::vector<Eigen::AlignedBox3d> fills;
  Eigen::AlignedBox3d around_fills;
  for (std::size_t t = first_new; t < triangles.size(); ++t) {
    fills.push_back(triangleBox(points, triangles[t]));
    around_fills.extend(fills.back());
  }
  std::vector<std::size_t> chosen; // positions in triangles
  for (std::size_t t = 0; t < first_new; ++t) {
    const Eigen::AlignedBox3d box = triangleBox(points, triangles[t]);
    if (box.intersects(around_fills) &&
        std::any_of(fills.begin(), fills.end(), [&](const Eigen::AlignedBox3d& fill) {
          return box.intersects(fill);
        }))
      chosen.push_back(t);
  }
  for (std::size_t t = first_new; t < triangles.size(); ++t)
    chosen.push_back(t);
  std::vector<TriangleIndices> near_fills;
  near_fills.reserve(chosen.size());
  for (const std::size_t t : chosen)
    near_fills.push_back(triangles[t]);
  std::vector<std::pair<std::size_t, std::size_t>> pairs =
      findSelfIntersections(points, near_fills, threads);
  for (auto& [a, b] : pairs) { // chosen is ascending: the order is kept
    a = chosen[a];
    b = chosen[b];
  }
  return pairs;
}

} // namespace

RestoreRepair
restoreInputPositions(const std::vector<Eigen::Vector3d>& points,
                      std::vector<TriangleIndices>& triangles, unsigned threads)
{
  RestoreRepair repair;
  std::vector<std::pair<std::size_t, std::size_t>> pairs =
      findSelfIntersections(points, triangles, threads);
  if (pairs.empty())
    return repair;
  std::vector<std::uint8_t> repaired(points.size(), 0); // over all rounds
  // Two rounds remove and fill; a third removes what still crosses without filling,
  // which cannot make a new crossing.
  for (int round = 0; round < 3 && !pairs.empty(); ++round) {
    std::vector<std::uint8_t> removed(triangles.size(), 0);
    for (const auto& [a, b] : pairs)
      removed[a] = removed[b] = 1;
    std::vector<std::uint8_t> touched(points.size(), 0);
    repair.removed_triangles += removeFlagged(triangles, removed, touched);
    VertexIncidence at(triangles, points.size());
    repair.removed_triangles += removePinches(triangles, touched, at);
    for (std::size_t v = 0; v < points.size(); ++v)
      repaired[v] |= touched[v];
    // Before the fills: a scrap inside a hole would block its fill.
    repair.removed_triangles += removeRepairScraps(triangles, repaired, at);
    if (round == 2)
      break;
    const std::size_t before_fills = triangles.size();
    repair.filled_triangles += fillHoles(points, touched, triangles);
    pairs = crossingsOfFills(points, triangles, before_fills, threads);
  }
  return repair;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
