// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/mesh_state.h"

#include <pcl/cocone/core/mesh_geometry.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cassert>
#include <numeric>

namespace pcl {
namespace cocone {
namespace detail {

MeshState::MeshState(const std::vector<Vector>& points)
  : points_(points), n_(points.size()), group_start_{0}, mesh_degree_(n_, 0),
    fan_normal_(n_, Vector::Zero())
{}

void
MeshState::reservePool(std::size_t triangles)
{
  pool_.reserve(triangles);
  state_.reserve(triangles);
  group_.reserve(triangles);
  oriented_.reserve(triangles);
}

void
MeshState::rebuildIncidence()
{
  late_.clear();
  offsets_.assign(n_ + 1, 0);
  for (const TriangleIndices& t : pool_)
    for (const SampleIndex v : t)
      ++offsets_[v + 1];
  for (std::size_t i = 0; i < n_; ++i)
    offsets_[i + 1] += offsets_[i];
  incidence_.resize(offsets_[n_]);
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::uint32_t t = 0; t < pool_.size(); ++t) {
    const TriangleIndices& tri = pool_[t];
    for (int k = 0; k < 3; ++k)
      incidence_[fill[tri[k]]++] = {t, {tri[(k + 1) % 3], tri[(k + 2) % 3]}};
  }
}

double
MeshState::area(const std::vector<std::uint32_t>& triangles) const
{
  double total = 0;
  for (const std::uint32_t t : triangles)
    total += 0.5 * orientedNormal(oriented_[t]).norm();
  return total;
}

std::size_t
MeshState::labelFans(SampleIndex v, std::vector<std::uint32_t>& fan,
                     std::vector<std::uint32_t>& label) const
{
  fan.clear();
  forEachAround(v, [&](std::uint32_t t) {
    if (state_[t] == kInMesh)
      fan.push_back(t);
  });
  // Union-find: triangles sharing an edge (v, w) belong to the same fan.
  label.resize(fan.size());
  std::iota(label.begin(), label.end(), 0u);
  const auto find = [&](std::uint32_t i) {
    while (label[i] != i)
      i = label[i] = label[label[i]];
    return i;
  };
  for (std::size_t i = 0; i < fan.size(); ++i)
    for (std::size_t j = i + 1; j < fan.size(); ++j)
      for (const SampleIndex w : pool_[fan[i]])
        if (w != v && contains(fan[j], w))
          label[find(static_cast<std::uint32_t>(i))] =
              find(static_cast<std::uint32_t>(j));
  std::size_t fans = 0;
  for (std::size_t i = 0; i < fan.size(); ++i) {
    label[i] = find(static_cast<std::uint32_t>(i));
    fans += label[i] == i;
  }
  return fans;
}

std::size_t
MeshState::countFans(SampleIndex v) const
{
  std::vector<std::uint32_t> fan, label;
  return labelFans(v, fan, label);
}

std::vector<std::vector<SampleIndex>>
MeshState::traceLoops() const
{
  // Boundary edges a -> b, as the single mesh triangle on them traverses them: found
  // among the edges that may be open (see maybe_open_).
  std::vector<Edge> edges;
  std::vector<std::uint32_t> on_edge;
  for (const auto& [a, b] : maybe_open_) {
    meshOnEdge(a, b, on_edge);
    if (on_edge.size() != 1)
      continue;
    if (traverses(on_edge[0], a, b))
      edges.emplace_back(a, b);
    else
      edges.emplace_back(b, a);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::uint8_t> used(edges.size(), 0);
  std::vector<std::vector<SampleIndex>> loops;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (used[start])
      continue;
    std::vector<SampleIndex> loop;
    std::size_t e = start;
    while (!used[e]) {
      used[e] = 1;
      loop.push_back(edges[e].first);
      // The edge leaving edges[e].second (one per vertex on a manifold boundary).
      const auto next = std::lower_bound(
          edges.begin(), edges.end(),
          std::make_pair(edges[e].second, static_cast<SampleIndex>(0)));
      if (next == edges.end() || next->first != edges[e].second)
        break;
      e = static_cast<std::size_t>(next - edges.begin());
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// The boundary loop through \a start, following at each vertex its single outgoing
// boundary edge (as its mesh triangle traverses it). False if a vertex on the way has
// none or several (a pinch), or the walk does not come back.
bool
MeshState::traceLoopFrom(SampleIndex start, std::vector<SampleIndex>& loop) const
{
  loop.clear();
  std::vector<std::uint32_t> on_edge;
  SampleIndex v = start;
  for (std::size_t steps = 0; steps <= n_; ++steps) {
    SampleIndex next = kNoSample;
    int outgoing = 0;
    forEachAround(v, [&](std::uint32_t t) {
      if (state_[t] != kInMesh)
        return;
      const TriangleIndices& o = oriented_[t];
      for (int slot = 0; slot < 3; ++slot)
        if (o[slot] == v) {
          meshOnEdge(v, o[(slot + 1) % 3], on_edge);
          if (on_edge.size() == 1) {
            next = o[(slot + 1) % 3];
            ++outgoing;
          }
        }
    });
    if (outgoing != 1)
      return false;
    loop.push_back(v);
    v = next;
    if (v == start)
      return loop.size() >= 3;
  }
  return false;
}

double
MeshState::loopLength(const std::vector<SampleIndex>& loop) const
{
  double length = 0;
  for (std::size_t k = 0; k < loop.size(); ++k)
    length += (points_[loop[(k + 1) % loop.size()]] - points_[loop[k]]).norm();
  return length;
}

std::vector<Box>
MeshState::takeNetChangedBoxes()
{
  std::stable_sort(changed_.begin(), changed_.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Box> changed_boxes;
  for (std::size_t k = 0; k < changed_.size(); ++k)
    if ((k == 0 || changed_[k].first != changed_[k - 1].first) &&
        changed_[k].second != (state_[changed_[k].first] == kInMesh))
      changed_boxes.push_back(boundingBox(oriented_[changed_[k].first]));
  changed_.clear();
  return changed_boxes;
}

Box
MeshState::boundingBox(const std::vector<SampleIndex>& samples) const
{
  Vector low = points_[samples.front()], high = low;
  for (const SampleIndex v : samples) {
    low = low.cwiseMin(points_[v]);
    high = high.cwiseMax(points_[v]);
  }
  return {low, high};
}

void
MeshState::buildGrid()
{
  if (grid_)
    return;
  double edges = 0;
  std::size_t count = 0;
  for (std::uint32_t u = 0; u < pool_.size(); ++u)
    if (state_[u] == kInMesh) {
      edges += (points_[oriented_[u][0]] - points_[oriented_[u][1]]).norm();
      ++count;
    }
  grid_.emplace(BoxGrid::cellSideFor(edges, count));
  // Without room for its cells the map rehashes as it grows: a quarter of the time of
  // this pass on PCL's table scene (about one cell for every four triangles there).
  grid_->reserve(count / 2);
  for (std::uint32_t u = 0; u < pool_.size(); ++u)
    if (state_[u] == kInMesh)
      grid_->insert(u, boundingBox(oriented_[u]));
}

// Mesh triangles whose grid cells meet those of the box, or whose own box meets it: a
// superset of the triangles that can touch the box, sorted. (Callers only keep the
// triangles that an exact test finds touching, so which superset it is does not change
// their results.)
void
MeshState::meshNear(const Box& box, std::vector<std::uint32_t>& nearby) const
{
  assert(grid_);
  nearby.clear();
  grid_->forEachNear(
      box, [&](std::uint32_t u) { return boundingBox(oriented_[u]); },
      [&](std::uint32_t u) {
        if (state_[u] == kInMesh)
          nearby.push_back(u);
      });
  std::sort(nearby.begin(), nearby.end());
  nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
}

bool
MeshState::crossesMesh(std::uint32_t t)
{
  buildGrid();
  meshNear(boundingBox(oriented_[t]), near_);
  for (const std::uint32_t u : near_)
    if (u != t && trianglesIntersect(points_, oriented_[t], oriented_[u]))
      return true;
  return false;
}

// Stitching fills are not restricted Delaunay triangles, so nothing else keeps them
// from folding through the surface at sharp or thin parts.
bool
MeshState::intersectsSurface(const std::vector<std::uint32_t>& added)
{
  for (const std::uint32_t t : added)
    if (crossesMesh(t))
      return true;
  return false;
}

// True when, with \a added in the mesh, every edge of the loop and of the added
// triangles has two triangles, every vertex involved a single fan, and no added
// triangle intersects the surface around the hole.
bool
MeshState::closes(const std::vector<SampleIndex>& loop,
                  const std::vector<std::uint32_t>& added)
{
  std::vector<std::uint32_t> on_edge;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    meshOnEdge(loop[k], loop[(k + 1) % loop.size()], on_edge);
    if (on_edge.size() != 2)
      return false;
  }
  for (const std::uint32_t t : added) {
    const TriangleIndices& o = oriented_[t];
    for (int k = 0; k < 3; ++k) {
      meshOnEdge(o[k], o[(k + 1) % 3], on_edge);
      if (on_edge.size() != 2 || traverses(on_edge[0], o[k], o[(k + 1) % 3]) ==
                                     traverses(on_edge[1], o[k], o[(k + 1) % 3]))
        return false;
      if (countFans(o[k]) != 1)
        return false;
    }
  }
  // Last: the exact intersection tests cost the most.
  return !intersectsSurface(added);
}

} // namespace detail
} // namespace cocone
} // namespace pcl
