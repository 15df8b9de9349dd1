// SPDX-License-Identifier: GPL-3.0-or-later
// triangulateTile (tiled_delaunay.h): a tile's triangulation with a halo grown until
// its samples' stars are exact.
#include "voronoi/tiled_delaunay.h"

#include "common/status_guard.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <CGAL/Interval_nt.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/constructions/kernel_ftC3.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

// Leaves a tile may test for conflicts, counted once per cell that reaches them, per
// sample its budget allows, before it gives up. Each costs up to a leaf's samples in
// exact tests.
constexpr std::size_t kLeafTestsPerSample = 16;

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
    local_[l] = kPending;
    pending_.push_back(l);
    const KdTiling::Node& leaf = tiling_.leaf(l);
    pending_count_ += leaf.last - leaf.first;
  }
  /** Whether leaf \a l was added, in this round or before. */
  bool
  isLocal(std::uint32_t l) const
  {
    return local_[l] != 0;
  }
  /** Whether leaf \a l was inserted in an earlier round. */
  bool
  isInserted(std::uint32_t l) const
  {
    return local_[l] == kInserted;
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
      local_[l] = kInserted;
      const KdTiling::Node& leaf = tiling_.leaf(l);
      samples.insert(samples.end(), tiling_.order().begin() + leaf.first,
                     tiling_.order().begin() + leaf.last);
    }
    pending_.clear();
    pending_count_ = 0;
    return samples;
  }

private:
  static constexpr char kPending = 1, kInserted = 2;
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

/** A bound on a finite cell's circumball: the box of its interval circumcenter, and a
 * radius no smaller than the true one from any point of that box. */
struct IntervalBall
{
  Eigen::AlignedBox3d center;
  double reach = std::numeric_limits<double>::infinity();

  bool
  bounded() const
  {
    return std::isfinite(reach) && center.min().allFinite() && center.max().allFinite();
  }
  /** Every point the ball may hold lies in this box. */
  Eigen::AlignedBox3d
  hull() const
  {
    return Eigen::AlignedBox3d(center.min().array() - reach,
                               center.max().array() + reach);
  }
  /** Whether \a box may hold a point of the ball. */
  bool
  mayReach(const Eigen::AlignedBox3d& box) const
  {
    if (!bounded())
      return true;
    const Eigen::Vector3d gap = (box.min() - center.max())
                                    .cwiseMax(center.min() - box.max())
                                    .cwiseMax(Eigen::Vector3d::Zero());
    return gap.squaredNorm() <= reach * reach;
  }
};

IntervalBall
circumballBound(CellHandle c)
{
  // Upward rounding for the whole construction rather than for each operation (the
  // protected intervals switch the rounding mode twice an operation, which made this
  // the hot spot of the halo search); restored when the function returns, before any
  // filtered predicate runs again.
  CGAL::Protect_FPU_rounding<true> upward;
  using IntervalKernel = CGAL::Simple_cartesian<CGAL::Interval_nt<false>>;
  std::array<IntervalKernel::Point_3, 4> q;
  for (int j = 0; j < 4; ++j) {
    const Point& p = c->vertex(j)->point();
    q[j] = IntervalKernel::Point_3(p.x(), p.y(), p.z());
  }
  // CGAL's formula, in intervals; a denominator that may be 0 leaves the box
  // unbounded (every leaf is tested).
  using Interval = CGAL::Interval_nt<false>;
  Interval num_x, num_y, num_z, den;
  CGAL::determinants_for_circumcenterC3(
      q[0].x(), q[0].y(), q[0].z(), q[1].x(), q[1].y(), q[1].z(), q[2].x(), q[2].y(),
      q[2].z(), q[3].x(), q[3].y(), q[3].z(), num_x, num_y, num_z, den);
  if (den.inf() <= 0 && den.sup() >= 0)
    return IntervalBall();
  const Interval inv = Interval(1) / (Interval(2) * den);
  const IntervalKernel::Point_3 o(q[0].x() + num_x * inv, q[0].y() - num_y * inv,
                                  q[0].z() + num_z * inv);
  IntervalBall ball;
  ball.center =
      Eigen::AlignedBox3d(Eigen::Vector3d(o.x().inf(), o.y().inf(), o.z().inf()),
                          Eigen::Vector3d(o.x().sup(), o.y().sup(), o.z().sup()));
  if (!ball.center.min().allFinite() || !ball.center.max().allFinite())
    return ball;
  // The farthest corner of the center's box from a vertex bounds the radius; the
  // relative 1e-12 covers the rounding of these few operations.
  const Point& v = c->vertex(0)->point();
  const Eigen::Vector3d vertex(v.x(), v.y(), v.z());
  const Eigen::Vector3d far = (ball.center.min() - vertex)
                                  .cwiseAbs()
                                  .cwiseMax((ball.center.max() - vertex).cwiseAbs());
  ball.reach = far.norm() * (1 + 1e-12);
  return ball;
}

} // namespace

TileTriangulationStats
triangulateTile(const KdTiling& tiling, unsigned tile,
                const std::vector<Eigen::Vector3d>& points,
                const std::vector<std::uint32_t>& tile_of, unsigned halo_factor,
                Delaunay& dt, const std::function<void(std::size_t)>& on_inserted,
                const std::function<bool()>& give_up)
{
  TileTriangulationStats stats;
  LocalLeaves leaves(tiling);
  for (std::uint32_t l = tiling.firstLeaf(tile); l < tiling.firstLeaf(tile + 1); ++l)
    leaves.add(l);
  stats.owned = leaves.pendingCount();
  // One tile holds every sample: no halo, and a budget it cannot exceed.
  const std::size_t budget =
      tiling.numTiles() == 1 ? tiling.order().size() : halo_factor * stats.owned + 2048;

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

  // Lengths below this are rounding, for the cloud's coordinates.
  const double floor_length = 1e-12 * tiling.box().diagonal().norm();
  const VertexHandle infinite = dt.infinite_vertex();
  const auto owned = [&](VertexHandle v) {
    return v != infinite && tile_of[v->info()] == tile;
  };
  // A leaf joins the halo when one of its samples conflicts with cell c (lies inside
  // its circumball, with CGAL's exact predicate and symbolic perturbation, the ones
  // that built the triangulation): the box tests only choose the leaves to test.
  // The leaves tested are counted, once per cell that reaches them: where the balls
  // are huge and touch much of the cloud (a sphere), the tests alone would cost more
  // than one whole triangulation. A leaf already brought into the halo in this round
  // is not tested again but still counted: the cells come out of the concurrent
  // triangulation in an order set by the thread schedule, and the count, and with it
  // whether the tile gives up, must not depend on it.
  std::size_t leaf_tests = 0;
  const auto add_if_in_conflict = [&](std::uint32_t l, CellHandle c) {
    if (leaves.isInserted(l))
      return;
    ++leaf_tests;
    if (leaves.isLocal(l))
      return;
    const KdTiling::Node& leaf = tiling.leaf(l);
    for (std::uint32_t i = leaf.first; i < leaf.last; ++i) {
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
        leaf_tests > kLeafTestsPerSample * budget || (give_up && give_up()))
      return stats;
    const std::vector<SampleIndex> fresh = leaves.takePending();
    stats.local += fresh.size();
    ++stats.rounds;
    insertSamples(dt, points, fresh, on_inserted);
    if (tiling.numTiles() == 1) {
      // Every sample is local: every star is final. Centering the points rounds
      // them, which can flatten a cloud that compute() found 3D.
      if (dt.dimension() < 3)
        throw StageFailure{Status::degenerate_dimension,
                           "all points are coplanar once centered: no 3D Voronoi cell "
                           "to measure"};
      break;
    }

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
        throw StageFailure{Status::degenerate_dimension,
                           "all points are coplanar once centered: no 3D Voronoi cell "
                           "to measure"};
      continue;
    }

    // Every cell at an own sample: may a sample outside tile and halo conflict with
    // it? If so, the leaves that may hold one join the halo.
    const std::size_t test_limit = kLeafTestsPerSample * budget;
    std::size_t cells_seen = 0;
    for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
      // Give up as soon as the budget is spent, not at the end of the round: a round
      // on a tile whose cells reach across the cloud costs more than the whole cloud.
      if (stats.local + leaves.pendingCount() > budget || leaf_tests > test_limit ||
          (give_up && (++cells_seen & 0xfffu) == 0 && give_up()))
        return stats;
      bool at_own_sample = false;
      for (int j = 0; j < 4 && !at_own_sample; ++j)
        at_own_sample = owned(c->vertex(j));
      if (!at_own_sample)
        continue;
      const int at_infinity = c->has_vertex(infinite) ? c->index(infinite) : -1;
      if (at_infinity < 0) {
        // The circumcenter in interval arithmetic: its box holds the true center
        // however flat the cell, and a sample may lie in the circumball only within
        // `reach` of that box. A cell too flat for intervals has an unbounded box,
        // and every leaf is tested.
        const IntervalBall ball = circumballBound(c);
        if (ball.bounded() && safe_box.contains(ball.hull()))
          continue;
        tiling.visitLeaves(
            [&](const Eigen::AlignedBox3d& b) { return ball.mayReach(b); },
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
      const Point& opposite = inside->vertex(inside->index(c))->point();
      Eigen::Vector3d normal = (b - a).cross(d - a);
      // Which side is beyond, exactly: the normal points away from the hull's inside.
      if (CGAL::orientation(c->vertex((at_infinity + 1) & 3)->point(),
                            c->vertex((at_infinity + 2) & 3)->point(),
                            c->vertex((at_infinity + 3) & 3)->point(),
                            opposite) == CGAL::POSITIVE)
        normal = -normal;
      const double length = normal.norm();
      if (!(length > 1e-8 * (b - a).norm() * (d - a).norm())) {
        // A needle facet: its normal's direction is not known well enough to cut
        // leaves away. Every leaf is tested.
        tiling.visitLeaves([](const Eigen::AlignedBox3d&) { return true; },
                           [&](std::uint32_t l) { add_if_in_conflict(l, c); });
        continue;
      }
      normal /= length;
      tiling.visitLeaves(
          [&](const Eigen::AlignedBox3d& box) {
            // The box's corner farthest along the normal. The normal's direction is
            // off by at most 1e-8 radians: a slack growing with the distance.
            const Eigen::Vector3d corner(normal.x() > 0 ? box.max().x() : box.min().x(),
                                         normal.y() > 0 ? box.max().y() : box.min().y(),
                                         normal.z() > 0 ? box.max().z()
                                                        : box.min().z());
            const Eigen::Vector3d offset = corner - a;
            return offset.dot(normal) >= -(1e-7 * offset.norm() + floor_length);
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
