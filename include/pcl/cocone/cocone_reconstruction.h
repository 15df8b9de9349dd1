// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <pcl/cocone/cocone_mesher.h>
#include <pcl/cocone/export.h>
#include <pcl/surface/reconstruction.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl {

/** \brief COCONE surface reconstruction with boundaries, after Dey, Giesen, Goswami,
 * Hudson, Wenger and Zhao, "Undersampling and Oversampling in Sample Based Shape
 * Modeling", IEEE Visualization 2001 (section 3.4), on the COCONE algorithm of Amenta,
 * Choi, Dey and Leekha (2000).
 *
 * The output is an oriented 2-manifold, possibly with boundary, whose vertices are the
 * input samples:
 * 1. BOUNDARY (see BoundarySampleEstimation) finds the samples near undersampling;
 * 2. each other sample chooses the Delaunay triangles whose dual Voronoi edge crosses
 *    its cocone; a triangle is a candidate when every non-boundary vertex chooses it;
 * 3. candidates covering a hole too large against the sample spacing are dropped, and
 *    triangles at sharp folds or dangling at bare edges are pruned (never those of a
 *    boundary sample, never those a flat sheet holds, so small gaps cannot cascade);
 * 4. a walk over the outer side of the candidates extracts the manifold, refusing a
 *    third triangle on an edge and a second fan at a vertex; closed components face
 *    outward;
 * 5. the holes left are stitched with Delaunay triangles (or, for a few vertices, the
 *    least-area triangulation of the hole), unless a hole is a true boundary: larger
 *    than the true-boundary ratio in sample spacings.
 *
 * No k-d tree and no normals are needed. Works for closed surfaces, surfaces with
 * boundaries (partial scans, terrain) and sharp features.
 *
 * Index spaces and special points:
 * - polygon vertex ids index the input cloud (also with setIndices, which selects the
 *   samples to reconstruct from); reconstruct(PolygonMesh&) copies the whole input
 *   cloud into the mesh, as every pcl::MeshConstruction does;
 * - points with a NaN or infinite coordinate, exact duplicates (the first of them is
 *   used) and isolated outliers end up in no triangle: getUnusedIndices() lists them;
 * - fewer than 4 distinct finite points, or all of them coplanar or collinear, have no
 *   3D Voronoi diagram: reconstruct() reports it with PCL_ERROR and returns no polygon.
 *
 * \tparam PointInT a point type with x, y, z
 * \ingroup surface
 */
template <typename PointInT>
class CoconeReconstruction : public MeshConstruction<PointInT>
{
public:
  using Ptr = shared_ptr<CoconeReconstruction<PointInT>>;
  using ConstPtr = shared_ptr<const CoconeReconstruction<PointInT>>;

  CoconeReconstruction() { check_tree_ = false; }

  /** \brief Set theta, the cocone angle. Radians; default pi/8 (the paper's value);
   * valid range (0, pi/2). Out of range: PCL_ERROR, unchanged. */
  void
  setCoconeAngle(double theta);
  /** \brief Get theta (see setCoconeAngle). */
  double
  getCoconeAngle() const
  {
    return cocone_angle_;
  }

  /** \brief Set rho, BOUNDARY's ratio bound (r_p / h_p <= rho for flat samples).
   * Dimensionless; default 0.99; valid range (0, 10]. Out of range: PCL_ERROR,
   * unchanged. */
  void
  setRatioBound(double rho);
  /** \brief Get rho (see setRatioBound). */
  double
  getRatioBound() const
  {
    return parameters_.boundary.ratio_bound;
  }

  /** \brief Set alpha, BOUNDARY's normal agreement angle. Radians; default pi/6; valid
   * range (0, pi/2]. Out of range: PCL_ERROR, unchanged. */
  void
  setNormalAngle(double alpha);
  /** \brief Get alpha (see setNormalAngle). */
  double
  getNormalAngle() const
  {
    return parameters_.boundary.normal_angle;
  }

  /** \brief Set the true-boundary size ratio: a hole whose size (twice its area over
   * its perimeter: the radius of a round hole) exceeds this many local sample
   * spacings is a true boundary and stays open; smaller holes are stitched. In local
   * spacings (about 1.1 sqrt(area / n) on an even sample); default 2; valid range
   * [0.5, 1000]. Raise it to close larger holes (e.g. a scan's cut), lower it to keep
   * smaller ones open. Out of range: PCL_ERROR, unchanged. */
  void
  setTrueBoundaryRatio(double ratio);
  /** \brief Get the true-boundary size ratio (see setTrueBoundaryRatio). */
  double
  getTrueBoundaryRatio() const
  {
    return parameters_.true_boundary_ratio;
  }

  /** \brief Detect boundary samples and let them cast no vote (default true). Off gives
   * the original COCONE, fine for densely sampled closed smooth surfaces only. */
  void
  setBoundaryDetection(bool enabled)
  {
    parameters_.detect_boundary = enabled;
  }
  /** \brief Get whether boundary detection is on. */
  bool
  getBoundaryDetection() const
  {
    return parameters_.detect_boundary;
  }

  /** \brief Close the holes that are not true boundaries (default true). */
  void
  setHoleStitching(bool enabled)
  {
    parameters_.stitch_holes = enabled;
  }
  /** \brief Get whether hole stitching is on. */
  bool
  getHoleStitching() const
  {
    return parameters_.stitch_holes;
  }

  /** \brief Number of threads for the per-sample work; 0 (default) uses every core. */
  void
  setNumberOfThreads(unsigned threads)
  {
    threads_ = threads;
  }
  /** \brief Get the number of threads (0: automatic). */
  unsigned
  getNumberOfThreads() const
  {
    return threads_;
  }

  /** \name Diagnostics of the last reconstruct() */
  /** \{ */
  /** \brief Boundary-sample flags, one per input cloud point (0 for points that did not
   * take part). */
  const std::vector<std::uint8_t>&
  getBoundarySamples() const
  {
    return boundary_samples_;
  }
  /** \brief Number of candidate triangles chosen by the cocones. */
  std::size_t
  getNumberOfCandidateTriangles() const
  {
    return report_.candidate_triangles;
  }
  /** \brief Number of candidates dropped because they covered a true boundary. */
  std::size_t
  getNumberOfLidTriangles() const
  {
    return report_.lid_triangles;
  }
  /** \brief Number of candidates pruned at sharp edges. */
  std::size_t
  getNumberOfPrunedTriangles() const
  {
    return report_.pruned_triangles;
  }
  /** \brief Number of holes closed by stitching. */
  std::size_t
  getNumberOfStitchedHoles() const
  {
    return report_.stitched_holes;
  }
  /** \brief Number of triangles added by stitching. */
  std::size_t
  getNumberOfStitchedTriangles() const
  {
    return report_.stitched_triangles;
  }
  /** \brief The boundary loops left open, as cycles of input cloud indices oriented
   * with the surface. */
  const std::vector<pcl::Vertices>&
  getBoundaryLoops() const
  {
    return boundary_loops_;
  }
  /** \brief Input cloud indices (among those selected) that are in no triangle:
   * non-finite points, duplicates, outliers, samples the extraction left out. */
  const pcl::Indices&
  getUnusedIndices() const
  {
    return unused_indices_;
  }
  /** \brief Why the last run produced no result (one line, e.g. "all points are
   * coplanar: no 3D Voronoi cell to measure"); empty after a successful run. The same
   * text went to PCL_ERROR. */
  const std::string&
  getErrorMessage() const
  {
    return error_message_;
  }
  /** \brief The core's report of the last run (sample indices are positions among the
   * finite selected points). */
  const cocone::ReconstructionReport&
  getReport() const
  {
    return report_;
  }
  /** \} */

protected:
  using MeshConstruction<PointInT>::check_tree_;
  using MeshConstruction<PointInT>::input_;
  using MeshConstruction<PointInT>::indices_;

  std::string
  getClassName() const override
  {
    return "CoconeReconstruction";
  }

  void
  performReconstruction(pcl::PolygonMesh& output) override;

  void
  performReconstruction(std::vector<pcl::Vertices>& polygons) override;

private:
  cocone::ReconstructionParameters parameters_;
  double cocone_angle_ = M_PI / 8;
  unsigned threads_ = 0;

  cocone::ReconstructionReport report_;
  std::vector<std::uint8_t> boundary_samples_;
  std::vector<pcl::Vertices> boundary_loops_;
  pcl::Indices unused_indices_;
  std::string error_message_;
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl/cocone/impl/cocone_reconstruction.hpp>
#endif
