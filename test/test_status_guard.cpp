// SPDX-License-Identifier: GPL-3.0-or-later
// No exception crosses the core's boundary: every exported core entry turns running out
// of memory (and anything else thrown) into Status::internal_error with a message that
// names the stage, and the classes hand that message on. Memory is made to run out on
// purpose: this executable replaces the global operator new with one that, while
// armed, refuses every block of kRefusedBytes or more (the core's per-sample arrays).
#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/boundary_samples.h>
#include <pcl/cocone/core/decimation.h>
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/voronoi_decimation.h>

#include "common/status_guard.h"

#include <support/clouds.h>
#include <support/shapes.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr std::size_t kRefusedBytes = 16 << 10;
std::atomic<bool> g_refusing{false};

void*
allocate(std::size_t size)
{
  if (g_refusing.load(std::memory_order_relaxed) && size >= kRefusedBytes)
    throw std::bad_alloc();
  if (void* block = std::malloc(size == 0 ? 1 : size))
    return block;
  throw std::bad_alloc();
}

/** Refuses large blocks while it lives. */
class RefuseLargeBlocks
{
public:
  RefuseLargeBlocks() { g_refusing = true; }
  ~RefuseLargeBlocks() { g_refusing = false; }
};

} // namespace

void*
operator new(std::size_t size)
{
  return allocate(size);
}
void*
operator new[](std::size_t size)
{
  return allocate(size);
}
void
operator delete(void* block) noexcept
{
  std::free(block);
}
void
operator delete[](void* block) noexcept
{
  std::free(block);
}
void
operator delete(void* block, std::size_t) noexcept
{
  std::free(block);
}
void
operator delete[](void* block, std::size_t) noexcept
{
  std::free(block);
}

namespace {

using pcl::cocone::Status;
using pcl::cocone::VoronoiCocone;
using namespace pcl::cocone::test;

// The guard itself: what a stage throws becomes internal_error and a message that
// names the stage.
TEST(StatusGuard, ExceptionsBecomeInternalErrorsNamingTheStage)
{
  using pcl::cocone::detail::runGuarded;
  std::string message;
  EXPECT_EQ(
      runGuarded("stitching", &message, []() -> Status { throw std::bad_alloc(); }),
      Status::internal_error);
  EXPECT_EQ(message, "out of memory during stitching");
  EXPECT_EQ(runGuarded("the walk", &message,
                       []() -> Status { throw std::runtime_error("no seed"); }),
            Status::internal_error);
  EXPECT_EQ(message, "the walk failed: no seed");
  EXPECT_EQ(runGuarded("pruning", &message, []() -> Status { throw 42; }),
            Status::internal_error);
  EXPECT_EQ(message, "pruning failed: unknown exception");
  // A stage passes on the failure of another entry it called, unchanged.
  EXPECT_EQ(runGuarded("the reconstruction", &message,
                       []() -> Status {
                         throw pcl::cocone::detail::StageFailure{
                             Status::internal_error,
                             "out of memory during boundary detection"};
                       }),
            Status::internal_error);
  EXPECT_EQ(message, "out of memory during boundary detection");
  message = "unchanged";
  EXPECT_EQ(runGuarded("anything", &message, [] { return Status::ok; }), Status::ok);
  EXPECT_EQ(message, "unchanged");
  EXPECT_EQ(runGuarded("anything", nullptr, []() -> Status { throw std::bad_alloc(); }),
            Status::internal_error);
}

/** True when \a message says that memory ran out during something. */
bool
saysOutOfMemory(const std::string& message)
{
  return message.rfind("out of memory during ", 0) == 0;
}

// Each exported core entry, with a diagram built beforehand where it needs one.
TEST(StatusGuard, EveryCoreEntryTurnsOutOfMemoryIntoAStatus)
{
  const std::vector<Eigen::Vector3d> points = sampleHemisphere(20000, 3).points;
  {
    VoronoiCocone voronoi;
    Status status;
    {
      RefuseLargeBlocks refuse;
      status = voronoi.compute(points);
    }
    std::cout << "[ measured ] compute(): " << voronoi.errorMessage() << std::endl;
    EXPECT_EQ(status, Status::internal_error);
    EXPECT_EQ(voronoi.status(), Status::internal_error);
    EXPECT_TRUE(saysOutOfMemory(voronoi.errorMessage())) << voronoi.errorMessage();
    EXPECT_EQ(voronoi.size(), 0u);
  }

  VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points), Status::ok);
  std::string message;
  std::vector<std::uint8_t> flags;
  {
    RefuseLargeBlocks refuse;
    EXPECT_EQ(pcl::cocone::detectBoundarySamples(
                  voronoi, pcl::cocone::BoundaryParameters(), flags, &message),
              Status::internal_error);
  }
  std::cout << "[ measured ] detectBoundarySamples(): " << message << std::endl;
  EXPECT_TRUE(saysOutOfMemory(message)) << message;
  EXPECT_TRUE(flags.empty());

  std::vector<pcl::cocone::TriangleIndices> triangles;
  pcl::cocone::ReconstructionReport report;
  message.clear();
  {
    RefuseLargeBlocks refuse;
    EXPECT_EQ(pcl::cocone::reconstructSurface(voronoi, {}, triangles, report, nullptr,
                                              &message),
              Status::internal_error);
  }
  std::cout << "[ measured ] reconstructSurface(): " << message << std::endl;
  EXPECT_TRUE(saysOutOfMemory(message)) << message;
  EXPECT_TRUE(triangles.empty());
  EXPECT_TRUE(report.boundary_samples.empty());

  std::vector<std::uint8_t> kept(voronoi.size(), 0), fixed(voronoi.size(), 0);
  for (std::size_t i = 0; i < kept.size(); i += 5)
    kept[i] = 1;
  const std::vector<std::uint8_t> kept_before = kept;
  std::size_t moves = 0;
  message.clear();
  {
    RefuseLargeBlocks refuse;
    EXPECT_EQ(
        pcl::cocone::relaxDecimatedSample(voronoi, fixed, 3, 1, kept, moves, &message),
        Status::internal_error);
  }
  std::cout << "[ measured ] relaxDecimatedSample(): " << message << std::endl;
  EXPECT_TRUE(saysOutOfMemory(message)) << message;
  EXPECT_EQ(kept, kept_before);

  ASSERT_EQ(pcl::cocone::detectBoundarySamples(
                voronoi, pcl::cocone::BoundaryParameters(), flags),
            Status::ok);
  pcl::cocone::DecimationLevels levels;
  message.clear();
  {
    RefuseLargeBlocks refuse;
    EXPECT_EQ(pcl::cocone::decimate(std::move(voronoi),
                                    pcl::cocone::DecimationParameters(), flags, levels,
                                    nullptr, &message),
              Status::internal_error);
  }
  std::cout << "[ measured ] decimate(): " << message << std::endl;
  EXPECT_TRUE(saysOutOfMemory(message)) << message;
  EXPECT_EQ(voronoi.status(), Status::not_computed); // consumed all the same

  // spatialOrder has no status: out of memory there is the caller's bad_alloc, as for
  // any container.
  RefuseLargeBlocks refuse;
  EXPECT_THROW(pcl::cocone::spatialOrder(points), std::bad_alloc);
}

// The classes check every status they get: the core's message reaches getErrorMessage()
// and the output is empty. The cloud is converted before memory runs out, so it is the
// core that fails.
TEST(StatusGuard, ClassesHandTheCoreMessageOn)
{
  const auto cloud = toCloud(sampleHemisphere(20000, 4).points);
  {
    pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
    cocone.setInputCloud(cloud);
    std::vector<pcl::Vertices> polygons;
    {
      RefuseLargeBlocks refuse;
      cocone.reconstruct(polygons);
    }
    std::cout << "[ measured ] CoconeReconstruction: " << cocone.getErrorMessage()
              << std::endl;
    EXPECT_TRUE(polygons.empty());
    EXPECT_TRUE(saysOutOfMemory(cocone.getErrorMessage())) << cocone.getErrorMessage();
    EXPECT_TRUE(cocone.getUnusedIndices().empty()); // documented: nothing refilled
  }
  {
    pcl::BoundarySampleEstimation<pcl::PointXYZ> boundary;
    boundary.setInputCloud(cloud);
    pcl::PointCloud<pcl::Boundary> flags;
    {
      RefuseLargeBlocks refuse;
      boundary.compute(flags);
    }
    std::cout << "[ measured ] BoundarySampleEstimation: " << boundary.getErrorMessage()
              << std::endl;
    EXPECT_TRUE(flags.empty());
    EXPECT_FALSE(boundary.getErrorMessage().empty());
  }
  {
    pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
    decimation.setInputCloud(cloud);
    pcl::Indices kept;
    {
      RefuseLargeBlocks refuse;
      decimation.filter(kept);
    }
    std::cout << "[ measured ] VoronoiDecimation: " << decimation.getErrorMessage()
              << std::endl;
    EXPECT_TRUE(kept.empty());
    EXPECT_FALSE(decimation.getErrorMessage().empty());
  }
}

} // namespace
