// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's manifold extraction: walks over the candidates from seeds on
// the outside, and the resolution of the pinched vertices some steps leave. Never
// installed.
#pragma once

#include "reconstruction/mesh_state.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Keeps one fan per vertex: the vertices noted here (apexes of forced steps, vertices
 * of removed triangles) are checked when resolve() runs, whichever stage noted them. */
class PinchResolver
{
public:
  explicit PinchResolver(MeshState& mesh) : mesh_(mesh) {}

  /** Notes that \a v may have several fans. */
  void
  note(SampleIndex v)
  {
    pending_.push_back(v);
  }
  /** Notes the three vertices of \a t. */
  void
  note(const TriangleIndices& t)
  {
    pending_.insert(pending_.end(), t.begin(), t.end());
  }
  /** Gives every noted vertex with several fans its largest one (see the source).
   * Returns the number of mesh triangles removed; appends them to \a removed when it
   * is given. */
  std::size_t resolve(std::vector<std::uint32_t>* removed = nullptr);

private:
  MeshState& mesh_;
  std::vector<SampleIndex> pending_; // noted vertices, in the order noted
  // Called once per growth of every hole: a member, all zero between calls, rather than
  // n bytes allocated each time.
  std::vector<std::uint8_t> queued_;
};

/** Walks over the candidates (see the source): the whole cocone group from seeds, or
 * a hole's group from the hole's edges. */
class Walker
{
public:
  /** A frontier entry: a mesh triangle and the slot k of its edge k -> k + 1. */
  using Front = std::pair<std::uint32_t, int>;

  /** Walks on \a mesh; forced steps note their apexes to \a pinches; the seeds are
   * sorted on \a threads threads (0: all). */
  Walker(MeshState& mesh, PinchResolver& pinches, unsigned threads)
    : mesh_(mesh), pinches_(pinches), threads_(threads)
  {}

  /** Extracts the surface from the candidates of the cocone group: seeds a walk on the
   * outside of what is left until no seed is left. Returns the number of triangles
   * walked (seeds included). */
  std::size_t walkAll();

  /** Walks over the candidates of \a group from the edges of \a frontier (emptied),
   * breadth first; appends the triangles added to \a added and returns their number. */
  std::size_t walk(std::vector<Front>& frontier, std::uint32_t group,
                   std::vector<std::uint32_t>& added);

private:
  struct Step
  {
    enum Outcome
    {
      done,    // the edge is closed, or no candidate is left on it
      added,   // triangle was added
      refused, // triangle would break an edge
      pinch    // triangle would give a vertex a second fan
    } outcome;
    std::uint32_t triangle;
  };
  Step step(std::uint32_t t, int slot, std::uint32_t group, bool allow_pinch);
  bool seedTriangle(std::uint32_t& seed);

  MeshState& mesh_;
  PinchResolver& pinches_;
  const unsigned threads_;
  std::vector<SampleIndex> seed_order_; // samples by decreasing x
  std::size_t seed_cursor_ = 0;
  // Scratch of step(), reused to keep the walk free of allocations.
  std::vector<std::uint32_t> on_edge_, around_;
  std::vector<SampleIndex> around_apex_; // apex of each triangle of around_
  // During walkAll only (empty otherwise): bit k of closed_edges_[t] says that edge k
  // of oriented(t) has two mesh triangles. Nothing leaves the mesh during that walk,
  // so a set bit stays true, and about a third of its steps (those that find the edge
  // closed by the time they are taken) skip the look-up that would find out.
  std::vector<std::uint8_t> closed_edges_;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
