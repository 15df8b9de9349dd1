// SPDX-License-Identifier: GPL-3.0-or-later
#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/parameters.h>

#include "boundary/cocone_links.h"
#include "common/parallel.h"
#include "common/status_guard.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl {
namespace cocone {

using detail::forEachCoconeLink;
using detail::forEachTriangleNeighbour;

namespace {

/** The samples q whose cocone meets V_p (p in N_q). Calls visit(q) for each (with
 * repeats). */
template <typename Visit>
void
forEachMarker(const VoronoiCocone& voronoi, SampleIndex p, Visit&& visit)
{
  forEachTriangleNeighbour(voronoi, p, [&](SampleIndex q, bool, bool q_marks) {
    if (q_marks)
      visit(q);
  });
}

/** Beyond the paper: BOUNDARY flags only part of the outermost row, because a rim
 * sample whose cell is closed off just beyond the rim by its neighbours' cells passes
 * the ratio test. Starting from the flags, walk along cocone links and flag every
 * sample whose links leave a rim-sized gap (kRimGapAngle), continuing only from the
 * samples so flagged: the walk stays on the rim, and a shape with no flag (closed and
 * well sampled) gets none. Each sample is tested once. */
void
completeRimRow(const VoronoiCocone& voronoi, std::vector<std::uint8_t>& is_boundary)
{
  std::vector<std::uint8_t> tested(is_boundary);
  std::vector<SampleIndex> queue;
  for (std::size_t i = 0; i < is_boundary.size(); ++i)
    if (is_boundary[i])
      queue.push_back(static_cast<SampleIndex>(i));
  std::vector<SampleIndex> candidates, links;
  std::vector<double> scratch;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    candidates.clear();
    forEachCoconeLink(voronoi, queue[head],
                      [&](SampleIndex q) { candidates.push_back(q); });
    for (const SampleIndex p : candidates) {
      if (tested[p])
        continue;
      tested[p] = 1;
      if (detail::widestTangentGap(voronoi, p, detail::TangentPlane::pole_vector, links,
                                   scratch)
              .angle > detail::kRimGapAngle) {
        is_boundary[p] = 1;
        queue.push_back(p);
      }
    }
  }
}

/** BOUNDARY on a diagram that holds one, with valid parameters. */
void
runBoundary(const VoronoiCocone& voronoi, const BoundaryParameters& parameters,
            std::vector<std::uint8_t>& is_boundary)
{
  const std::size_t n = voronoi.size();
  is_boundary.assign(n, 0);
  const double cos_alpha = std::cos(parameters.normal_angle);
  // Both conditions compare pole *lines*: orientation is ignored.
  const auto agree = [&](SampleIndex p, SampleIndex q) {
    return std::abs(voronoi.poleVector(p).dot(voronoi.poleVector(q))) >= cos_alpha;
  };

  // Both conditions per sample, in parallel. The normal condition: every q whose cocone
  // meets V_p (p in N_q: a triangle at p that q marks) agrees with p.
  std::vector<std::uint8_t> thin(n, 0), disagrees(n, 0);
  detail::runInArena(voronoi.getNumberOfThreads(), [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const auto p = static_cast<SampleIndex>(i);
        if (voronoi.representative(p) != p)
          continue;
        thin[i] = voronoi.ratio(p) <= parameters.ratio_bound;
        forEachMarker(voronoi, p, [&](SampleIndex q) { disagrees[i] |= !agree(p, q); });
      }
    });
  });

  // R: the flat samples, grown through cocone neighbours (p in N_q, q in R) that are
  // thin and agree with q: the least set closed under that rule. Only thin samples
  // that disagree can join, so the closure is computed from their side (a few
  // percent of the samples on a scan) instead of from every flat sample.
  std::vector<std::uint8_t> interior(n, 0), queued(n, 0);
  std::vector<SampleIndex> queue;
  for (std::size_t i = 0; i < n; ++i) {
    interior[i] = thin[i] && !disagrees[i];
    if (thin[i] && disagrees[i]) {
      queue.push_back(static_cast<SampleIndex>(i));
      queued[i] = 1;
    }
  }
  std::vector<SampleIndex> neighbours;
  while (!queue.empty()) {
    const SampleIndex p = queue.back();
    queue.pop_back();
    queued[p] = 0;
    bool joins = false;
    forEachMarker(voronoi, p, [&](SampleIndex q) {
      joins = joins || (interior[q] && agree(p, q));
    });
    if (!joins)
      continue;
    interior[p] = 1;
    // p now lets the thin samples of N_p join: look at them again.
    voronoi.coconeNeighbours(p, neighbours);
    for (const SampleIndex r : neighbours)
      if (thin[r] && !interior[r] && !queued[r]) {
        queued[r] = 1;
        queue.push_back(r);
      }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const SampleIndex r = voronoi.representative(static_cast<SampleIndex>(i));
    is_boundary[i] = r == i && !interior[i];
  }

  if (parameters.complete_rim_row)
    completeRimRow(voronoi, is_boundary);

  // Optional band: rings of cocone neighbours around the flags.
  std::vector<SampleIndex> frontier;
  for (std::size_t i = 0; i < n; ++i)
    if (is_boundary[i])
      frontier.push_back(static_cast<SampleIndex>(i));
  std::vector<SampleIndex> next;
  for (unsigned ring = 0; ring < parameters.band_rings && !frontier.empty(); ++ring) {
    next.clear();
    for (const SampleIndex p : frontier)
      forEachCoconeLink(voronoi, p, [&](SampleIndex q) {
        if (!is_boundary[q]) {
          is_boundary[q] = 1;
          next.push_back(q);
        }
      });
    frontier.swap(next);
  }

  for (std::size_t i = 0; i < n; ++i)
    is_boundary[i] = is_boundary[voronoi.representative(static_cast<SampleIndex>(i))];
}

} // namespace

Status
detectBoundarySamples(const VoronoiCocone& voronoi,
                      const BoundaryParameters& parameters,
                      std::vector<std::uint8_t>& is_boundary, std::string* message)
{
  is_boundary.clear();
  if (voronoi.status() != Status::ok) {
    detail::setMessage(message, "BOUNDARY needs a diagram: compute() did not succeed");
    return Status::not_computed;
  }
  if (!isValid(parameters)) {
    detail::setMessage(message, "a parameter of BOUNDARY is outside its range");
    return Status::invalid_parameter;
  }
  const Status status = detail::runGuarded("boundary detection", message, [&] {
    runBoundary(voronoi, parameters, is_boundary);
    return Status::ok;
  });
  if (status != Status::ok)
    std::vector<std::uint8_t>().swap(is_boundary);
  return status;
}

namespace detail {

namespace {

/** Links longer than this many times the median link of a sample are not its surface
 * neighbours: across a hole, the cocone of a rim sample meets cells on the other side.
 * The results hardly depend on it (2 to 3.5 gave the same flags within 0.1% on the
 * benchmark's open surfaces). */
constexpr double kFarLink = 2.5;

} // namespace

TangentGap
widestTangentGap(const VoronoiCocone& voronoi, SampleIndex p, TangentPlane plane,
                 std::vector<SampleIndex>& links, std::vector<double>& scratch)
{
  TangentGap result;
  result.normal = voronoi.poleVector(p);
  result.direction.setZero();
  links.clear();
  forEachCoconeLink(voronoi, p, [&](SampleIndex q) { links.push_back(q); });
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  const std::vector<Eigen::Vector3d>& points = voronoi.centeredPoints();
  const Eigen::Vector3d& origin = points[p];
  scratch.clear();
  for (const SampleIndex q : links)
    scratch.push_back((points[q] - origin).squaredNorm());
  if (scratch.size() < 2)
    return result;
  std::nth_element(scratch.begin(), scratch.begin() + scratch.size() / 2,
                   scratch.end());
  const double limit = kFarLink * kFarLink * scratch[scratch.size() / 2];

  if (plane == TangentPlane::fitted) {
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const SampleIndex q : links) {
      const Eigen::Vector3d d = points[q] - origin;
      if (d.squaredNorm() <= limit)
        scatter += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(scatter);
    result.normal = solver.eigenvectors().col(0); // smallest eigenvalue first
    const Eigen::Vector3d& spread = solver.eigenvalues();
    result.thickness = spread[1] > 0 ? spread[0] / spread[1] : 1;
  }
  const Eigen::Vector3d& normal = result.normal;
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d w = normal.cross(u);
  scratch.clear();
  for (const SampleIndex q : links) {
    const Eigen::Vector3d d = points[q] - origin;
    if (d.squaredNorm() <= limit)
      scratch.push_back(std::atan2(d.dot(w), d.dot(u)));
  }
  if (scratch.size() < 2)
    return result;
  std::sort(scratch.begin(), scratch.end());
  // The gap that wraps around from the last direction to the first, then the others.
  result.angle = scratch.front() + 2 * M_PI - scratch.back();
  double gap_start = scratch.back();
  for (std::size_t k = 1; k < scratch.size(); ++k)
    if (scratch[k] - scratch[k - 1] > result.angle) {
      result.angle = scratch[k] - scratch[k - 1];
      gap_start = scratch[k - 1];
    }
  const double middle = gap_start + result.angle / 2;
  result.direction = std::cos(middle) * u + std::sin(middle) * w;
  return result;
}

} // namespace detail

} // namespace cocone
} // namespace pcl
