// SPDX-License-Identifier: GPL-3.0-or-later
// DECIMATE (Dey et al. 2001, section 4) on the triangulation of VoronoiCocone.
#include "boundary/cocone_links.h"
#include "common/parallel.h"
#include "common/status_guard.h"
#include "voronoi/cell_clipper.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <pcl/cocone/core/decimation.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <queue>
#include <tuple>

namespace pcl {
namespace cocone {

using namespace detail;

namespace {

/** A rim sample's links lie near one plane: their mean squared distance to the fitted
 * plane is below this share of their spread along its second axis. On the 10k cube,
 * 139 of BOUNDARY's flags along the edges show a wide gap in their fitted plane; 90%
 * of them score 0.24 or more (links on both faces), and the few below 0.1 see only one
 * face. On the 10k monkey saddle, 90% of the rim samples score 0.03 or less. */
constexpr double kRimThickness = 0.1;

struct QueueEntry
{
  double ratio;
  SampleIndex sample;
  std::uint32_t version;
  // std::priority_queue is a max-heap: "greater" puts the smallest ratio on top, ties
  // broken by the smaller index, so the order (and the result) is deterministic.
  bool
  operator<(const QueueEntry& other) const
  {
    return std::tie(ratio, sample) > std::tie(other.ratio, other.sample);
  }
};

/** Drops removed samples, the sample itself and repeats from a neighbour list. */
void
compact(std::vector<SampleIndex>& list, SampleIndex self,
        const std::vector<std::uint8_t>& alive)
{
  list.erase(std::remove_if(list.begin(), list.end(),
                            [&](SampleIndex q) { return q == self || !alive[q]; }),
             list.end());
  std::sort(list.begin(), list.end());
  list.erase(std::unique(list.begin(), list.end()), list.end());
}

// How the diagram is kept up to date. CGAL's Delaunay_triangulation_3::remove costs
// about 130 us per vertex on surface samples (it triangulates the hole in a fresh
// auxiliary triangulation, with hash maps), 20 times the rest of a removal step. But
// removing p only joins pairs of p's former Delaunay neighbours, so the new neighbours
// of a sample q are among its old ones and p's: the Delaunay graph is updated in place
// by merging neighbour lists (supersets are harmless), and the cocone radius of each
// affected sample is recomputed from its own cell alone, by clipping with the bisectors
// of its listed neighbours (CoconeCellClipper). Only cocone points closer than
// rho * h_q matter (a larger radius means "keep"), which bounds the clipped cell and
// the neighbour lists (see kListMargin).
//
// Removals are lazy in one more way: a sample whose cell changed keeps its old ratio as
// its key (ratios only grow when neighbours go), and its radius is recomputed when that
// key reaches the top of the queue. The smallest true ratio is therefore always removed
// first, and a sample is recomputed once per time it is a candidate, not once per
// neighbour removal.
Status
runDecimate(const VoronoiCocone& voronoi, DiagramState& d, double rho, bool thin_rims,
            const std::vector<std::uint8_t>& flags, DecimationLevels& levels,
            const ProgressCallback& progress, std::string* message)
{
  const std::size_t n = d.representative.size();
  const unsigned threads = voronoi.getNumberOfThreads();
  const double sin_theta = std::sin(voronoi.getCoconeAngle());
  levels.level.assign(n, std::numeric_limits<double>::infinity());
  levels.largest_ratio_bound = rho;

  // Beyond the paper (thin_rims): r_p stands for how far the surface that p represents
  // reaches, but at a rim the cocone runs on past the last samples, where there is no
  // surface, so DECIMATE as published keeps nearly every rim sample: on the 10k monkey
  // saddle at rho 0.4, 252 of the 270 in the outermost row (and 381 in all). A rim
  // sample (BOUNDARY's flag, a gap wider than kRimGapAngle between its cocone links,
  // links near one plane) is instead measured on its cell cut by the plane through it
  // across the gap, in a cocone around the plane of its links, since its pole vector
  // may run out through the gap. The cut and the plane are fixed, like h_p and v_p.
  // That cocone is half as wide (theta / 2): the cut cell is still unbounded towards
  // the convex hull's normals, which a full-width cocone reaches on a curved rim (73
  // of the 270 rim samples of that saddle at theta, 1 at theta / 2).
  // Per sample: the plane fitted to a rim sample's links and the way out through its
  // gap; a zero outward vector for every other sample.
  struct RimFrame
  {
    Eigen::Vector3d axis, outward;
  };
  std::vector<RimFrame> rims;
  if (thin_rims) {
    if (std::find(flags.begin(), flags.end(), 1) != flags.end()) {
      rims.assign(n, {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
      runInArena(threads, [&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& range) {
              std::vector<SampleIndex> links;
              std::vector<double> scratch;
              for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (!flags[i] || d.representative[i] != i)
                  continue;
                const TangentGap gap =
                    widestTangentGap(voronoi, static_cast<SampleIndex>(i),
                                     TangentPlane::fitted, links, scratch);
                if (gap.angle > kRimGapAngle && gap.angle < 2 * M_PI &&
                    gap.thickness < kRimThickness)
                  rims[i] = {gap.normal, gap.direction};
              }
            });
      });
    }
  }
  // The cocone a sample is measured in: around its pole vector at theta, or for a rim
  // sample around its fitted plane at theta / 2, cut across its gap.
  struct CoconeFrame
  {
    const Eigen::Vector3d& axis;
    double sin_theta;
    const Eigen::Vector3d* cut;
  };
  const double rim_sin_theta = std::sin(voronoi.getCoconeAngle() / 2);
  const auto frame_of = [&](SampleIndex s) -> CoconeFrame {
    if (!rims.empty() && !rims[s].outward.isZero())
      return {rims[s].axis, rim_sin_theta, &rims[s].outward};
    return {d.pole_vector[s], sin_theta, nullptr};
  };
  // The positions of the samples in \a list relative to s, for the clipper.
  const auto offsets_from = [&](SampleIndex s, const std::vector<SampleIndex>& list,
                                std::vector<Eigen::Vector3d>& offsets) {
    offsets.clear();
    for (const SampleIndex q : list)
      offsets.push_back(d.centered[q] - d.centered[s]);
  };
  // r_p / h_p from a measurement bounded by limit = rho h_p: infinite when the cocone
  // reaches the limit (the sample stays at rho), or when there is no limit.
  const auto ratio_of = [&](SampleIndex s, const CoconeCellClipper::Result& measured,
                            double limit) {
    return measured.reached_limit || !(measured.radius < limit)
               ? std::numeric_limits<double>::infinity()
               : measured.radius / d.height[s];
  };

  std::vector<std::uint8_t> alive(n, 0), tracked(n, 0), dirty(n, 0);
  std::vector<std::uint32_t> version(n, 0);
  std::vector<SampleIndex> candidates;
  std::vector<double> start_ratio(n, std::numeric_limits<double>::infinity());
  std::size_t alive_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (d.representative[i] != i) {
      levels.level[i] = 0; // an exact duplicate never adds anything
      continue;
    }
    alive[i] = 1;
    ++alive_count;
    start_ratio[i] = d.ratio(static_cast<SampleIndex>(i));
    if (start_ratio[i] < rho || frame_of(static_cast<SampleIndex>(i)).cut)
      candidates.push_back(static_cast<SampleIndex>(i));
  }

  std::vector<std::vector<SampleIndex>> adjacency(n);
  {
    runInArena(threads, [&] {
      // Delaunay neighbours of the candidates: only their lists are ever read. A rim
      // sample is measured on its cut cell here.
      tbb::enumerable_thread_specific<SampleMarks> marks;
      tbb::enumerable_thread_specific<CoconeCellClipper> clippers;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          SampleMarks& seen = marks.local();
                          std::vector<Eigen::Vector3d> offsets;
                          for (std::size_t k = range.begin(); k != range.end(); ++k) {
                            const SampleIndex s = candidates[k];
                            std::vector<SampleIndex>& list = adjacency[s];
                            d.stars.appendNeighbours(s, seen, list);
                            // The stars' cell order follows the triangulation's thread
                            // schedule: sorted, the clipping rounds the same every run.
                            std::sort(list.begin(), list.end());
                            compact(list, s, alive);
                            const CoconeFrame frame = frame_of(s);
                            if (!frame.cut)
                              continue;
                            offsets_from(s, list, offsets);
                            const double limit = rho * d.height[s];
                            start_ratio[s] =
                                ratio_of(s,
                                         clippers.local().coconeRadius(
                                             frame.axis, frame.sin_theta, limit, 1,
                                             offsets, nullptr, frame.cut),
                                         limit);
                          }
                        });
    });
  }
  double smallest = std::numeric_limits<double>::infinity();
  for (const SampleIndex s : candidates) {
    if (start_ratio[s] < rho) {
      tracked[s] = 1;
      smallest = std::min(smallest, start_ratio[s]);
    }
    else {
      adjacency[s].clear();
      adjacency[s].shrink_to_fit();
    }
  }

  // The triangulation changes from here on: nothing derived from it applies any more,
  // however the run ends (a cancelled or failed run leaves no usable diagram either).
  d.status = Status::not_computed;
  d.stars.clear();
  d.triangles.clear();
  d.triangles.shrink_to_fit();
  d.triangle_offsets.clear();
  d.triangle_ids.clear();

  std::priority_queue<QueueEntry> queue;
  for (const SampleIndex s : candidates)
    if (tracked[s])
      queue.push({start_ratio[s], s, 0});

  CoconeCellClipper clipper;
  std::vector<Eigen::Vector3d> offsets;
  std::vector<int> kept;
  // After each measurement a list keeps the samples bounding the cell in a box twice
  // the size the radius needs, so that merged lists still cover a neighbour's grown
  // cell; a list that grows past kListLimit anyway is cut to the exact Delaunay
  // neighbours (whole cell). Measured on a 20k torus: 834 samples kept against 835 for
  // exact lists, in a tenth of the time.
  constexpr double kListMargin = 2;
  constexpr std::size_t kListLimit = 128;
  // "Infinity" for unbounded cells: far beyond the data.
  double extent = 0;
  for (const Eigen::Vector3d& p : d.centered)
    extent = std::max(extent, p.cwiseAbs().maxCoeff());
  extent = 1e3 * std::max(extent, 1e-300);
  double running_max = 0;
  std::size_t removals = 0;
  {
    while (!queue.empty()) {
      const QueueEntry top = queue.top();
      queue.pop();
      const SampleIndex s = top.sample;
      if (top.version != version[s] || !alive[s] || !tracked[s])
        continue; // stale entry
      if (top.ratio >= rho)
        break;
      if (alive_count <= 4)
        break;

      if (dirty[s]) {
        // Its cell grew since the key was computed: measure again, queue again.
        std::vector<SampleIndex>& list = adjacency[s];
        compact(list, s, alive);
        offsets_from(s, list, offsets);
        const double limit = rho * d.height[s];
        const CoconeFrame frame = frame_of(s);
        CoconeCellClipper::Result measured;
        if (list.size() > kListLimit) // rare: prune to the exact Delaunay neighbours
          measured = clipper.fullCell(frame.axis, frame.sin_theta, extent, offsets,
                                      kept, frame.cut);
        else
          measured = clipper.coconeRadius(frame.axis, frame.sin_theta, limit,
                                          kListMargin, offsets, &kept, frame.cut);
        std::sort(kept.begin(), kept.end());
        for (std::size_t k = 0; k < kept.size(); ++k)
          list[k] = list[kept[k]];
        list.resize(kept.size());
        dirty[s] = 0;
        ++version[s];
        const double ratio = ratio_of(s, measured, limit);
        if (ratio < rho) {
          queue.push({ratio, s, version[s]});
        }
        else {
          tracked[s] = 0; // ratios only grow: it stays from now on
          adjacency[s].clear();
          adjacency[s].shrink_to_fit();
        }
        continue;
      }

      // A removal only enlarges the neighbours' cells, so ratios rarely decrease; the
      // running maximum makes "kept at rho" exactly the result of a run stopped at rho.
      running_max = std::max(running_max, top.ratio);
      levels.level[s] = running_max;
      alive[s] = 0;
      --alive_count;
      tracked[s] = 0;
      ++removals;
      std::vector<SampleIndex> removed_list = std::move(adjacency[s]);
      adjacency[s] = std::vector<SampleIndex>();
      for (const SampleIndex q : removed_list) {
        if (!alive[q] || !tracked[q])
          continue;
        std::vector<SampleIndex>& list = adjacency[q];
        list.insert(list.end(), removed_list.begin(), removed_list.end());
        if (list.size() > 1024)
          compact(list, q, alive);
        dirty[q] = 1;
      }

      if (progress && (removals & 1023u) == 0 && std::isfinite(smallest) &&
          rho > smallest) {
        if (!progress(std::min(1.0, (running_max - smallest) / (rho - smallest)))) {
          detail::setMessage(message, "cancelled");
          levels.removals = removals;
          return Status::internal_error;
        }
      }
    }
  }
  levels.removals = removals;
  if (progress && !progress(1.0)) {
    detail::setMessage(message, "cancelled");
    return Status::internal_error;
  }
  return Status::ok;
}

/** The relaxation after DECIMATE at \a rho; the levels follow its output. */
Status
relaxLevels(const VoronoiCocone& voronoi, const std::vector<std::uint8_t>& fixed,
            unsigned iterations, double rho, DecimationLevels& levels,
            std::string* message)
{
  const std::size_t n = voronoi.size();
  std::vector<std::uint8_t> kept(n, 0);
  for (std::size_t s = 0; s < n; ++s)
    kept[s] = levels.level[s] >= rho;
  const Status status =
      relaxDecimatedSample(voronoi, fixed, iterations, voronoi.getNumberOfThreads(),
                           kept, levels.relaxation_moves, message);
  if (status != Status::ok)
    return status;
  // The levels stay true to the output: a sample moved to is kept at rho, one moved
  // from is removed just below it. Both stay kept at every smaller rho, so the sets
  // still nest (the smaller ones are DECIMATE's own).
  for (std::size_t s = 0; s < n; ++s) {
    if (kept[s] && !(levels.level[s] >= rho))
      levels.level[s] = rho;
    else if (!kept[s] && levels.level[s] >= rho)
      levels.level[s] = std::nextafter(rho, 0.0);
  }
  return Status::ok;
}

} // namespace

Status
decimate(VoronoiCocone&& voronoi, const DecimationParameters& parameters,
         const std::vector<std::uint8_t>& boundary, DecimationLevels& levels,
         const ProgressCallback& progress, std::string* message)
{
  levels = DecimationLevels();
  DiagramState& d = detail::VoronoiCoconeAccess::state(voronoi);
  if (d.status != Status::ok) {
    detail::setMessage(message, "decimation needs a diagram: compute() did not succeed "
                                "(or an earlier decimation consumed it)");
    return Status::not_computed;
  }
  if (!isValid(parameters)) {
    detail::setMessage(message, "a parameter of the decimation is outside its range");
    return Status::invalid_parameter;
  }
  const bool relaxing = parameters.relaxation_iterations > 0;
  if ((parameters.thin_rims || relaxing) && boundary.size() != voronoi.size()) {
    detail::setMessage(message,
                       "the decimation needs BOUNDARY's flag of every sample: " +
                           std::to_string(boundary.size()) + " flags for " +
                           std::to_string(voronoi.size()) + " samples");
    return Status::invalid_parameter;
  }
  // The relaxation takes about a tenth of a run when it runs.
  const ProgressCallback removing = progressPart(progress, 0, relaxing ? 0.9 : 1);
  Status status = detail::runGuarded("decimation", message, [&] {
    return runDecimate(voronoi, d, parameters.ratio_bound, parameters.thin_rims,
                       boundary, levels, removing, message);
  });
  if (status == Status::ok && relaxing) {
    status = relaxLevels(voronoi, boundary, parameters.relaxation_iterations,
                         parameters.ratio_bound, levels, message);
    if (status == Status::ok && progress && !progress(1)) {
      detail::setMessage(message, "cancelled");
      status = Status::internal_error;
    }
  }
  // Consumed, however the run ended: nothing of the diagram applies any more.
  d = DiagramState();
  return status;
}

} // namespace cocone
} // namespace pcl
