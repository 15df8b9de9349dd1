// SPDX-License-Identifier: GPL-3.0-or-later
#include "support/noise.h"

#include <cmath>
#include <random>

namespace pcl {
namespace cocone {
namespace test {

namespace {

/** Standard normal deviates by the Box-Muller transform, two per pair of uniforms. */
class GaussianDeviates
{
public:
  explicit GaussianDeviates(std::uint32_t seed) : engine_(seed) {}

  double
  next()
  {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    // u1 in (0, 1]: its logarithm is finite.
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * 3.14159265358979323846 * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

private:
  /** Uniform in [0, 1) with 53 random bits. */
  double
  uniform()
  {
    const std::uint64_t high = engine_() >> 5; // 27 bits
    const std::uint64_t low = engine_() >> 6;  // 26 bits
    return static_cast<double>((high << 26) | low) * (1.0 / 9007199254740992.0);
  }

  std::mt19937 engine_;
  double spare_ = 0;
  bool has_spare_ = false;
};

} // namespace

std::vector<Eigen::Vector3d>
addGaussianNoise(const std::vector<Eigen::Vector3d>& points, double sigma,
                 std::uint32_t seed)
{
  GaussianDeviates deviates(seed);
  std::vector<Eigen::Vector3d> noisy;
  noisy.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const double dx = deviates.next(), dy = deviates.next(), dz = deviates.next();
    noisy.emplace_back(p + sigma * Eigen::Vector3d(dx, dy, dz));
  }
  return noisy;
}

SampledShape
withGaussianNoise(SampledShape shape, double sigma_in_spacings, std::uint32_t seed)
{
  shape.points =
      addGaussianNoise(shape.points, sigma_in_spacings * shape.spacing(), seed);
  return shape;
}

} // namespace test
} // namespace cocone
} // namespace pcl
