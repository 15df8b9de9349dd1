// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * Combinatorial checks of a triangle mesh given as index triples: manifoldness,
 * orientation, boundary loops, Euler characteristic and genus. Used by
 * CoconeReconstruction (to find the holes to stitch and to report what it produced),
 * by the tools' summary line and by the tests.
 */
#pragma once

#include <pcl/cocone/export.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {

/** \brief A triangle as three vertex indices. */
using TriangleIndices = std::array<std::uint32_t, 3>;

/** \brief What analyzeTriangleMesh finds. Vertex indices are those of the triangles;
 * vertices referenced by no triangle do not count anywhere. */
struct MeshTopology
{
  std::size_t vertices = 0;  ///< distinct vertices referenced by the triangles
  std::size_t edges = 0;     ///< distinct undirected edges
  std::size_t triangles = 0; ///< triangles given (degenerate and repeated ones included)

  std::size_t degenerate_triangles = 0; ///< triangles repeating a vertex
  std::size_t duplicate_triangles = 0;  ///< triangles with the vertex set of an earlier one
  std::size_t boundary_edges = 0;       ///< edges with exactly one triangle
  std::size_t non_manifold_edges = 0;   ///< edges with more than two triangles
  /** Vertices whose incident triangles do not form a single fan (triangles around the
   * vertex connected through edges incident to it): the mesh is pinched there. */
  std::size_t non_manifold_vertices = 0;
  /** Edges with two triangles that traverse them in the same direction. */
  std::size_t inconsistently_oriented_edges = 0;
  std::size_t components = 0; ///< components connected through shared edges

  /** Cycles of boundary edges, each a list of vertices in order (the edge from the last
   * vertex back to the first closes it), oriented along the triangles' orientation.
   * Filled only when there is no non-manifold edge or vertex. */
  std::vector<std::vector<std::uint32_t>> boundary_loops;

  /** V - E + F. */
  long
  eulerCharacteristic() const
  {
    return static_cast<long>(vertices) - static_cast<long>(edges) +
           static_cast<long>(triangles);
  }

  /** True for a 2-manifold (possibly with boundary): every edge has one or two
   * triangles, every vertex a single fan, no degenerate or repeated triangle. */
  bool
  isManifold() const
  {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 &&
           degenerate_triangles == 0 && duplicate_triangles == 0;
  }

  /** True for a manifold without boundary. */
  bool
  isClosed() const
  {
    return isManifold() && boundary_edges == 0 && triangles > 0;
  }

  /** True when the orientation is consistent over every edge. */
  bool
  isConsistentlyOriented() const
  {
    return inconsistently_oriented_edges == 0;
  }

  /** Total genus of an orientable manifold: chi = 2c - 2g - b summed over components,
   * so g = (2c - chi - b) / 2. -1 when the mesh is not a manifold or not orientable. */
  long
  genus() const
  {
    if (!isManifold() || !isConsistentlyOriented())
      return -1;
    const long twice =
        2 * static_cast<long>(components) - eulerCharacteristic() -
        static_cast<long>(boundary_loops.size());
    return twice >= 0 && twice % 2 == 0 ? twice / 2 : -1;
  }
};

/** \brief Analyzes the triangles \a triangles (indices into any vertex array). Runs in
 * O(T log T); needs no coordinates. */
PCL_COCONE_EXPORT MeshTopology
analyzeTriangleMesh(const std::vector<TriangleIndices>& triangles);

} // namespace cocone
} // namespace pcl
