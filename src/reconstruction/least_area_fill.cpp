// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/least_area_fill.h"

#include "reconstruction/box_grid.h"

#include <pcl/cocone/core/mesh_geometry.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <unordered_map>
#include <utility>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

using Vector = Eigen::Vector3d;

// Rounds of the lazily constrained least-area fill (see fillLoopByLeastArea) before
// the search that tests every candidate takes over. Each round excludes at least one
// triangle; on the scans, 9 fills in 10 that close need at most 16 rounds.
constexpr std::size_t kFillRounds = 32;

Box
boundingBox(const std::vector<Vector>& points, const TriangleIndices& t)
{
  return {points[t[0]].cwiseMin(points[t[1]]).cwiseMin(points[t[2]]),
          points[t[0]].cwiseMax(points[t[1]]).cwiseMax(points[t[2]])};
}

/** Twice the area, along the normal of the orientation. */
Vector
orientedNormal(const std::vector<Vector>& points, const TriangleIndices& o)
{
  return (points[o[1]] - points[o[0]]).cross(points[o[2]] - points[o[0]]);
}

} // namespace

// The triangulation of the loop polygon of least total area (dynamic programming over
// the polygon's diagonals, O(m^3)), using no diagonal that is an edge of the mesh
// already and no triangle that intersects the surface around the hole (the obstacles).
// Triangles are oriented to continue the surface across the loop's edges.
//
// Testing every candidate triangle against the surface made the fills most of the
// stitching time on noisy scans. Most holes close on the first try, so the constraint
// is first applied lazily: solve, test only the triangles of the optimum, exclude those
// that cross (and every triangle on a diagonal that goes through the surface), and
// solve again. When an optimum passes, it is the constrained optimum, tie-breaking
// included: its subproblems cost the same with every constraint applied, and no
// excluded triangle could have replaced one of its triangles. (A diagonal through the
// surface also excludes a degenerate triangle on it, which the triangle test would let
// pass: no loss.) When no optimum passes within kFillRounds, the full search decides,
// and names the blockers: the obstacles that the candidates it tests cross.
//
// A fill must also not cross itself. That constraint is not one of single triangles:
// a triangle is excluded for crossing another triangle of one optimum, which the next
// optimum may not hold. So once a fold has been found, the fill returned is clear of
// itself and of the surface, but not always the least-area such fill: a heuristic for
// a rare case (2 of 300 strongly folded random loops in the tests fold at the least
// area).
bool
fillLoopByLeastArea(const std::vector<Vector>& points,
                    const std::vector<std::uint32_t>& loop,
                    const std::function<bool(std::uint32_t, std::uint32_t)>& is_edge,
                    const std::vector<TriangleIndices>& obstacles,
                    std::vector<TriangleIndices>& fill,
                    std::vector<std::uint32_t>& blockers, LeastAreaFillScratch& scratch)
{
  fill.clear();
  blockers.clear();
  const std::size_t m = loop.size();
  if (m < 3)
    return false;
  std::vector<std::uint8_t> new_diagonal(m * m, 1);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = i + 2; k < m; ++k)
      if (!(i == 0 && k == m - 1)) // loop edges are usable; diagonals must be new
        new_diagonal[i * m + k] = !is_edge(loop[i], loop[k]);
  std::vector<std::uint8_t> usable = new_diagonal; // minus those through the surface
  // The obstacles are sifted by bounding boxes before the exact test.
  std::vector<Box> boxes;
  boxes.reserve(obstacles.size());
  for (const TriangleIndices& u : obstacles)
    boxes.push_back(boundingBox(points, u));
  // Whether t, of box t_box, meets obstacle k.
  const auto meets = [&](const TriangleIndices& t, const Box& t_box, std::size_t k) {
    return !boxesApart(boxes[k], t_box) && trianglesIntersect(points, t, obstacles[k]);
  };
  const auto crosses = [&](const TriangleIndices& t,
                           std::vector<std::uint32_t>& crossed) {
    const Box t_box = boundingBox(points, t);
    bool crossing = false;
    for (std::size_t k = 0; k < obstacles.size(); ++k)
      if (meets(t, t_box, k)) {
        crossing = true;
        crossed.push_back(static_cast<std::uint32_t>(k));
      }
    return crossing;
  };
  // The full search needs a verdict per candidate but only the set of blockers, so a
  // triangle already named is tested after the others, and only until one is met: the
  // verdict is then settled, and the name is known. Most candidates of a hole that no
  // fill closes cross many of the same triangles.
  std::vector<std::uint8_t> named(obstacles.size(), 0);
  const auto blocked = [&](const TriangleIndices& t) {
    const Box t_box = boundingBox(points, t);
    bool crossing = false;
    for (std::size_t k = 0; k < obstacles.size(); ++k)
      if (!named[k] && meets(t, t_box, k)) {
        crossing = true;
        named[k] = 1;
        blockers.push_back(static_cast<std::uint32_t>(k));
      }
    for (std::size_t k = 0; k < obstacles.size() && !crossing; ++k)
      crossing = named[k] && meets(t, t_box, k);
    return crossing;
  };

  // Each round solves the same problem with more triangles excluded, so the areas are
  // computed once, and laid out so that the inner loop over the split j reads memory
  // in order: area(i, j, k) at (i * m + k) * m + j, cost(j, k) also as cost_to(k, j).
  const double infinity = std::numeric_limits<double>::infinity();
  const auto at = [m](std::size_t i, std::size_t j, std::size_t k) {
    return (i * m + k) * m + j;
  };
  std::vector<double>& areas = scratch.areas;
  areas.assign(m * m * m, infinity);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = i + 2; k < m; ++k)
      if (new_diagonal[i * m + k])
        for (std::size_t j = i + 1; j < k; ++j) {
          // The loop runs a -> b as its mesh triangles traverse it; the fill runs
          // b -> a.
          const TriangleIndices triangle = {loop[j], loop[i], loop[k]};
          areas[at(i, j, k)] = 0.5 * orientedNormal(points, triangle).norm();
        }
  enum : std::uint8_t
  {
    kUntested,
    kClear,
    kCrossing
  };
  std::vector<std::uint8_t>& verdicts = scratch.verdicts;
  verdicts.assign(m * m * m, kUntested);
  // What the tested triangles of the rounds cross (positions in obstacles): crossed_by
  // maps one to its range.
  std::vector<std::uint32_t> crossed;
  std::unordered_map<std::size_t, std::pair<std::size_t, std::size_t>> crossed_by;
  std::vector<double> cost(m * m), cost_to(m * m);
  std::vector<std::uint32_t> split(m * m, 0);
  // The least-area fill with the triangles known to cross excluded. The full search
  // (test_every) takes each subproblem's candidates from the smallest area up, testing
  // those the rounds did not, and stops at the first that crosses nothing: the same
  // choice as a scan keeping the smallest clear one, with ties to the smaller split.
  // What the smaller candidates cross is what stands between the subproblem and a
  // smaller fill: those are the blockers. Larger candidates are never tested.
  std::vector<std::pair<double, std::uint32_t>> by_area;
  const auto solve = [&](bool test_every) {
    const std::vector<std::uint8_t>& diagonals = test_every ? new_diagonal : usable;
    std::fill(cost.begin(), cost.end(), infinity);
    std::fill(cost_to.begin(), cost_to.end(), infinity);
    for (std::size_t i = 0; i + 1 < m; ++i)
      cost[i * m + i + 1] = cost_to[(i + 1) * m + i] = 0;
    for (std::size_t span = 2; span < m; ++span)
      for (std::size_t i = 0; i + span < m; ++i) {
        const std::size_t k = i + span;
        if (!diagonals[i * m + k])
          continue;
        const double* from_i = &cost[i * m];
        const double* to_k = &cost_to[k * m];
        const double* area = &areas[at(i, 0, k)];
        double best = infinity;
        std::size_t best_j = 0;
        if (test_every) {
          by_area.clear();
          for (std::size_t j = i + 1; j < k; ++j) {
            const double total = from_i[j] + to_k[j] + area[j];
            if (total < infinity)
              by_area.emplace_back(total, static_cast<std::uint32_t>(j));
          }
          std::sort(by_area.begin(), by_area.end());
          for (const auto& [total, j] : by_area) {
            const std::uint8_t verdict = verdicts[at(i, j, k)];
            if (verdict == kCrossing) {
              const auto [from, to] = crossed_by.at(at(i, j, k));
              blockers.insert(blockers.end(), crossed.begin() + from,
                              crossed.begin() + to);
              continue;
            }
            if (verdict == kUntested && blocked({loop[j], loop[i], loop[k]}))
              continue;
            best = total;
            best_j = j;
            break;
          }
        }
        else {
          for (std::size_t j = i + 1; j < k; ++j) {
            const double total = from_i[j] + to_k[j] + area[j];
            if (total < best && verdicts[at(i, j, k)] != kCrossing) {
              best = total;
              best_j = j;
            }
          }
        }
        cost[i * m + k] = cost_to[k * m + i] = best;
        split[i * m + k] = static_cast<std::uint32_t>(best_j);
      }
    return cost[m - 1] < infinity;
  };
  // The optimum's triangles, from the splits, as (i, j, k) of the loop and in the fill.
  std::vector<std::array<std::size_t, 3>> chosen;
  const auto collectFill = [&] {
    fill.clear();
    chosen.clear();
    std::vector<std::pair<std::size_t, std::size_t>> stack = {{0, m - 1}};
    while (!stack.empty()) {
      const auto [i, k] = stack.back();
      stack.pop_back();
      if (k < i + 2)
        continue;
      const std::size_t j = split[i * m + k];
      fill.push_back({loop[j], loop[i], loop[k]});
      chosen.push_back({i, j, k});
      stack.emplace_back(i, j);
      stack.emplace_back(j, k);
    }
  };

  // A fill folded over itself (found on a noisy cube's crease: a 7-edge loop whose
  // least-area fill put two of its triangles through each other) is no fill. Each pair
  // of its triangles is tested; the larger of a crossing pair (ties: the later) is
  // excluded like a triangle that crosses the surface, and the fill solved again.
  // Returns whether the fill is clear of itself.
  const auto clearOfItself = [&] {
    for (std::size_t a = 0; a < fill.size(); ++a)
      for (std::size_t b = a + 1; b < fill.size(); ++b) {
        if (!trianglesIntersect(points, fill[a], fill[b]))
          continue;
        const auto [ia, ja, ka] = chosen[a];
        const auto [ib, jb, kb] = chosen[b];
        const std::size_t larger = areas[at(ia, ja, ka)] > areas[at(ib, jb, kb)]
                                       ? at(ia, ja, ka)
                                       : at(ib, jb, kb);
        verdicts[larger] = kCrossing;
        crossed_by.emplace(larger, std::make_pair(crossed.size(), crossed.size()));
        return false;
      }
    return true;
  };

  for (std::size_t round = 0; round < kFillRounds && solve(false); ++round) {
    collectFill();
    bool clear = true;
    for (std::size_t t = 0; t < chosen.size(); ++t) {
      const auto [i, j, k] = chosen[t];
      std::uint8_t& verdict = verdicts[at(i, j, k)];
      if (verdict != kUntested) {
        clear = clear && verdict == kClear;
        continue;
      }
      const std::size_t first = crossed.size();
      if (!crosses(fill[t], crossed)) {
        verdict = kClear;
        continue;
      }
      verdict = kCrossing;
      clear = false;
      crossed_by.emplace(at(i, j, k), std::make_pair(first, crossed.size()));
      // A diagonal through the surface excludes every triangle on it at once; it can
      // only cross what its triangle crosses.
      for (const auto& [from, to] : {std::pair{i, j}, std::pair{j, k}, std::pair{i, k}})
        if (to > from + 1 && !(from == 0 && to == m - 1) && usable[from * m + to])
          for (std::size_t b = first; b < crossed.size(); ++b)
            if (segmentCrossesTriangle(points, loop[from], loop[to],
                                       obstacles[crossed[b]])) {
              usable[from * m + to] = 0;
              break;
            }
    }
    if (clear && clearOfItself())
      return true;
  }

  // No fill passed in time: the full search decides, and names everything the
  // candidates it considers cross, for the caller to grow the hole over.
  // Each fold found excludes one more triangle of the optimum, so this ends.
  fill.clear();
  bool found = solve(true);
  while (found) {
    collectFill();
    if (clearOfItself())
      break;
    found = solve(true);
  }
  std::sort(blockers.begin(), blockers.end());
  blockers.erase(std::unique(blockers.begin(), blockers.end()), blockers.end());
  if (!found) {
    fill.clear();
    return false;
  }
  return true;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
