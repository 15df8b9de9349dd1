// SPDX-License-Identifier: GPL-3.0-or-later
// triangulateTile (tiled_delaunay.h): a tile's triangulation with a halo grown until
// its samples' stars are exact.
#include "voronoi/tiled_delaunay.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

// Conflict tests a tile may spend, per sample its budget allows, before it gives up.
constexpr std::size_t kTestsPerSample = 32;

/** The leaves a tile triangulates, and those still to insert. */
class LocalLeaves
{
public:
  LocalLeaves(const KdTiling& tiling) : tiling_(tiling), local_(tiling.numLeaves(), 0)
  {}

  /** Adds leaf \a l unless it is local already. */
  void
  add(std::uint32_t l)
  {
    if (local_[l])
      return;
    local_[l] = 1;
    pending_.push_back(l);
    const KdTiling::Node& leaf = tiling_.leaf(l);
    pending_count_ += leaf.last - leaf.first;
  }
  bool
  isLocal(std::uint32_t l) const
  {
    return local_[l] != 0;
  }
  std::size_t
  pendingCount() const
  {
    return pending_count_;
  }
  /** The samples of the leaves added since the last call, which become local. */
  std::vector<SampleIndex>
  takePending()
  {
    std::vector<SampleIndex> samples;
    samples.reserve(pending_count_);
    // Leaf order, not the order they were found in: the insertion order is then a
    // function of the set alone (the triangulation is anyway; this keeps runs alike).
    std::sort(pending_.begin(), pending_.end());
    for (const std::uint32_t l : pending_) {
      const KdTiling::Node& leaf = tiling_.leaf(l);
      samples.insert(samples.end(), tiling_.order().begin() + leaf.first,
                     tiling_.order().begin() + leaf.last);
    }
    pending_.clear();
    pending_count_ = 0;
    return samples;
  }

private:
  const KdTiling& tiling_;
  std::vector<char> local_;
  std::vector<std::uint32_t> pending_;
  std::size_t pending_count_ = 0;
};

/** Inserts \a samples into \a dt, each vertex carrying its sample index, in CGAL's
 * spatial order, on every core: a thread locks the vertex it starts its search from and
 * the point's place, CGAL's insertion locks the cells it replaces, and when any lock
 * is taken the thread lets go and tries again. The first samples go in one by one,
 * until the triangulation spans 3D. \a on_inserted hears, on the calling thread,
 * of every 65536 insertions made there and of the rest at the end. */
void
insertSamples(Delaunay& dt, const std::vector<Eigen::Vector3d>& points,
              const std::vector<SampleIndex>& samples,
              const std::function<void(std::size_t)>& on_inserted)
{
  std::vector<Point> input(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Eigen::Vector3d& p = points[samples[i]];
    input[i] = Point(p.x(), p.y(), p.z());
  }
  std::vector<std::size_t> order(samples.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  using SortTraits =
      CGAL::Spatial_sort_traits_adapter_3<Kernel,
                                          CGAL::Pointer_property_map<Point>::type>;
  CGAL::spatial_sort<CGAL::Parallel_if_available_tag>(
      order.begin(), order.end(), SortTraits(CGAL::make_property_map(input)));

  std::size_t next = 0;
  VertexHandle hint;
  while (next < order.size() &&
         (next < 100 || dt.dimension() < 3 || !dt.is_parallel())) {
    hint = dt.insert(input[order[next]], hint);
    hint->info() = samples[order[next]];
    ++next;
    if ((next & 0xffffu) == 0 && on_inserted)
      on_inserted(0x10000);
  }
  if (on_inserted)
    on_inserted(next & 0xffffu);
  if (next == order.size())
    return;

  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::size_t> unreported{0};
  tbb::enumerable_thread_specific<VertexHandle> hints(hint);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(next, order.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      VertexHandle& start = hints.local();
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const Point& p = input[order[k]];
                        while (true) {
                          bool zone_locked = false;
                          if (dt.try_lock_vertex(start) && dt.try_lock_point(p)) {
                            const VertexHandle v = dt.insert(p, start, &zone_locked);
                            dt.unlock_all_elements();
                            if (zone_locked) {
                              v->info() = samples[order[k]];
                              start = v;
                              break;
                            }
                          }
                          else {
                            dt.unlock_all_elements();
                          }
                        }
                      }
                      const std::size_t done = unreported += range.size();
                      if (on_inserted && done >= 0x10000 &&
                          std::this_thread::get_id() == caller)
                        on_inserted(unreported.exchange(0));
                    });
  if (on_inserted)
    on_inserted(unreported.exchange(0));
}

} // namespace

TileTriangulationStats
triangulateTile(const KdTiling& tiling, unsigned tile,
                const std::vector<Eigen::Vector3d>& points,
                const std::vector<std::uint32_t>& tile_of, std::size_t budget,
                Delaunay& dt, const std::function<void(std::size_t)>& on_inserted,
                const std::function<bool()>& give_up)
{
  TileTriangulationStats stats;
  LocalLeaves leaves(tiling);
  for (std::uint32_t l = tiling.firstLeaf(tile); l < tiling.firstLeaf(tile + 1); ++l)
    leaves.add(l);
  stats.owned = leaves.pendingCount();

  // The first halo: every leaf within a margin of the tile's box. Any sample inside
  // the grown box is then local, which settles most cells without a search.
  const Eigen::AlignedBox3d& tile_box = tiling.tileBox(tile);
  std::vector<double> diagonals;
  for (std::uint32_t l = tiling.firstLeaf(tile); l < tiling.firstLeaf(tile + 1); ++l)
    diagonals.push_back(tiling.leaf(l).box.diagonal().norm());
  std::nth_element(diagonals.begin(), diagonals.begin() + diagonals.size() / 2,
                   diagonals.end());
  double margin = 2 * diagonals[diagonals.size() / 2];
  Eigen::AlignedBox3d safe_box(tile_box.min().array() - margin,
                               tile_box.max().array() + margin);
  const auto add_box = [&](const Eigen::AlignedBox3d& box) {
    tiling.visitLeaves([&](const Eigen::AlignedBox3d& b) { return b.intersects(box); },
                       [&](std::uint32_t l) { leaves.add(l); });
  };
  if (tiling.numTiles() > 1)
    add_box(safe_box);

  const double scale = std::max(1e-300, tile_box.diagonal().norm());
  const VertexHandle infinite = dt.infinite_vertex();
  const auto owned = [&](VertexHandle v) {
    return v != infinite && tile_of[v->info()] == tile;
  };
  // A leaf joins the halo when one of its samples conflicts with cell c (lies inside
  // its circumball, with CGAL's exact predicate and symbolic perturbation, the ones
  // that built the triangulation): the box tests only choose the leaves to test.
  // Each test is counted: where the balls are huge and touch much of the cloud (a
  // sphere), the tests alone would cost more than one whole triangulation.
  std::size_t tests = 0;
  const auto add_if_in_conflict = [&](std::uint32_t l, CellHandle c) {
    if (leaves.isLocal(l))
      return;
    const KdTiling::Node& leaf = tiling.leaf(l);
    for (std::uint32_t i = leaf.first; i < leaf.last; ++i) {
      ++tests;
      const Eigen::Vector3d& q = points[tiling.order()[i]];
      if (dt.side_of_sphere(c, Point(q.x(), q.y(), q.z()), true) ==
          CGAL::ON_BOUNDED_SIDE) {
        leaves.add(l);
        return;
      }
    }
  };
  while (true) {
    if (stats.local + leaves.pendingCount() > budget ||
        tests > kTestsPerSample * budget || (give_up && give_up()))
      return stats;
    const std::vector<SampleIndex> fresh = leaves.takePending();
    stats.local += fresh.size();
    ++stats.rounds;
    insertSamples(dt, points, fresh, on_inserted);
    if (tiling.numTiles() == 1)
      break; // every sample is local: every star is final

    if (dt.dimension() < 3) {
      // The local samples are flat: widen the halo until they are not (the whole
      // cloud is not flat, compute() checked).
      const double floor = 1e-6 * tiling.box().diagonal().norm();
      do {
        margin = std::max(2 * margin, floor);
        safe_box = Eigen::AlignedBox3d(tile_box.min().array() - margin,
                                       tile_box.max().array() + margin);
        add_box(safe_box);
      } while (leaves.pendingCount() == 0 && !safe_box.contains(tiling.box()));
      if (leaves.pendingCount() == 0)
        throw std::logic_error("a tile of a 3D cloud stays flat with every leaf local");
      continue;
    }

    // Every cell at an own sample: may a sample outside tile and halo conflict with
    // it? If so, the leaves that may hold one join the halo.
    const std::size_t test_limit = kTestsPerSample * budget;
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
      // Give up as soon as the budget is spent, not at the end of the round: a round
      // on a tile whose cells reach across the cloud costs more than the whole cloud.
      if (stats.local + leaves.pendingCount() > budget || tests > test_limit)
        return stats;
      bool at_own_sample = false;
      for (int j = 0; j < 4 && !at_own_sample; ++j)
        at_own_sample = owned(c->vertex(j));
      if (!at_own_sample)
        continue;
      const int at_infinity = c->has_vertex(infinite) ? c->index(infinite) : -1;
      if (at_infinity < 0) {
        const Point center =
            CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                               c->vertex(2)->point(), c->vertex(3)->point());
        const Eigen::Vector3d o = toEigen(center);
        const double radius = (o - toEigen(c->vertex(0)->point())).norm();
        const double reach = radius * (1 + 1e-6) + 1e-12 * scale;
        if (std::isfinite(reach) && safe_box.contains(Eigen::AlignedBox3d(
                                        o.array() - reach, o.array() + reach)))
          continue;
        tiling.visitLeaves(
            [&](const Eigen::AlignedBox3d& b) {
              return !std::isfinite(reach) ||
                     b.squaredExteriorDistance(o) <= reach * reach;
            },
            [&](std::uint32_t l) { add_if_in_conflict(l, c); });
        continue;
      }
      // A hull facet: a sample conflicts with the cell when it lies beyond the facet's
      // plane (or on it, within the facet's circle): leaves that meet the closed
      // half-space, widened, are tested.
      const Eigen::Vector3d a = toEigen(c->vertex((at_infinity + 1) & 3)->point());
      const Eigen::Vector3d b = toEigen(c->vertex((at_infinity + 2) & 3)->point());
      const Eigen::Vector3d d = toEigen(c->vertex((at_infinity + 3) & 3)->point());
      const CellHandle inside = c->neighbor(at_infinity);
      const Eigen::Vector3d opposite =
          toEigen(inside->vertex(inside->index(c))->point());
      Eigen::Vector3d normal = (b - a).cross(d - a);
      if (normal.dot(opposite - a) > 0)
        normal = -normal;
      const double length = normal.norm();
      if (!(length > 0)) {
        // A facet too thin to have a normal: which side is beyond cannot be told.
        tiling.visitLeaves([](const Eigen::AlignedBox3d&) { return true; },
                           [&](std::uint32_t l) { add_if_in_conflict(l, c); });
        continue;
      }
      normal /= length;
      const double slack = 1e-6 * scale;
      tiling.visitLeaves(
          [&](const Eigen::AlignedBox3d& box) {
            // The box's corner farthest along the normal.
            const Eigen::Vector3d corner(normal.x() > 0 ? box.max().x() : box.min().x(),
                                         normal.y() > 0 ? box.max().y() : box.min().y(),
                                         normal.z() > 0 ? box.max().z()
                                                        : box.min().z());
            return (corner - a).dot(normal) >= -slack;
          },
          [&](std::uint32_t l) { add_if_in_conflict(l, c); });
    }
    if (leaves.pendingCount() == 0)
      break;
  }
  stats.complete = true;
  return stats;
}

} // namespace detail
} // namespace cocone
} // namespace pcl
