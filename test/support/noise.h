// SPDX-License-Identifier: GPL-3.0-or-later
// Scanner noise for the tests and benchmarks: Gaussian perturbations of sampled shapes.
#pragma once

#include "support/shapes.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl {
namespace cocone {
namespace test {

/** \a points, each moved by an isotropic Gaussian displacement: every coordinate gets
 * an independent normal deviate of standard deviation \a sigma (so the distance along
 * any direction, the surface normal included, has standard deviation \a sigma).
 * Deterministic for a given seed on every platform (the deviates are made here, by
 * Box-Muller over std::mt19937, whose output the standard fixes bit for bit). */
std::vector<Eigen::Vector3d>
addGaussianNoise(const std::vector<Eigen::Vector3d>& points, double sigma,
                 std::uint32_t seed = 7);

/** \a shape with Gaussian noise of standard deviation \a sigma_in_spacings times its
 * spacing (SampledShape::spacing) added to its points (see addGaussianNoise); its
 * normals, rim and distance functions still describe the true surface. */
SampledShape
withGaussianNoise(SampledShape shape, double sigma_in_spacings, std::uint32_t seed = 7);

} // namespace test
} // namespace cocone
} // namespace pcl
