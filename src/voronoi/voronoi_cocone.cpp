// SPDX-License-Identifier: GPL-3.0-or-later
// VoronoiCocone (core/voronoi_cocone.h): the Delaunay triangulation of the samples, its
// per-sample geometry (cell_geometry.cpp) and the queries on what it keeps.
#include "common/parallel.h"
#include "common/progress.h"
#include "common/status_guard.h"
#include "voronoi/cell_geometry.h"
#include "voronoi/cgal_delaunay.h"
#include "voronoi/tile_messages.h"
#include "voronoi/tiled_delaunay.h"
#include "voronoi/tiling.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <pcl/cocone/core/denoise.h>
#include <pcl/cocone/core/tile_exchange.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

namespace pcl {
namespace cocone {

// ---------------------------------------------------------------------------------
using namespace detail;

namespace {
// Cells per side of the lock grid of CGAL's concurrent insertion (its own examples'
// value).
constexpr int kLockGrid = 50;
// The most tiles a diagram is cut into.
constexpr unsigned kMaxTiles = 1024;
// Samples per leaf, the unit a halo grows by.
constexpr unsigned kLeafSamples = 128;
// A tile whose halo would hold more than this many times its own samples (plus
// 2048) gives up: the cloud's cells reach too far for tiles to pay.
constexpr unsigned kHaloBudget = 3;
} // namespace

VoronoiCocone::VoronoiCocone(const VoronoiParameters& parameters)
  : impl_(new Impl), parameters_(parameters)
{}
VoronoiCocone::~VoronoiCocone() = default;
VoronoiCocone::VoronoiCocone(VoronoiCocone&&) noexcept = default;
VoronoiCocone& VoronoiCocone::operator=(VoronoiCocone&&) noexcept = default;

Status
VoronoiCocone::setCoconeAngle(double theta)
{
  if (!kCoconeAngleRange.contains(theta))
    return Status::invalid_parameter;
  parameters_.cocone_angle = theta;
  return Status::ok;
}

double
VoronoiCocone::getCoconeAngle() const
{
  return parameters_.cocone_angle;
}

void
VoronoiCocone::setNumberOfThreads(unsigned threads)
{
  parameters_.threads = threads;
}

unsigned
VoronoiCocone::getNumberOfThreads() const
{
  return parameters_.threads;
}

const VoronoiCocone::Timings&
VoronoiCocone::timings() const
{
  return impl_->timings;
}

Status
VoronoiCocone::status() const
{
  return impl_->status;
}

const std::string&
VoronoiCocone::errorMessage() const
{
  return impl_->message;
}

std::size_t
VoronoiCocone::size() const
{
  return impl_->representative.size();
}

std::size_t
VoronoiCocone::numUniqueSamples() const
{
  return impl_->unique_count;
}

SampleIndex
VoronoiCocone::representative(SampleIndex i) const
{
  return impl_->representative[i];
}

double
VoronoiCocone::typicalSpacing() const
{
  const DiagramState& d = *impl_;
  if (d.stars.empty() || d.unique_count == 0)
    return 0;
  constexpr std::size_t kProbes = 1024;
  const std::size_t n = d.representative.size();
  const std::size_t stride = std::max<std::size_t>(1, n / kProbes);
  SampleMarks seen;
  std::vector<SampleIndex> neighbours;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < n; i += stride) {
    const SampleIndex s = d.representative[i];
    neighbours.clear();
    d.stars.appendNeighbours(s, seen, neighbours);
    double best = std::numeric_limits<double>::infinity();
    for (const SampleIndex q : neighbours)
      best = std::min(best, (d.centered[q] - d.centered[s]).squaredNorm());
    if (std::isfinite(best))
      nearest.push_back(best);
  }
  if (nearest.empty())
    return 0;
  const auto middle = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), middle, nearest.end());
  return std::sqrt(*middle);
}

const std::vector<Eigen::Vector3d>&
VoronoiCocone::centeredPoints() const
{
  return impl_->centered;
}

const std::vector<Eigen::Vector3d>&
VoronoiCocone::centeredInputPoints() const
{
  return impl_->input_centered.empty() ? impl_->centered : impl_->input_centered;
}

bool
VoronoiCocone::denoised() const
{
  return !impl_->input_centered.empty();
}

const NoiseEstimate&
VoronoiCocone::noiseEstimate() const
{
  return impl_->noise;
}

unsigned
VoronoiCocone::smoothingRounds() const
{
  return impl_->smoothing_rounds;
}

void
VoronoiCocone::setDenoise(DenoiseMode mode)
{
  parameters_.denoise = mode;
}

DenoiseMode
VoronoiCocone::getDenoise() const
{
  return parameters_.denoise;
}

const Eigen::Vector3d&
VoronoiCocone::offset() const
{
  return impl_->offset;
}

const Eigen::Vector3d&
VoronoiCocone::poleVector(SampleIndex i) const
{
  return impl_->pole_vector[impl_->representative[i]];
}

bool
VoronoiCocone::positivePoleAtInfinity(SampleIndex i) const
{
  return impl_->unbounded[impl_->representative[i]] != 0;
}

Eigen::Vector3d
VoronoiCocone::positivePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (impl_->unbounded[r])
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  return impl_->positive_pole[r] + impl_->offset;
}

Eigen::Vector3d
VoronoiCocone::negativePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (!(impl_->height[r] > 0))
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return impl_->negative_pole[r] + impl_->offset;
}

double
VoronoiCocone::height(SampleIndex i) const
{
  return impl_->height[impl_->representative[i]];
}

double
VoronoiCocone::coconeRadius(SampleIndex i) const
{
  return impl_->radius[impl_->representative[i]];
}

double
VoronoiCocone::ratio(SampleIndex i) const
{
  return impl_->ratio(impl_->representative[i]);
}

const std::vector<MarkedTriangle>&
VoronoiCocone::markedTriangles() const
{
  return impl_->triangles;
}

IndexRange
VoronoiCocone::trianglesAround(SampleIndex i) const
{
  if (impl_->triangle_offsets.empty())
    return {};
  const SampleIndex r = impl_->representative[i];
  const std::uint32_t* base = impl_->triangle_ids.data();
  return {base + impl_->triangle_offsets[r], base + impl_->triangle_offsets[r + 1]};
}

void
VoronoiCocone::coconeNeighbours(SampleIndex i,
                                std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  const SampleIndex r = impl_->representative[i];
  for (const std::uint32_t t : trianglesAround(r)) {
    const MarkedTriangle& triangle = impl_->triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (triangle.vertex[k] != r || !triangle.isMarkedBy(k))
        continue;
      for (int other = 0; other < 3; ++other)
        if (other != k)
          neighbours.push_back(triangle.vertex[other]);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
}

void
VoronoiCocone::delaunayNeighbours(SampleIndex i,
                                  std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  if (impl_->stars.empty())
    return;
  // Several threads may ask at once: per-thread scratch, which stops allocating after
  // a thread's first calls.
  thread_local SampleMarks seen;
  impl_->stars.appendNeighbours(impl_->representative[i], seen, neighbours);
  std::sort(neighbours.begin(), neighbours.end());
}

void
VoronoiCocone::delaunayTrianglesAmong(
    const std::vector<SampleIndex>& samples,
    std::vector<std::array<SampleIndex, 3>>& triangles) const
{
  triangles.clear();
  const DelaunayStars& stars = impl_->stars;
  if (stars.empty())
    return;
  // Several threads may ask at once (one hole each): per-thread scratch.
  thread_local SampleMarks is_member;
  thread_local std::vector<SampleIndex> members;
  members.clear();
  is_member.clear();
  for (const SampleIndex s : samples)
    if (is_member.mark(impl_->representative[s]))
      members.push_back(impl_->representative[s]);
  // kNoSample (the infinite vertex) is never marked.
  for (const SampleIndex s : members) {
    for (std::uint32_t k = stars.offsets[s]; k < stars.offsets[s + 1]; ++k) {
      const std::array<SampleIndex, 4>& cell = stars.cell_samples[stars.cells[k]];
      // Most cells at a hole's rim have only s and one other member: no facet of
      // three members, told without looking at the facets.
      int in_cell = 0;
      for (const SampleIndex w : cell)
        in_cell += is_member.isMarked(w);
      if (in_cell < 3)
        continue;
      for (int i = 0; i < 4; ++i) {
        if (cell[i] == s)
          continue; // the facet opposite s does not contain it
        std::array<SampleIndex, 3> t;
        int m = 0;
        bool keep = true;
        for (int j = 0; j < 4 && keep; ++j) {
          if (j == i)
            continue;
          if (!is_member.isMarked(cell[j]))
            keep = false;
          else
            t[m++] = cell[j];
        }
        // Report each triangle from its smallest vertex; it lies in two cells, so the
        // repeats go after sorting.
        if (!keep)
          continue;
        std::sort(t.begin(), t.end());
        if (t[0] == s)
          triangles.push_back(t);
      }
    }
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
}

namespace {

/** The one-line reason of a failure caught in the tile phase, for the root: what
 * runGuarded would have said of it ("out of memory during the tile triangulation"). */
std::string
reasonOf(const std::exception_ptr& failure)
{
  std::string reason;
  runGuarded("the tile triangulation", &reason,
             [&]() -> Status { std::rethrow_exception(failure); });
  return reason.empty() ? std::string("the tile triangulation failed") : reason;
}

/** compute() without its outer guard: each stage that allocates much runs in a guard of
 * its own, whose message names it. */
Status
buildDiagram(DiagramState& d, const VoronoiParameters& parameters,
             const std::vector<Eigen::Vector3d>& points,
             const ProgressCallback& callback)
{
  // The triangulation takes about three quarters of compute(), the geometry the rest.
  const StageProgress progress(callback, 0, 1);
  const StageProgress triangulation = progress.part(0, 0.75);
  d = DiagramState();
  // Several processes (core/tile_exchange.h): this one builds the tiles dealt to it,
  // and calls the exchange exactly once, whatever happens: a process that fails
  // before its tiles are sent sends its reason instead, and a root that fails first
  // still calls it, so that no process waits for another forever. A failed root hands
  // its reason too, which tells the exchange that it will read nothing.
  TileExchange* const exchange = parameters.exchange.get();
  const unsigned rank = exchange ? exchange->rank() : 0;
  const unsigned ranks = exchange ? exchange->size() : 1;
  bool exchanged = !exchange || ranks < 2 || rank >= ranks;
  const auto fail = [&](Status status, const std::string& message) {
    if (!exchanged) {
      exchanged = true;
      try {
        exchange->gatherToRoot(packFailure(message)); // the root too: see below
      }
      catch (...) { // the failure reported here says more than the exchange's
      }
    }
    DiagramState fresh;
    fresh.status = status;
    fresh.message = message;
    d = std::move(fresh);
    return status;
  };

  if (!isValid(parameters))
    return fail(Status::invalid_parameter,
                "the cocone angle " + std::to_string(parameters.cocone_angle) +
                    " is outside " + kCoconeAngleRange.text());
  if (ranks == 0 || rank >= ranks)
    return fail(Status::invalid_parameter, "the tile exchange names process " +
                                               std::to_string(rank) + " of " +
                                               std::to_string(ranks));
  const std::size_t n = points.size();
  if (n >= static_cast<std::size_t>(kNoSample))
    return fail(Status::too_many_points,
                "more points than 32-bit sample indices address");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      std::ostringstream message;
      message << "point " << i << " has a non-finite coordinate";
      return fail(Status::non_finite_input, message.str());
    }
    sum += points[i];
  }
  if (n < 4)
    return fail(Status::too_few_points,
                "need at least 4 points for a 3D Voronoi diagram, got " +
                    std::to_string(n));
  // Decide the dimension on the points as given, with exact predicates: translating
  // them to their centroid rounds each coordinate, which can lift exactly coplanar
  // points off their plane by 1e-15 and hide the degeneracy from the triangulation.
  {
    const auto at = [&](std::size_t i) {
      return Point(points[i].x(), points[i].y(), points[i].z());
    };
    std::size_t second = 1, third = 0, fourth = 0;
    while (second < n && at(second) == at(0))
      ++second;
    for (std::size_t i = second + 1; i < n && third == 0; ++i)
      if (!CGAL::collinear(at(0), at(second), at(i)))
        third = i;
    for (std::size_t i = third + 1; third != 0 && i < n && fourth == 0; ++i)
      if (CGAL::orientation(at(0), at(second), at(third), at(i)) != CGAL::COPLANAR)
        fourth = i;
    if (second == n)
      return fail(Status::too_few_points, "need at least 4 distinct points, got 1");
    if (third == 0)
      return fail(Status::degenerate_dimension,
                  "all points are collinear: no 3D Voronoi cell to measure");
    if (fourth == 0)
      return fail(Status::degenerate_dimension,
                  "all points are coplanar: no 3D Voronoi cell to measure");
  }

  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  // Scanner noise (core/denoise.h): the diagram of a noisy cloud is built on a smoothed
  // copy, while every result stays indexed by the samples as given.
  const Clock::time_point denoise_start = Clock::now();
  std::vector<Eigen::Vector3d> smoothed;
  if (parameters.denoise != DenoiseMode::off) {
    std::string denoise_message;
    const Status denoise_status =
        runGuarded("the noise handling", &denoise_message, [&] {
          d.noise = estimateNoise(points, parameters.threads);
          if (parameters.denoise == DenoiseMode::on ||
              d.noise.relative_noise > kNoiseThreshold) {
            SmoothedSamples copy = smoothSamples(points, parameters.threads);
            d.smoothing_rounds = copy.rounds;
            smoothed = std::move(copy.points);
          }
          return Status::ok;
        });
    if (denoise_status != Status::ok)
      return fail(denoise_status, denoise_message);
  }
  const bool denoised = !smoothed.empty();
  const std::vector<Eigen::Vector3d>& geometry = denoised ? smoothed : points;
  d.timings.denoise = seconds_since(denoise_start);
  if (parameters.denoise != DenoiseMode::off)
    PCL_DEBUG(
        "[pcl::cocone::VoronoiCocone::compute] noise %.4f spacings (threshold %g): "
        "%s, %u smoothing rounds, %.3f s\n",
        d.noise.relative_noise, kNoiseThreshold, denoised ? "smoothed" : "as given",
        d.smoothing_rounds, d.timings.denoise);

  const Clock::time_point start = Clock::now();
  std::string message;
  std::vector<SampleIndex> distinct;
  Status status = runGuarded("the Delaunay triangulation", &message, [&] {
    runInArena(parameters.threads, [&] {
      d.offset = sum / static_cast<double>(n);
      d.centered.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        d.centered[i] = geometry[i] - d.offset;
      if (denoised) {
        d.input_centered.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          d.input_centered[i] = points[i] - d.offset;
      }
      // Identical points are one sample: every input point maps to the smallest index
      // of its group, so nothing is lost or renumbered, and only those smallest
      // indices are triangulated.
      std::vector<SampleIndex> by_position(n);
      std::iota(by_position.begin(), by_position.end(), SampleIndex(0));
      tbb::parallel_sort(by_position.begin(), by_position.end(),
                         [&](SampleIndex a, SampleIndex b) {
                           const Eigen::Vector3d &p = d.centered[a], &q = d.centered[b];
                           if (p.x() != q.x())
                             return p.x() < q.x();
                           if (p.y() != q.y())
                             return p.y() < q.y();
                           if (p.z() != q.z())
                             return p.z() < q.z();
                           return a < b;
                         });
      d.representative.resize(n);
      for (std::size_t i = 0; i < n;) {
        std::size_t j = i + 1;
        while (j < n && d.centered[by_position[j]] == d.centered[by_position[i]])
          ++j;
        for (std::size_t k = i; k < j; ++k)
          d.representative[by_position[k]] = by_position[i];
        distinct.push_back(by_position[i]);
        i = j;
      }
      d.unique_count = distinct.size();
    });
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  if (d.unique_count < 4)
    return fail(Status::too_few_points, "need at least 4 distinct points, got " +
                                            std::to_string(d.unique_count));

  // The tiles (parameters.h, VoronoiParameters::tiles): each a triangulation with a
  // halo that makes its samples' stars exact, then the per-sample geometry of its own
  // samples; joined into one diagram.
  const std::size_t unique = d.unique_count;
  // Automatic: one tile. The halos that make a surface's stars exact are large (the
  // poles of a sample lie on the medial axis, as far as the local feature size):
  // measured on random samples of closed and open surfaces, two tiles triangulate
  // 1.5 to 2 times the samples, more tiles give up (docs/scaling.md). One
  // triangulation built on every core beats that.
  // At most one tile per leaf, and kMaxTiles: each tile scans every leaf's box.
  const unsigned tiles = std::min<unsigned>(
      {parameters.tiles == 0 ? 1 : parameters.tiles, kMaxTiles,
       static_cast<unsigned>(std::max<std::size_t>(1, unique / kLeafSamples))});
  const double sin_theta = std::sin(parameters.cocone_angle);
  std::vector<TileContribution> contributions;
  double delaunay_seconds = 0, geometry_seconds = 0;
  std::size_t triangulated = 0;
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::size_t> inserted{0};
  std::atomic<bool> cancelled{false};
  enum class Outcome
  {
    built,
    outgrown,
    handed_off
  };
  // distributed: the tiles are dealt out among the processes, tile t to process
  // t mod ranks, and the root gathers the others' results.
  const auto build_tiles = [&](unsigned tile_count, bool distributed) {
    // One tile needs no leaves: every sample is its own.
    const KdTiling tiling(d.centered, distinct, tile_count,
                          tile_count == 1 ? ~0u : kLeafSamples);
    const unsigned count = tiling.numTiles();
    std::vector<std::uint32_t> tile_of(n, 0);
    for (unsigned t = 0; t < count; ++t)
      tiling.forEachSampleOfTile(t, [&](SampleIndex s) { tile_of[s] = t; });
    contributions.assign(count, TileContribution());
    std::vector<unsigned> mine;
    for (unsigned t = 0; t < count; ++t)
      if (!distributed || t % ranks == rank)
        mine.push_back(t);
    std::vector<TileTriangulationStats> stats(count);
    std::vector<double> dt_time(count, 0), geometry_time(count, 0);
    std::atomic<bool> outgrown{false};
    const auto on_inserted = [&](std::size_t k) {
      const std::size_t done = inserted += k;
      if (cancelled)
        throw StageFailure{Status::internal_error, "cancelled"};
      if (std::this_thread::get_id() == caller) {
        try {
          triangulation.report(std::min(1.0, double(done) / double(unique)));
        }
        catch (...) {
          cancelled = true;
          throw;
        }
      }
    };
    // A failure here (cancelled, out of memory) is kept until the tiles are exchanged.
    std::exception_ptr failure;
    try {
      tbb::parallel_for(
          std::size_t(0), mine.size(), std::size_t(1), [&](std::size_t k) {
            const unsigned t = mine[k];
            if (outgrown)
              return;
            Clock::time_point tile_start = Clock::now();
            const Eigen::AlignedBox3d& box = tiling.box();
            DelaunayLocks locks(CGAL::Bbox_3(box.min().x(), box.min().y(),
                                             box.min().z(), box.max().x(),
                                             box.max().y(), box.max().z()),
                                kLockGrid);
            // One thread: no locks, CGAL's sequential insertion.
            Delaunay dt(Kernel(), parameters.threads == 1 ? nullptr : &locks);
            stats[t] = triangulateTile(tiling, t, d.centered, tile_of, kHaloBudget, dt,
                                       on_inserted, [&] { return outgrown.load(); });
            if (!stats[t].complete) {
              outgrown = true;
              return;
            }
            dt_time[t] = seconds_since(tile_start);
            tile_start = Clock::now();
            computeTileGeometry(dt, d.centered, tile_of, t, sin_theta, d,
                                contributions[t]);
            geometry_time[t] = seconds_since(tile_start);
          });
    }
    catch (...) {
      failure = std::current_exception();
    }
    bool complete = !outgrown;
    if (distributed && !exchanged) {
      // Every process sends, even one whose tiles gave up or failed, so that none
      // waits.
      const std::uint64_t fingerprint = diagramFingerprint(d, tiling);
      // The root sends nothing unless it failed: then its reason tells the exchange
      // that the others' messages will not be read (job files need not wait for them).
      std::vector<std::uint8_t> mine_message;
      try {
        if (failure)
          mine_message = packFailure(reasonOf(failure));
        else if (rank != 0)
          mine_message =
              packTiles(tiling, mine, complete, fingerprint, d, contributions);
      }
      catch (...) {
        mine_message = packFailure("out of memory packing its tiles");
      }
      exchanged = true;
      std::vector<std::vector<std::uint8_t>> messages;
      try {
        messages = exchange->gatherToRoot(mine_message);
      }
      catch (...) {
        if (!failure)
          throw;
        // This process's own failure came first and is the one to report.
      }
      if (failure)
        std::rethrow_exception(failure);
      if (rank != 0)
        return Outcome::handed_off;
      if (messages.size() != ranks)
        throw StageFailure{Status::internal_error,
                           "the tile exchange returned " +
                               std::to_string(messages.size()) + " messages for " +
                               std::to_string(ranks) + " processes"};
      for (unsigned r = 1; r < ranks; ++r) {
        if (!unpackTiles(messages[r], r, ranks, tiling, fingerprint, d, contributions))
          complete = false;
        std::vector<std::uint8_t>().swap(messages[r]); // its copy is in d now
      }
    }
    if (failure)
      std::rethrow_exception(failure);
    if (!complete)
      return Outcome::outgrown;
    for (unsigned t = 0; t < count; ++t) {
      delaunay_seconds += dt_time[t];
      geometry_seconds += geometry_time[t];
      triangulated += stats[t].local;
    }
    d.timings.tiles = count;
    return Outcome::built;
  };
  Outcome outcome = Outcome::built;
  status = runGuarded("the Delaunay triangulation", &message, [&] {
    runInArena(parameters.threads, [&] {
      d.pole_vector.assign(n, Eigen::Vector3d::Zero());
      d.positive_pole.assign(n, Eigen::Vector3d::Zero());
      d.negative_pole.assign(n, Eigen::Vector3d::Zero());
      d.height.assign(n, std::numeric_limits<double>::quiet_NaN());
      d.radius.assign(n, std::numeric_limits<double>::quiet_NaN());
      d.unbounded.assign(n, 0);
      outcome = build_tiles(tiles, true);
      if (outcome == Outcome::outgrown) {
        PCL_DEBUG("[pcl::cocone::VoronoiCocone] a tile's halo outgrew %u times its "
                  "samples: one tile instead of %u\n",
                  kHaloBudget, tiles);
        inserted = 0;
        outcome = build_tiles(1, false);
      }
    });
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  if (outcome == Outcome::handed_off)
    return fail(Status::not_computed,
                "this process built its tiles and sent them to the root process");
  const double tile_phase = seconds_since(start);
  const double worked = delaunay_seconds + geometry_seconds;
  d.timings.delaunay = worked > 0 ? tile_phase * delaunay_seconds / worked : tile_phase;
  d.timings.triangulated_share = double(triangulated) / double(unique);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] Delaunay triangulation of %zu samples (%zu "
            "distinct) in %u tiles (%.3f of them triangulated): %.3f s\n",
            n, d.unique_count, d.timings.tiles, d.timings.triangulated_share,
            d.timings.delaunay);
  const Clock::time_point geometry_start = Clock::now();
  status = runGuarded("the Voronoi geometry", &message, [&] {
    progress.report(0.75);
    runInArena(parameters.threads, [&] { joinTiles(contributions, d); });
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  d.timings.geometry = tile_phase - d.timings.delaunay + seconds_since(geometry_start);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] poles, radii and cocone marks: %.3f s, %zu "
            "marked triangles\n",
            d.timings.geometry, d.triangles.size());
  status = runGuarded("the Voronoi geometry", &message, [&] {
    progress.report(1);
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  d.status = Status::ok;
  d.message.clear();
  return Status::ok;
}

} // namespace

Status
VoronoiCocone::compute(const std::vector<Eigen::Vector3d>& points,
                       const ProgressCallback& progress)
{
  std::string message;
  const Status status = runGuarded("building the diagram", &message, [&] {
    return buildDiagram(*impl_, parameters_, points, progress);
  });
  if (impl_->status != status) {
    // Something failed after the stages' own guards: forget the half-built diagram.
    *impl_ = Impl();
    impl_->status = status;
    impl_->message = std::move(message);
  }
  return status;
}

} // namespace cocone
} // namespace pcl
