// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's stitching of holes (paper 3.4.2): each hole is offered its
// Delaunay triangles, pruned and walked like the candidates, and closed by a polygon
// fill when they do not close it; true boundaries stay open. Never installed.
#pragma once

#include "reconstruction/fill.h"
#include "reconstruction/mesh_state.h"
#include "reconstruction/prune.h"
#include "reconstruction/walk.h"

#include <pcl/cocone/core/voronoi_cocone.h>

#include <cstddef>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Stitches the holes of a MeshState, round by round (see the source). */
class Stitcher
{
public:
  /** Stitches the holes of \a mesh with the Delaunay triangles of \a voronoi, whose
   * samples have the local spacings \a spacing, through the same \a pruner and
   * \a walker as the candidates, and \a filler. */
  Stitcher(MeshState& mesh, const VoronoiCocone& voronoi,
           const std::vector<double>& spacing, Pruner& pruner, Walker& walker,
           PolygonFiller& filler, const HoleRule& rule)
    : mesh_(mesh), voronoi_(voronoi), spacing_(spacing), pruner_(pruner),
      walker_(walker), filler_(filler), rule_(rule)
  {}

  /** One round: offers the loops of the mesh not offered before, and those offered
   * before around which the mesh changed since (its change log, which this reads and
   * clears). Returns the number of loops offered. */
  std::size_t stitchLoops();

  /** Offers every loop of \a loops (boundary loops of the mesh, as its triangles run
   * them); keeps in \a loops those that stay open. */
  void stitch(std::vector<std::vector<SampleIndex>>& loops);

  /** Holes closed so far. */
  std::size_t
  stitchedHoles() const
  {
    return stitched_holes_;
  }
  /** Triangles added so far to close them, less those removed to grow them. */
  std::size_t
  stitchedTriangles() const
  {
    return stitched_triangles_;
  }

private:
  double typicalSpacing(const std::vector<SampleIndex>& samples) const;
  bool isTrueBoundary(double area, double perimeter, double spacing,
                      const std::vector<SampleIndex>& loop) const;

  MeshState& mesh_;
  const VoronoiCocone& voronoi_;
  const std::vector<double>& spacing_;
  Pruner& pruner_;
  Walker& walker_;
  PolygonFiller& filler_;
  const HoleRule& rule_;
  std::vector<std::vector<SampleIndex>> tried_; // vertex sets of the loops offered
  std::size_t stitched_holes_ = 0, stitched_triangles_ = 0;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
