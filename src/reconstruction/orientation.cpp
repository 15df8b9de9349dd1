// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction/orientation.h"

#include "common/disjoint_sets.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

// Closed components face outward: flip any whose signed volume is negative.
void
orientClosedComponentsOutward(MeshState& mesh)
{
  const std::vector<Eigen::Vector3d>& points = mesh.points();
  const std::size_t n = mesh.sampleCount();
  // Components of the mesh through shared vertices, by union-find over the samples.
  // Every vertex has a single fan (PinchResolver), so these are the components
  // through shared edges, found without looking up a single edge.
  DisjointSets components(n);
  const auto find = [&](SampleIndex v) { return components.find(v); };
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t)
    if (mesh.inMesh(t)) {
      components.unite(mesh.oriented(t)[0], mesh.oriented(t)[1]);
      components.unite(mesh.oriented(t)[0], mesh.oriented(t)[2]);
    }
  // Signed volume per component (divergence theorem, up to a factor 6), summed in
  // triangle order.
  std::vector<double> volume(n, 0);
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t)
    if (mesh.inMesh(t)) {
      const TriangleIndices& o = mesh.oriented(t);
      volume[find(o[0])] += points[o[0]].dot(points[o[1]].cross(points[o[2]]));
    }
  // A component with a boundary edge is open: its inside is undefined.
  std::vector<std::uint8_t> open(n, 0);
  std::vector<std::uint32_t> on_edge;
  for (const auto& [a, b] : mesh.maybeOpen()) {
    mesh.meshOnEdge(a, b, on_edge);
    if (on_edge.size() == 1)
      open[find(a)] = 1;
  }
  for (std::uint32_t t = 0; t < mesh.poolSize(); ++t)
    if (mesh.inMesh(t)) {
      const SampleIndex root = find(mesh.oriented(t)[0]);
      if (!open[root] && volume[root] < 0)
        mesh.flip(t);
    }
}

} // namespace detail
} // namespace cocone
} // namespace pcl
