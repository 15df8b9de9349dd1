// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the cocone radius of one sample from its Voronoi neighbours alone, by
// clipping a cocone-shaped box with bisector planes. Used by decimation, where the
// diagram changes after every removal and a global triangulation update costs far more
// than the few cells it touches.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

/** Clips a convex polytope, kept as faces with oriented corners, by half-spaces
 * n.y <= c. Every face remembers the plane that made it; every corner remembers the
 * plane across the edge that starts at it, so Voronoi edges (edges between two
 * bisector faces) can be told from edges of the starting box. One instance per thread;
 * after the first cells it no longer allocates. */
class CoconeCellClipper
{
public:
  struct Result
  {
    double radius = 0; ///< largest distance of a Voronoi edge point in the cocone
    bool reached_limit = false; ///< the cocone reaches the box: radius >= limit
  };

  /** Cocone radius of the sample at the origin, from the part of its Voronoi cell in a
   * box around the cocone.
   * \param axis unit pole vector of the sample
   * \param sin_theta sine of the cocone angle
   * \param limit only cocone points closer than this are measured exactly; a radius
   *        of \a limit or more is reported as reached_limit
   * \param margin the box is \a margin times larger than needed for \a limit (>= 1),
   *        so that \a neighbours also covers some surroundings
   * \param offsets positions of a superset of the Voronoi neighbours, relative to the
   *        sample (no zero vector)
   * \param[out] neighbours if given: the indices into \a offsets whose bisector bounds
   *             the cell inside the box
   * \param cut if given: the cell is also cut by the plane through the sample normal
   *        to *cut, keeping the side y.cut <= 0, and the edges of that cut count as
   *        Voronoi edges (a rim sample measured on the side where the surface is) */
  Result coconeRadius(const Eigen::Vector3d& axis, double sin_theta, double limit,
                      double margin, const std::vector<Eigen::Vector3d>& offsets,
                      std::vector<int>* neighbours = nullptr,
                      const Eigen::Vector3d* cut = nullptr);

  /** The whole Voronoi cell of the sample at the origin, inside a cube of half size
   * \a extent (far larger than the data: what lies beyond is "at infinity").
   * \param[out] neighbours the indices into \a offsets whose bisector bounds the cell:
   *             its Delaunay neighbours among \a offsets
   * \param cut as for coconeRadius
   * \return the cocone radius; reached_limit when the cocone reaches the cube (an
   *         unbounded cocone) */
  Result fullCell(const Eigen::Vector3d& axis, double sin_theta, double extent,
                  const std::vector<Eigen::Vector3d>& offsets,
                  std::vector<int>& neighbours, const Eigen::Vector3d* cut = nullptr);

private:
  void clipAll(const std::vector<Eigen::Vector3d>& offsets);
  /** Resets to the box, clips it by every neighbour and lists the neighbours whose
   * planes bound the result in \a neighbours (if given). */
  void clipBox(const Eigen::Vector3d& axis, double half_width, double half_height,
               const std::vector<Eigen::Vector3d>& offsets,
               std::vector<int>* neighbours, const Eigen::Vector3d* cut);
  Result
  measureRadius(const Eigen::Vector3d& axis, double sin_theta, double limit) const;

  /** Plane index of the cut: above every offset index, so that its edges with
   * bisector faces are visited from the bisector side like any Voronoi edge. */
  static constexpr int kCutPlane = std::numeric_limits<int>::max();

  struct Corner
  {
    Eigen::Vector3d position;
    int across; // plane of the face on the other side of the edge from this corner
  };
  struct Face
  {
    int plane; // >= 0: index into offsets; < 0: a face of the box
    std::uint32_t first;
    std::uint32_t count;
  };
  struct Cut
  {
    Eigen::Vector3d from; // where the face is entered again
    Eigen::Vector3d to;   // where the face was left
    int plane;            // the cut face
  };

  void resetToBox(const Eigen::Vector3d& axis, double half_width, double half_height);
  void clip(const Eigen::Vector3d& normal, double offset, int plane);

  std::vector<Corner> corners_, next_corners_;
  std::vector<Face> faces_, next_faces_;
  std::vector<double> distance_;
  std::vector<Cut> cuts_;
  std::vector<std::pair<double, int>> order_;
  double max_corner_norm2_ = 0;
};

} // namespace detail
} // namespace cocone
} // namespace pcl
