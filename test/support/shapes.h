// SPDX-License-Identifier: GPL-3.0-or-later
// Analytic test surfaces, sampled in the tests themselves (no data files needed).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

/** A sample of an analytic surface with the facts the tests check results against. */
struct SampledShape
{
  std::string name;
  std::vector<Eigen::Vector3d> points;
  /** Unit surface normal at each point (outward for closed shapes). On the cube's
   * faces the face normal. */
  std::vector<Eigen::Vector3d> normals;
  double area = 0; ///< surface area
  bool closed = true;
  int genus = 0;
  int boundary_loops = 0;

  /** sqrt(area / n): the "spacing" the tests measure distances in. */
  double spacing() const;

  /** Dense points (spacing/4 apart or closer) along the true rim of an open shape, and
   * along the sharp edges of the cube; empty for smooth closed shapes. */
  std::vector<Eigen::Vector3d> rim;

  /** Distance from a point of the surface to the rim (open shapes) or to the nearest
   * sharp edge (cube); +infinity where there is none. */
  std::function<double(const Eigen::Vector3d&)> distance_to_rim;

  /** Local feature size at a point of the surface (distance to the medial axis), where
   * known in closed form (sphere, torus); empty otherwise. */
  std::function<double(const Eigen::Vector3d&)> local_feature_size;

  /** Distance from any point of space to the surface (exact or a tight
   * approximation: within 1% of the spacing). */
  std::function<double(const Eigen::Vector3d&)> distance_to_surface;
};

// Every generator returns exactly n points, deterministic for a given seed, spread as
// blue noise (well separated, no large gaps: the largest empty disc on the surface is
// at most about 1.5 spacings), and moved off the surface by a tiny normal jitter (at
// most 1e-5 of the bounding-box diagonal, and 1e-3 spacing^2 / diagonal: small enough
// not to move the Voronoi vertices deep inside) so that no four points are exactly
// co-spherical (exact samples of analytic surfaces make Delaunay slow and degenerate).

/** Unit sphere centred at the origin. */
SampledShape sampleSphere(std::size_t n, std::uint32_t seed = 1);

/** Sphere of radius 1 whose cap within 40 degrees of +z is sampled 8 times denser than
 * the rest (per unit area). */
SampledShape sampleSphereWithDenseCap(std::size_t n, std::uint32_t seed = 1);

/** Torus around the z axis, major radius 1, minor radius 0.35 (genus 1). */
SampledShape sampleTorus(std::size_t n, std::uint32_t seed = 1);

/** Tube of radius 0.25 around the trefoil knot
 * (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t), t in [0, 2 pi): the paper's KNOT
 * (closed, genus 1). */
SampledShape sampleTrefoilKnot(std::size_t n, std::uint32_t seed = 1);

/** A closed genus-3 surface: a rounded slab (about 3.9 x 1.7 x 0.5: the points within
 * 0.25 of a planar stadium) with three round through-holes in a row (radius 0.5 at the
 * flat faces, 0.25 at the waist). Local feature size at least 0.25. */
SampledShape sampleGenus3(std::size_t n, std::uint32_t seed = 1);

/** Upper unit hemisphere z >= 0 (open: one boundary loop, the equator). */
SampledShape sampleHemisphere(std::size_t n, std::uint32_t seed = 1);

/** Monkey saddle z = x^3 - 3 x y^2 over the unit disc (the paper's MONKEYSADDLE; open:
 * one boundary loop). */
SampledShape sampleMonkeySaddle(std::size_t n, std::uint32_t seed = 1);

/** Open cylinder of radius 0.5 and height 2 around the z axis (two boundary loops). */
SampledShape sampleOpenCylinder(std::size_t n, std::uint32_t seed = 1);

/** Surface of the cube [-1, 1]^3: closed, genus 0, 12 sharp edges. */
SampledShape sampleCube(std::size_t n, std::uint32_t seed = 1);

/** Half of the open cylinder: the part y >= 0 (open: one boundary loop, two half
 * circles and two straight edges meeting at four right-angled corners). */
SampledShape sampleHalfCylinder(std::size_t n, std::uint32_t seed = 1);

/** The shapes above, for sampleRandom (the dense-cap sphere is left out: its density
 * is its point). */
enum class Shape
{
  sphere,
  torus,
  trefoil_knot,
  genus3,
  cube,
  hemisphere,
  open_cylinder,
  half_cylinder,
  monkey_saddle,
};

/** A Shape's short name: "sphere", "torus", "knot", "genus3", "cube", "hemisphere",
 * "open_cylinder", "half_cylinder", "monkey_saddle". */
const char* shapeName(Shape shape);

/** Every Shape, closed ones first. */
const std::vector<Shape>& allShapes();

/** The same shapes sampled as a scanner does rather than as blue noise: n independent
 * area-uniform random points (a Poisson sample: close pairs and wide gaps, the widest
 * empty disc growing like sqrt(log n) spacings), deterministic for a given seed, with
 * a normal jitter of at most 1e-5 of the bounding-box diagonal. With \a density_ramp
 * the density per unit area grows as 8^t along x (t from 0 to 1 over the shape's
 * extent): 8 times denser at one end than at the other. The facts (area, genus,
 * loops, rim, distances) are those of the blue-noise generators; spacing() is the
 * mean one. */
SampledShape sampleRandom(Shape shape, std::size_t n, std::uint32_t seed = 1,
                          bool density_ramp = false);

} // namespace test
} // namespace cocone
} // namespace pcl
