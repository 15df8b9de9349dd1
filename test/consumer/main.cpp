// SPDX-License-Identifier: GPL-3.0-or-later
//
// A downstream program built against the *installed* package: it reconstructs a
// generated sphere and succeeds only if the mesh is a closed manifold, and checks the
// error policy (empty result + getErrorMessage()) on input without a 3D Voronoi
// diagram. Exit code 0 on success.
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

int
main()
{
  // Fibonacci lattice on the unit sphere, every point moved radially by a different
  // tiny amount: exactly co-spherical points are the Delaunay worst case.
  pcl::PointCloud<pcl::PointXYZ>::Ptr sphere(new pcl::PointCloud<pcl::PointXYZ>);
  const int n = 1500;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    const double scale = 1.0 + 1e-5 * std::sin(12.9898 * i);
    sphere->emplace_back(static_cast<float>(scale * r * std::cos(golden * i)),
                         static_cast<float>(scale * r * std::sin(golden * i)),
                         static_cast<float>(scale * z));
  }

  pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
  cocone.setInputCloud(sphere);
  std::vector<pcl::Vertices> polygons;
  cocone.reconstruct(polygons);

  std::vector<pcl::cocone::TriangleIndices> triangles;
  for (const pcl::Vertices& polygon : polygons)
    triangles.push_back({static_cast<std::uint32_t>(polygon.vertices[0]),
                         static_cast<std::uint32_t>(polygon.vertices[1]),
                         static_cast<std::uint32_t>(polygon.vertices[2])});
  const pcl::cocone::MeshTopology topology =
      pcl::cocone::analyzeTriangleMesh(triangles);
  std::printf("consumer: %zu triangles, closed %s, manifold %s\n", topology.triangles,
              topology.isClosed() ? "yes" : "no", topology.isManifold() ? "yes" : "no");
  if (!topology.isClosed() || !topology.isManifold())
    return 1;

  // Coplanar input: PCL_ERROR, no polygon, and the reason in getErrorMessage().
  pcl::PointCloud<pcl::PointXYZ>::Ptr plane(new pcl::PointCloud<pcl::PointXYZ>);
  for (int i = 0; i < 10; ++i)
    plane->emplace_back(static_cast<float>(i % 4), static_cast<float>(i / 4), 0.0f);
  cocone.setInputCloud(plane);
  cocone.reconstruct(polygons);
  std::printf("consumer: coplanar input gives %zu polygons: %s\n", polygons.size(),
              cocone.getErrorMessage().c_str());
  return polygons.empty() && !cocone.getErrorMessage().empty() ? 0 : 1;
}
