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

/** \brief A triangle as three vertex indices; the index space is the caller's vertex
 * array (e.g. sample indices of a VoronoiCocone in reconstructSurface). The order of
 * the indices gives the orientation. */
using TriangleIndices = std::array<std::uint32_t, 3>;

/** \brief What analyzeTriangleMesh finds. Vertex indices are those of the triangles;
 * vertices referenced by no triangle do not count anywhere. */
struct MeshTopology
{
  std::size_t vertices = 0; ///< distinct vertices referenced by the triangles
  std::size_t edges = 0;    ///< distinct undirected edges of non-degenerate triangles
  std::size_t triangles =
      0; ///< triangles given (degenerate and repeated ones included)

  std::size_t degenerate_triangles = 0; ///< triangles repeating a vertex
  std::size_t duplicate_triangles =
      0;                          ///< triangles with the vertex set of an earlier one
  std::size_t boundary_edges = 0; ///< edges with exactly one triangle
  std::size_t non_manifold_edges = 0; ///< edges with more than two triangles
  /** Vertices whose incident triangles do not form a single fan (triangles around the
   * vertex connected through edges incident to it): the mesh is pinched there. */
  std::size_t non_manifold_vertices = 0;
  /** Edges with two triangles that traverse them in the same direction. */
  std::size_t inconsistently_oriented_edges = 0;
  /** Components: non-degenerate triangles connected through shared edges. */
  std::size_t components = 0;

  /** Cycles of boundary edges, each a list of vertex indices (the triangles' index
   * space) in order (the edge from the last vertex back to the first closes it),
   * oriented along the triangles' orientation. Filled only when there is no
   * non-manifold edge or vertex. */
  std::vector<std::vector<std::uint32_t>> boundary_loops;

  /** \brief Euler characteristic of the mesh.
   * \return V - E + F: #vertices - #edges + #triangles (degenerate and repeated
   *         triangles included in F) */
  long
  eulerCharacteristic() const
  {
    return static_cast<long>(vertices) - static_cast<long>(edges) +
           static_cast<long>(triangles);
  }

  /** \brief Whether the mesh is a 2-manifold, possibly with boundary.
   * \return true when every edge has one or two triangles, every vertex a single fan,
   *         and no triangle is degenerate or repeated (also true for no triangle) */
  bool
  isManifold() const
  {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 &&
           degenerate_triangles == 0 && duplicate_triangles == 0;
  }

  /** \brief Whether the mesh is a manifold without boundary.
   * \return true for a non-empty manifold (isManifold()) without boundary edge */
  bool
  isClosed() const
  {
    return isManifold() && boundary_edges == 0 && triangles > 0;
  }

  /** \brief Whether the orientation is consistent over every edge.
   * \return true when no edge is traversed twice in the same direction */
  bool
  isConsistentlyOriented() const
  {
    return inconsistently_oriented_edges == 0;
  }

  /** \brief Total genus of a consistently oriented manifold: chi = 2c - 2g - b summed
   * over the components, so g = (2c - chi - b) / 2.
   * \return the genus summed over the components; -1 when the mesh is not a manifold,
   *         is not consistently oriented (even if it is orientable), or 2c - chi - b is
   *         negative or odd */
  long
  genus() const
  {
    if (!isManifold() || !isConsistentlyOriented())
      return -1;
    const long twice = 2 * static_cast<long>(components) - eulerCharacteristic() -
                       static_cast<long>(boundary_loops.size());
    return twice >= 0 && twice % 2 == 0 ? twice / 2 : -1;
  }
};

/** \brief Analyzes the combinatorics of a triangle mesh. Runs in O(T log T); needs no
 * coordinates.
 * \param[in] triangles the mesh, as index triples into any vertex array (indices may be
 *            sparse; vertices referenced by no triangle do not count)
 * \return the counts, flags and boundary loops of the mesh, with vertex indices in the
 *         index space of \a triangles */
PCL_COCONE_EXPORT MeshTopology
analyzeTriangleMesh(const std::vector<TriangleIndices>& triangles);

} // namespace cocone
} // namespace pcl
