// SPDX-License-Identifier: GPL-3.0-or-later
//
// Uses the three classes on a generated open hemisphere and checks what each promises:
// BoundarySampleEstimation flags samples near the rim and none near the pole,
// VoronoiDecimation keeps a proper subset, CoconeReconstruction gives one manifold
// disc (one boundary loop, Euler characteristic 1). Exit code 0 on success.
#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

int
main()
{
  // Upper hemisphere of the unit sphere, Fibonacci lattice, tiny radial jitter.
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  const int n = 3000;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (i + 0.5) / n; // (0, 1): the upper half only
    const double r = std::sqrt(1.0 - z * z);
    const double scale = 1.0 + 1e-5 * std::sin(12.9898 * i);
    cloud->emplace_back(static_cast<float>(scale * r * std::cos(golden * i)),
                        static_cast<float>(scale * r * std::sin(golden * i)),
                        static_cast<float>(scale * z));
  }

  pcl::BoundarySampleEstimation<pcl::PointXYZ> boundary;
  boundary.setInputCloud(cloud);
  pcl::PointCloud<pcl::Boundary> flags;
  boundary.compute(flags);
  std::size_t flagged = 0, flagged_near_pole = 0;
  for (std::size_t i = 0; i < flags.size(); ++i) {
    flagged += flags[i].boundary_point;
    flagged_near_pole += flags[i].boundary_point && (*cloud)[i].z > 0.5f;
  }

  pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
  decimation.setInputCloud(cloud);
  pcl::Indices kept;
  decimation.filter(kept);

  pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
  cocone.setInputCloud(cloud);
  std::vector<pcl::Vertices> polygons;
  cocone.reconstruct(polygons);
  std::set<std::pair<int, int>> edges;
  std::set<int> vertices;
  for (const pcl::Vertices& polygon : polygons)
    for (int k = 0; k < 3; ++k) {
      const int a = polygon.vertices[k], b = polygon.vertices[(k + 1) % 3];
      edges.emplace(std::min(a, b), std::max(a, b));
      vertices.insert(a);
    }
  const long euler = static_cast<long>(vertices.size()) -
                     static_cast<long>(edges.size()) +
                     static_cast<long>(polygons.size());

  std::printf("core consumer: %zu flags (%zu near the pole), %zu of %d kept, %zu "
              "triangles, %zu loops, Euler characteristic %ld\n",
              flagged, flagged_near_pole, kept.size(), n, polygons.size(),
              cocone.getBoundaryLoops().size(), euler);
  const bool ok = flagged > 0 && flagged_near_pole == 0 && !kept.empty() &&
                  kept.size() < static_cast<std::size_t>(n) &&
                  cocone.getBoundaryLoops().size() == 1 && euler == 1;
  return ok ? 0 : 1;
}
