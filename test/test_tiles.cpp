// SPDX-License-Identifier: GPL-3.0-or-later
// Tiles with exact seams (issue 24): the diagram built in 1, 2, 7 or 64 tiles, with any
// thread count, is the same diagram bit for bit (poles, heights, radii, marked
// triangles, Delaunay neighbours), and the reconstruction from it the same mesh; on
// generated shapes, sampled at random and on grids full of cospherical points, and on
// the shared scans.
#include "support/data_paths.h"
#include "support/noise.h"
#include "support/shapes.h"

#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/tile_exchange.h>
#include <pcl/cocone/core/voronoi_cocone.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

using pcl::cocone::MarkedTriangle;
using pcl::cocone::ReconstructionParameters;
using pcl::cocone::ReconstructionReport;
using pcl::cocone::SampleIndex;
using pcl::cocone::Status;
using pcl::cocone::TriangleIndices;
using pcl::cocone::VoronoiCocone;
using pcl::cocone::VoronoiParameters;
using pcl::cocone::test::Shape;
namespace shapes = pcl::cocone::test;

/** Whether two doubles are the same bits (NaN equals NaN, infinity infinity). */
bool
sameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool
sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

VoronoiCocone
diagram(const std::vector<Eigen::Vector3d>& points, unsigned tiles, unsigned threads)
{
  VoronoiParameters parameters;
  parameters.tiles = tiles;
  parameters.threads = threads;
  VoronoiCocone voronoi(parameters);
  EXPECT_EQ(voronoi.compute(points), Status::ok) << voronoi.errorMessage();
  return voronoi;
}

/** Every per-sample value, every marked triangle and every Delaunay neighbourhood of
 * \a tiled equals that of \a whole; counts the first differences. */
void
expectSameDiagram(const VoronoiCocone& whole, const VoronoiCocone& tiled,
                  const std::string& label)
{
  SCOPED_TRACE(label);
  ASSERT_EQ(whole.size(), tiled.size());
  ASSERT_EQ(whole.numUniqueSamples(), tiled.numUniqueSamples());
  std::size_t differences = 0;
  std::vector<SampleIndex> a, b;
  for (SampleIndex s = 0; s < whole.size(); ++s) {
    const bool same =
        whole.representative(s) == tiled.representative(s) &&
        sameBits(whole.poleVector(s), tiled.poleVector(s)) &&
        sameBits(whole.height(s), tiled.height(s)) &&
        sameBits(whole.coconeRadius(s), tiled.coconeRadius(s)) &&
        whole.positivePoleAtInfinity(s) == tiled.positivePoleAtInfinity(s) &&
        (whole.positivePoleAtInfinity(s) ||
         sameBits(whole.positivePole(s), tiled.positivePole(s)));
    whole.delaunayNeighbours(s, a);
    tiled.delaunayNeighbours(s, b);
    if ((!same || a != b) && ++differences <= 5)
      ADD_FAILURE() << "sample " << s << " differs (same geometry: " << same
                    << ", same neighbours: " << (a == b) << "): pole vector "
                    << whole.poleVector(s).transpose() << " / "
                    << tiled.poleVector(s).transpose() << ", height " << whole.height(s)
                    << " / " << tiled.height(s) << ", radius " << whole.coconeRadius(s)
                    << " / " << tiled.coconeRadius(s);
  }
  EXPECT_EQ(differences, 0u);
  const std::vector<MarkedTriangle>& t = whole.markedTriangles();
  const std::vector<MarkedTriangle>& u = tiled.markedTriangles();
  ASSERT_EQ(t.size(), u.size());
  std::size_t triangle_differences = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k].vertex != u[k].vertex || t[k].marked_by != u[k].marked_by)
      ++triangle_differences;
  EXPECT_EQ(triangle_differences, 0u);
}

std::vector<TriangleIndices>
mesh(const VoronoiCocone& voronoi)
{
  std::vector<TriangleIndices> triangles;
  ReconstructionReport report;
  std::string message;
  EXPECT_EQ(pcl::cocone::reconstructSurface(voronoi, ReconstructionParameters(),
                                            triangles, report, nullptr, &message),
            Status::ok)
      << message;
  for (TriangleIndices& t : triangles)
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

/** The diagram in 1 tile against \a tile_counts tiles, and the meshes from them. Tile
 * counts up to \a must_tile_up_to must really be tiled (no fallback to one tile); the
 * others may fall back, when a tile's halo outgrows its budget. */
void
expectTilingChangesNothing(const std::vector<Eigen::Vector3d>& points,
                           const std::string& label,
                           const std::vector<unsigned>& tile_counts,
                           unsigned must_tile_up_to)
{
  const VoronoiCocone whole = diagram(points, 1, 0);
  ASSERT_EQ(whole.timings().tiles, 1u);
  const std::vector<TriangleIndices> whole_mesh = mesh(whole);
  ASSERT_FALSE(whole_mesh.empty());
  for (const unsigned tiles : tile_counts)
    for (const unsigned threads : {1u, 2u}) {
      const std::string run = label + ", " + std::to_string(tiles) + " tiles, " +
                              std::to_string(threads) + " threads";
      const VoronoiCocone tiled = diagram(points, tiles, threads);
      std::cout << run << ": built in " << tiled.timings().tiles
                << " tiles, triangulated share " << tiled.timings().triangulated_share
                << "\n";
      if (tiles <= must_tile_up_to) {
        EXPECT_EQ(tiled.timings().tiles, tiles) << run << ": fell back to one tile";
        EXPECT_GT(tiled.timings().triangulated_share, 1.0) << run;
      }
      expectSameDiagram(whole, tiled, run);
      EXPECT_TRUE(mesh(tiled) == whole_mesh) << run << ": the meshes differ";
    }
}

TEST(Tiles, RandomSamplesOfClosedAndOpenShapes)
{
  // At 20k samples the halo of 2 tiles holds 0.7 to 1 times the tile's own samples
  // on the torus, cube, open cylinder and saddle; the hemisphere's cells reach down to
  // its centre, so it falls back to one tile, as do 7 and 64 tiles. Whether a tile
  // gives up does not depend on the thread schedule, so the first four must tile every
  // run. Either way the diagram must not change.
  for (const Shape shape : {Shape::torus, Shape::cube, Shape::open_cylinder,
                            Shape::monkey_saddle, Shape::hemisphere}) {
    const shapes::SampledShape sampled = shapes::sampleRandom(shape, 20000, 3);
    expectTilingChangesNothing(sampled.points, sampled.name, {2, 7, 64},
                               shape == Shape::hemisphere ? 0 : 2);
  }
}

TEST(Tiles, DensityThatVariesAcrossTheSurface)
{
  const shapes::SampledShape sampled =
      shapes::sampleRandom(Shape::genus3, 20000, 5, /*density_ramp=*/true);
  expectTilingChangesNothing(sampled.points, sampled.name + " ramp", {2, 7}, 0);
}

TEST(Tiles, CosphericalGridWithDuplicates)
{
  // A cube's surface sampled on a grid: every grid square is four cocircular points,
  // and with the square beside it six cospherical ones, so the triangulation is
  // decided by CGAL's symbolic perturbation; it must decide the same in every tile.
  // Some points repeated, to check duplicates keep their representative.
  std::vector<Eigen::Vector3d> points;
  const int m = 24;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j)
      for (int k = 0; k <= m; ++k)
        if (i == 0 || j == 0 || k == 0 || i == m || j == m || k == m)
          points.emplace_back(i, j, k);
  const std::size_t distinct = points.size();
  for (std::size_t i = 0; i < distinct; i += 37)
    points.push_back(points[i]);
  expectTilingChangesNothing(points, "grid cube", {2, 7, 64}, 0);
}

TEST(Tiles, SphereFallsBackToOneTileWithTheSameResult)
{
  // Every Voronoi cell of a sphere's samples reaches its centre: no halo short of the
  // whole sphere makes a star exact, so the build falls back to one tile, and says so.
  const shapes::SampledShape sphere = shapes::sampleRandom(Shape::sphere, 20000, 2);
  const VoronoiCocone tiled = diagram(sphere.points, 7, 0);
  EXPECT_EQ(tiled.timings().tiles, 1u);
  expectSameDiagram(diagram(sphere.points, 1, 0), tiled, "sphere");
}

TEST(Tiles, MoreTilesThanSamples)
{
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                               {0, 0, 1}, {1, 1, 1}, {0.5, 0.2, 0.7}};
  const VoronoiCocone whole = diagram(points, 1, 0);
  const VoronoiCocone tiled = diagram(points, 1000, 0);
  expectSameDiagram(whole, tiled, "6 points");
}

/** The rank and size every test exchange below reports. */
class FixedRankExchange : public pcl::cocone::TileExchange
{
public:
  FixedRankExchange(unsigned rank, unsigned size) : rank_(rank), size_(size) {}
  unsigned
  rank() const override
  {
    return rank_;
  }
  unsigned
  size() const override
  {
    return size_;
  }

protected:
  unsigned rank_, size_;
};

/** A TileExchange between threads of this process, standing for the processes of an
 * MPI run: each thread holds one with its rank, all share one mailbox. */
class ThreadExchange : public FixedRankExchange
{
public:
  struct Mailbox
  {
    std::mutex mutex;
    std::condition_variable arrived;
    std::vector<std::vector<std::uint8_t>> messages;
    unsigned received = 0;
  };

  ThreadExchange(unsigned rank, unsigned size, std::shared_ptr<Mailbox> mailbox)
    : FixedRankExchange(rank, size), mailbox_(std::move(mailbox))
  {}

  std::vector<std::vector<std::uint8_t>>
  gatherToRoot(const std::vector<std::uint8_t>& message) override
  {
    std::unique_lock<std::mutex> lock(mailbox_->mutex);
    if (rank_ != 0) {
      mailbox_->messages[rank_] = message;
      ++mailbox_->received;
      mailbox_->arrived.notify_all();
      return {};
    }
    mailbox_->arrived.wait(lock, [&] { return mailbox_->received + 1 == size_; });
    return mailbox_->messages;
  }

private:
  std::shared_ptr<Mailbox> mailbox_;
};

/** The diagram of \a points built by \a processes threads sharing \a tiles tiles
 * through a ThreadExchange: the root's diagram. Every other one must hand off. */
VoronoiCocone
sharedDiagram(const std::vector<Eigen::Vector3d>& points, unsigned tiles,
              unsigned processes)
{
  auto mailbox = std::make_shared<ThreadExchange::Mailbox>();
  mailbox->messages.resize(processes);
  const auto parameters = [&](unsigned rank) {
    VoronoiParameters p;
    p.tiles = tiles;
    p.threads = 1;
    p.exchange = std::make_shared<ThreadExchange>(rank, processes, mailbox);
    return p;
  };
  std::vector<Status> worker_status(processes, Status::ok);
  std::vector<std::thread> workers;
  for (unsigned r = 1; r < processes; ++r)
    workers.emplace_back([&, r] {
      VoronoiCocone worker(parameters(r));
      worker_status[r] = worker.compute(points);
    });
  VoronoiCocone root(parameters(0));
  EXPECT_EQ(root.compute(points), Status::ok) << root.errorMessage();
  for (std::thread& worker : workers)
    worker.join();
  for (unsigned r = 1; r < processes; ++r)
    EXPECT_EQ(worker_status[r], Status::not_computed) << "process " << r;
  return root;
}

TEST(Tiles, SharedByProcessesAsOneProcessBuildsIt)
{
  // Clean and noisy random samples (the noisy ones are smoothed by every process on
  // its own: the same smoothing everywhere), tiled and falling back to one tile.
  const shapes::SampledShape torus = shapes::sampleRandom(Shape::torus, 20000, 4);
  const shapes::SampledShape noisy =
      shapes::withGaussianNoise(shapes::sampleRandom(Shape::torus, 20000, 6), 0.3);
  for (const shapes::SampledShape* shape : {&torus, &noisy}) {
    const VoronoiCocone whole = diagram(shape->points, 1, 0);
    const std::vector<TriangleIndices> whole_mesh = mesh(whole);
    for (const unsigned processes : {2u, 3u}) {
      const std::string run =
          shape->name + ", " + std::to_string(processes) + " processes";
      const VoronoiCocone shared = sharedDiagram(shape->points, processes, processes);
      EXPECT_EQ(shared.timings().tiles, processes) << run << ": fell back";
      expectSameDiagram(whole, shared, run);
      EXPECT_TRUE(mesh(shared) == whole_mesh) << run << ": the meshes differ";
    }
    // 64 tiles outgrow their halos: the root builds one tile itself.
    const VoronoiCocone fallback = sharedDiagram(shape->points, 64, 3);
    EXPECT_EQ(fallback.timings().tiles, 1u);
    expectSameDiagram(whole, fallback, shape->name + ", 64 tiles on 3 processes");
  }
}

/** An exchange for process \a rank of \a size: a root handed \a messages instead of
 * the other processes', or another process whose message is kept in #sent. */
class ForgedExchange : public FixedRankExchange
{
public:
  ForgedExchange(unsigned rank, unsigned size,
                 std::vector<std::vector<std::uint8_t>> messages = {})
    : FixedRankExchange(rank, size), messages_(std::move(messages))
  {}
  std::vector<std::vector<std::uint8_t>>
  gatherToRoot(const std::vector<std::uint8_t>& message) override
  {
    ++calls;
    sent = message;
    return rank_ == 0 ? messages_ : std::vector<std::vector<std::uint8_t>>();
  }

  std::vector<std::uint8_t> sent;
  int calls = 0;

private:
  std::vector<std::vector<std::uint8_t>> messages_;
};

TEST(Tiles, BadMessagesFromOtherProcessesFailWithAReason)
{
  const shapes::SampledShape torus = shapes::sampleRandom(Shape::torus, 20000, 4);
  // The true message of process 1 of 2.
  auto worker = std::make_shared<ForgedExchange>(1, 2);
  VoronoiParameters p;
  p.tiles = 2;
  p.exchange = worker;
  EXPECT_EQ(VoronoiCocone(p).compute(torus.points), Status::not_computed);
  ASSERT_EQ(worker->calls, 1);
  const std::vector<std::uint8_t> good = worker->sent;
  ASSERT_GT(good.size(), 1000u);

  const auto root = [&](unsigned size, std::vector<std::vector<std::uint8_t>> messages,
                        Status expected_status, const std::string& expected) {
    VoronoiParameters q;
    q.tiles = 2;
    q.exchange = std::make_shared<ForgedExchange>(0, size, std::move(messages));
    VoronoiCocone diagram(q);
    EXPECT_EQ(diagram.compute(torus.points), expected_status) << expected;
    EXPECT_NE(diagram.errorMessage().find(expected), std::string::npos)
        << diagram.errorMessage();
    return diagram;
  };
  // The true message joins into the diagram of one process.
  expectSameDiagram(diagram(torus.points, 1, 0), root(2, {{}, good}, Status::ok, ""),
                    "2 processes");
  // Truncated, by one byte or to nothing.
  root(2, {{}, std::vector<std::uint8_t>(good.begin(), good.end() - 1)},
       Status::internal_error, "truncated");
  root(2, {{}, {}}, Status::internal_error, "truncated");
  // Another kind, another fingerprint (the points of another input).
  std::vector<std::uint8_t> forged = good;
  forged[0] = 7;
  root(2, {{}, forged}, Status::internal_error, "unknown kind 7");
  forged = good;
  forged[3] ^= 1;
  root(2, {{}, forged}, Status::internal_error, "was made from other points");
  // The root's own tile 0 instead of tile 1 (after kind, fingerprint and count).
  forged = good;
  std::fill(forged.begin() + 13, forged.begin() + 17, 0);
  root(2, {{}, forged}, Status::internal_error,
       "names tile 0 where tile 1 was dealt to process 1");
  // The same message from process 2 of 3, which was dealt no tile of 2.
  root(3, {{}, good, good}, Status::internal_error,
       "holds 1 tiles, not the 0 dealt to process 2");
  // A message missing altogether, and a process that failed.
  root(2, {{}}, Status::internal_error, "1 messages for 2 processes");
  root(2, {{}, {2, 'o', 'o', 'p', 's'}}, Status::internal_error,
       "process 1 failed: oops");

  // A process that fails before its tiles still calls the exchange once, with its
  // reason, so that the root does not wait for it.
  auto failing = std::make_shared<ForgedExchange>(1, 2);
  VoronoiParameters f;
  f.tiles = 2;
  f.exchange = failing;
  std::vector<Eigen::Vector3d> with_nan = torus.points;
  with_nan[5].x() = std::nan("");
  EXPECT_EQ(VoronoiCocone(f).compute(with_nan), Status::non_finite_input);
  EXPECT_EQ(failing->calls, 1);
  ASSERT_FALSE(failing->sent.empty());
  EXPECT_EQ(failing->sent[0], 2);
  EXPECT_NE(std::string(failing->sent.begin() + 1, failing->sent.end())
                .find("non-finite coordinate"),
            std::string::npos);
  // And a root that fails first still takes the messages.
  auto failing_root = std::make_shared<ForgedExchange>(
      0, 2, std::vector<std::vector<std::uint8_t>>{{}, good});
  f.exchange = failing_root;
  EXPECT_EQ(VoronoiCocone(f).compute(with_nan), Status::non_finite_input);
  EXPECT_EQ(failing_root->calls, 1);
  // Its message says it failed, so that an exchange need not wait for the others.
  ASSERT_FALSE(failing_root->sent.empty());
  EXPECT_EQ(failing_root->sent[0], 2);
  // And when the exchange then fails too, the root's own failure is the one reported.
  struct ThrowingExchange : FixedRankExchange
  {
    ThrowingExchange() : FixedRankExchange(0, 2) {}
    std::vector<std::vector<std::uint8_t>>
    gatherToRoot(const std::vector<std::uint8_t>&) override
    {
      throw std::runtime_error("the other job's file did not appear");
    }
  };
  f.exchange = std::make_shared<ThrowingExchange>();
  VoronoiCocone failing_twice(f);
  EXPECT_EQ(failing_twice.compute(with_nan), Status::non_finite_input);
  EXPECT_NE(failing_twice.errorMessage().find("non-finite"), std::string::npos)
      << failing_twice.errorMessage();
  // The same for a root that fails while it builds its tiles (here: cancelled).
  VoronoiCocone cancelled_root(f);
  EXPECT_EQ(cancelled_root.compute(torus.points, [](double) { return false; }),
            Status::internal_error);
  EXPECT_EQ(cancelled_root.errorMessage(), "cancelled");

  // A process with an invalid rank.
  VoronoiParameters lost_parameters;
  lost_parameters.exchange = std::make_shared<ForgedExchange>(3, 2);
  VoronoiCocone lost(lost_parameters);
  EXPECT_EQ(lost.compute(torus.points), Status::invalid_parameter);
}

TEST(Tiles, SharedScans)
{
  const std::vector<std::string> files = {"bun_zipper_35947.ply", "pcl_milk_13704.pcd",
                                          "fandisk_6475.obj",
                                          "pcl_lidar_terrain_samp11-utm_38010.pcd"};
  std::size_t found = 0;
  for (const std::string& file : files) {
    const std::string path = shapes::dataFile(file);
    if (path.empty())
      continue;
    ++found;
    const auto cloud = shapes::loadCloud(path);
    std::vector<Eigen::Vector3d> points;
    for (const auto& p : cloud->points)
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
        points.emplace_back(p.x, p.y, p.z);
    expectTilingChangesNothing(points, file, {2, 7, 64}, 0);
  }
  if (found == 0)
    GTEST_SKIP() << "no shared scan in " << shapes::dataDirectory();
}

} // namespace
