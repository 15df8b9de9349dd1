// SPDX-License-Identifier: GPL-3.0-or-later
// Private: what the stages of the mesher (reconstructSurface) share: the pool of
// triangles that may become part of the surface, their incidence lists, the mesh
// (the pool triangles in it, oriented, with the degree and fan normal of each sample),
// the edges that may be open, the log of changes, and the grid of the mesh's triangles
// for intersection checks. Never installed.
#pragma once

#include "reconstruction/box_grid.h"

#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** The group of the cocone candidates; group k > 0 holds the Delaunay triangles offered
 * to the k-th hole, and a group's triangles are contiguous in the pool. */
constexpr std::uint32_t kCoconeGroup = 0;
/** Triangles of polygon fills and sample insertion (not Delaunay triangles): never
 * offered to a walk. */
constexpr std::uint32_t kPolygonGroup = std::numeric_limits<std::uint32_t>::max();

/** State of a triangle of the pool. */
enum TriangleState : std::uint8_t
{
  kRejected = 0,  // pruned, refused for good, or rolled back
  kCandidate = 1, // may still be walked onto
  kInMesh = 2     // part of the output
};

/** The pool of triangles and the mesh made of some of them. Sample indices are those of
 * \a points; triangle ids are positions in the pool, which only grows. */
class MeshState
{
public:
  using Vector = Eigen::Vector3d;
  using Edge = std::pair<SampleIndex, SampleIndex>;

  /** A pool triangle at a vertex, with its two other vertices. */
  struct Incidence
  {
    std::uint32_t triangle;
    std::array<SampleIndex, 2> other;
  };
  /** The incidence list of a vertex, for a range-based for loop. */
  struct IncidenceRange
  {
    const Incidence* first;
    const Incidence* last;
    const Incidence*
    begin() const
    {
      return first;
    }
    const Incidence*
    end() const
    {
      return last;
    }
  };

  /** An empty pool over \a points (kept by reference: they must outlive the state). */
  explicit MeshState(const std::vector<Vector>& points);

  const std::vector<Vector>&
  points() const
  {
    return points_;
  }
  /** The number of samples: the valid sample indices are 0 to sampleCount() - 1. */
  std::size_t
  sampleCount() const
  {
    return n_;
  }

  // --- the pool -------------------------------------------------------------------
  std::uint32_t
  poolSize() const
  {
    return static_cast<std::uint32_t>(pool_.size());
  }
  void reservePool(std::size_t triangles);
  /** Adds \a t to the pool as a candidate of \a group (oriented as given); returns its
   * id. */
  std::uint32_t
  addToPool(const TriangleIndices& t, std::uint32_t group)
  {
    pool_.push_back(t);
    state_.push_back(kCandidate);
    group_.push_back(group);
    oriented_.push_back(t);
    const auto id = static_cast<std::uint32_t>(pool_.size() - 1);
    if (!offsets_.empty()) // incidence lists exist: note it until they are rebuilt
      for (const SampleIndex v : t)
        late_[v].push_back(id);
    return id;
  }
  /** Ends the group whose triangles were added last: the next group starts here. */
  void
  closeGroup()
  {
    group_start_.push_back(poolSize());
  }
  /** The number of groups closed so far. */
  std::uint32_t
  groupCount() const
  {
    return static_cast<std::uint32_t>(group_start_.size() - 1);
  }
  /** Group \a g's triangles have the ids [groupBegin(g), groupEnd(g)). The range of
   * the first hole of a round of stitching also holds the kPolygonGroup triangles
   * made since the previous round (never candidates: they enter the mesh at once). */
  std::uint32_t
  groupBegin(std::uint32_t g) const
  {
    return group_start_[g];
  }
  std::uint32_t
  groupEnd(std::uint32_t g) const
  {
    return group_start_[g + 1];
  }
  /** The vertices of pool triangle \a t as it was added (see oriented()). */
  const TriangleIndices&
  triangle(std::uint32_t t) const
  {
    return pool_[t];
  }
  std::uint32_t
  group(std::uint32_t t) const
  {
    return group_[t];
  }
  TriangleState
  state(std::uint32_t t) const
  {
    return static_cast<TriangleState>(state_[t]);
  }
  bool
  inMesh(std::uint32_t t) const
  {
    return state_[t] == kInMesh;
  }
  /** Refuses candidate \a t for good (a triangle of the mesh leaves by leaveMesh). */
  void
  reject(std::uint32_t t)
  {
    state_[t] = kRejected;
  }
  /** The orientation of \a t in the mesh. */
  const TriangleIndices&
  oriented(std::uint32_t t) const
  {
    return oriented_[t];
  }
  /** Sets the orientation \a t will have in the mesh (before enterMesh). */
  void
  orient(std::uint32_t t, const TriangleIndices& o)
  {
    oriented_[t] = o;
  }
  /** Reverses the orientation of mesh triangle \a t (fan normals are not updated: for
   * the end, see orientClosedComponentsOutward). */
  void
  flip(std::uint32_t t)
  {
    std::swap(oriented_[t][1], oriented_[t][2]);
  }
  bool
  contains(std::uint32_t t, SampleIndex v) const
  {
    const TriangleIndices& tri = pool_[t];
    return tri[0] == v || tri[1] == v || tri[2] == v;
  }
  /** The vertex of \a t other than \a a and \a b. */
  SampleIndex
  apex(std::uint32_t t, SampleIndex a, SampleIndex b) const
  {
    const TriangleIndices& tri = pool_[t];
    for (const SampleIndex v : tri)
      if (v != a && v != b)
        return v;
    return kNoSample;
  }

  // --- incidence ------------------------------------------------------------------
  /** Builds the incidence lists of the whole pool. */
  void rebuildIncidence();
  /** Whether triangles were added since the lists were last built. */
  bool
  hasLateTriangles() const
  {
    return !late_.empty();
  }
  /** The triangles at \a v in the incidence lists (not those added since they were
   * last built). */
  IncidenceRange
  listedAround(SampleIndex v) const
  {
    return {incidence_.data() + offsets_[v], incidence_.data() + offsets_[v + 1]};
  }
  /** Calls f(t) for every pool triangle t at v: those of the incidence lists, and
   * those added since they were last rebuilt. */
  template <typename F>
  void
  forEachAround(SampleIndex v, F&& f) const
  {
    for (std::uint32_t k = offsets_[v]; k < offsets_[v + 1]; ++k)
      f(incidence_[k].triangle);
    forEachLate(v, f);
  }
  /** Calls f(t, apex) for every pool triangle t on edge (a, b), apex being its third
   * vertex. */
  template <typename F>
  void
  forEachOnEdge(SampleIndex a, SampleIndex b, F&& f) const
  {
    // The other two vertices are stored beside each triangle id: no look-up of the
    // triangle itself, neither for the many that do not contain b nor for the apex.
    for (std::uint32_t k = offsets_[a]; k < offsets_[a + 1]; ++k) {
      const Incidence& at = incidence_[k];
      if (at.other[0] == b)
        f(at.triangle, at.other[1]);
      else if (at.other[1] == b)
        f(at.triangle, at.other[0]);
    }
    forEachLate(a, [&](std::uint32_t t) {
      if (contains(t, b))
        f(t, apex(t, a, b));
    });
  }
  /** Pool triangles on edge (a, b) accepted by \a keep. */
  template <typename Keep>
  void
  trianglesOnEdge(SampleIndex a, SampleIndex b, Keep&& keep,
                  std::vector<std::uint32_t>& out) const
  {
    out.clear();
    forEachOnEdge(a, b, [&](std::uint32_t t, SampleIndex) {
      if (keep(t))
        out.push_back(t);
    });
  }
  /** Mesh triangles on edge (a, b). */
  void
  meshOnEdge(SampleIndex a, SampleIndex b, std::vector<std::uint32_t>& out) const
  {
    trianglesOnEdge(
        a, b, [&](std::uint32_t t) { return state_[t] == kInMesh; }, out);
  }

  // --- the mesh -------------------------------------------------------------------
  /** Puts pool triangle t (oriented already) into the mesh. */
  void
  enterMesh(std::uint32_t t)
  {
    if (log_changes_)
      changed_.emplace_back(t, state_[t] == kInMesh);
    state_[t] = kInMesh;
    const Vector nt = orientedNormal(oriented_[t]);
    for (const SampleIndex v : oriented_[t]) {
      ++mesh_degree_[v];
      fan_normal_[v] += nt;
    }
    if (grid_)
      grid_->insert(t, boundingBox(oriented_[t]));
  }
  /** Takes mesh triangle t out of the mesh; its edges may be open now. */
  void
  leaveMesh(std::uint32_t t)
  {
    if (log_changes_)
      changed_.emplace_back(t, state_[t] == kInMesh);
    state_[t] = kRejected;
    const TriangleIndices& o = oriented_[t];
    const Vector nt = orientedNormal(o);
    for (int k = 0; k < 3; ++k) {
      fan_normal_[o[k]] -= nt;
      --mesh_degree_[o[k]];
      maybe_open_.emplace_back(o[k], o[(k + 1) % 3]);
    }
  }
  /** Takes the triangles of \a added out of the mesh again. */
  void
  undo(const std::vector<std::uint32_t>& added)
  {
    for (const std::uint32_t t : added)
      leaveMesh(t);
  }
  /** The number of mesh triangles at \a v. */
  std::uint32_t
  meshDegree(SampleIndex v) const
  {
    return mesh_degree_[v];
  }
  /** True when mesh triangle t traverses the edge a -> b. */
  bool
  traverses(std::uint32_t t, SampleIndex a, SampleIndex b) const
  {
    return edgeSlot(t, a, b) >= 0;
  }
  /** The k for which mesh triangle t's edge k is a -> b; -1 when it has no such edge.
   */
  int
  edgeSlot(std::uint32_t t, SampleIndex a, SampleIndex b) const
  {
    const TriangleIndices& o = oriented_[t];
    for (int k = 0; k < 3; ++k)
      if (o[k] == a && o[(k + 1) % 3] == b)
        return k;
    return -1;
  }
  /** Twice the area, along the normal of the orientation \a o. */
  Vector
  orientedNormal(const TriangleIndices& o) const
  {
    return (points_[o[1]] - points_[o[0]]).cross(points_[o[2]] - points_[o[0]]);
  }
  /** Whether the triangle (b, a, x), which would continue the mesh across its edge
   * a -> b, faces away from the mesh around a or around b (the fan normals: the sums
   * of the oriented normals of the mesh triangles there, the side the mesh faces). */
  bool
  turnsOver(SampleIndex a, SampleIndex b, SampleIndex x) const
  {
    const Vector normal = orientedNormal({b, a, x});
    return normal.dot(fan_normal_[a]) < 0 || normal.dot(fan_normal_[b]) < 0;
  }
  /** The total area of the mesh triangles \a triangles. */
  double area(const std::vector<std::uint32_t>& triangles) const;
  /** Sorts the mesh triangles at \a v (into \a fan) into fans: triangles connected
   * through edges at v; label[i] is the fan of fan[i] (the position in \a fan of one
   * of its triangles). Returns the number of fans. */
  std::size_t labelFans(SampleIndex v, std::vector<std::uint32_t>& fan,
                        std::vector<std::uint32_t>& label) const;
  std::size_t countFans(SampleIndex v) const;

  // --- open edges and loops -------------------------------------------------------
  /** Notes that edge (a, b) may be a boundary edge of the mesh. */
  void
  noteMaybeOpen(SampleIndex a, SampleIndex b)
  {
    maybe_open_.emplace_back(a, b);
  }
  /** Edges that may be boundary edges: those the walk could not continue across and
   * those of removed triangles. Every boundary edge of the mesh is among them, so
   * tracing the loops does not need to look at every triangle. */
  const std::vector<Edge>&
  maybeOpen() const
  {
    return maybe_open_;
  }
  /** The boundary loops of the mesh, each a cycle a -> b -> ... as the mesh
   * triangles traverse its edges. */
  std::vector<std::vector<SampleIndex>> traceLoops() const;
  /** The boundary loop through \a start (see the source); false if there is none. */
  bool traceLoopFrom(SampleIndex start, std::vector<SampleIndex>& loop) const;
  /** Length of a closed loop (the last vertex joins the first). */
  double loopLength(const std::vector<SampleIndex>& loop) const;

  // --- the change log -------------------------------------------------------------
  /** Whether enterMesh and leaveMesh log what they do (off at first). */
  void
  logChanges(bool on)
  {
    log_changes_ = on;
  }
  /** Whether a triangle entered or left the mesh since the log was last cleared (a
   * triangle that entered and left counts). */
  bool
  hasChanges() const
  {
    return !changed_.empty();
  }
  /** The boxes of the triangles whose membership in the mesh changed since the log
   * was last cleared, net (a fill tried and undone changed nothing); clears the log. */
  std::vector<Box> takeNetChangedBoxes();
  void
  clearChanges()
  {
    changed_.clear();
  }

  // --- boxes and crossings --------------------------------------------------------
  /** Corners of the axis-aligned bounding box of triangle \a t. */
  Box
  boundingBox(const TriangleIndices& t) const
  {
    return {points_[t[0]].cwiseMin(points_[t[1]]).cwiseMin(points_[t[2]]),
            points_[t[0]].cwiseMax(points_[t[1]]).cwiseMax(points_[t[2]])};
  }
  Box boundingBox(const std::vector<SampleIndex>& samples) const;
  /** Whether the grid of mesh triangles exists (buildGrid). */
  bool
  hasGrid() const
  {
    return grid_.has_value();
  }
  /** Enters the mesh triangles into the grid, once (enterMesh keeps it up to date). */
  void buildGrid();
  /** A superset of the mesh triangles that can touch \a box, sorted. Needs buildGrid().
   * Read-only: threads may query at once. */
  void meshNear(const Box& box, std::vector<std::uint32_t>& nearby) const;
  /** Whether mesh triangle t crosses another mesh triangle. */
  bool crossesMesh(std::uint32_t t);
  /** Whether a triangle of \a added (already in the mesh) crosses another mesh
   * triangle. */
  bool intersectsSurface(const std::vector<std::uint32_t>& added);
  /** Whether \a added (already in the mesh) closes the hole of \a loop (see the
   * source). */
  bool
  closes(const std::vector<SampleIndex>& loop, const std::vector<std::uint32_t>& added);

private:
  const std::vector<Vector>& points_;
  const std::size_t n_;

  std::vector<TriangleIndices> pool_;
  std::vector<std::uint8_t> state_;
  std::vector<std::uint32_t> group_;
  std::vector<TriangleIndices> oriented_;  // orientation in the mesh
  std::vector<std::uint32_t> group_start_; // group g spans [start[g], start[g + 1])
  // Incidence lists: the triangles at v are incidence_[offsets_[v] .. offsets_[v + 1]).
  std::vector<std::uint32_t> offsets_;
  std::vector<Incidence> incidence_;
  std::unordered_map<SampleIndex, std::vector<std::uint32_t>> late_; // added since

  std::vector<std::uint32_t> mesh_degree_; // mesh triangles at each sample
  // Sum of the oriented normals (twice the areas) of the mesh triangles at each sample:
  // the side the mesh faces there (see turnsOver()).
  std::vector<Vector> fan_normal_;
  std::vector<Edge> maybe_open_; // see maybeOpen()

  bool log_changes_ = false; // whether enterMesh and leaveMesh log to changed_
  // Triangles that entered or left the mesh, each with whether it was in the mesh
  // before.
  std::vector<std::pair<std::uint32_t, bool>> changed_;

  // A uniform grid over the mesh triangles' bounding boxes, built (buildGrid) by the
  // first check that added triangles cross nothing (a fill across a hole can meet a
  // part of the surface that is near in space but far along it). Triangles added later
  // are entered as they come; removed ones stay listed and are skipped by state.
  std::optional<BoxGrid> grid_;
  std::vector<std::uint32_t> near_; // scratch of crossesMesh

  /** Calls f(t) for every pool triangle t at v added since the lists were rebuilt. */
  template <typename F>
  void
  forEachLate(SampleIndex v, F&& f) const
  {
    if (late_.empty())
      return;
    const auto late = late_.find(v);
    if (late != late_.end())
      for (const std::uint32_t t : late->second)
        f(t);
  }
};

} // namespace detail
} // namespace cocone
} // namespace pcl
