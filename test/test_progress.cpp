// SPDX-License-Identifier: GPL-3.0-or-later
// Progress and cancellation: the classes and the core report the share of a run done,
// rising from 0 to 1, from the thread that called them, and a callback that returns
// false stops the run with the message "cancelled" and an empty result.
#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/core/reconstruction.h>
#include <pcl/cocone/core/voronoi_cocone.h>
#include <pcl/cocone/voronoi_decimation.h>

#include <support/clouds.h>
#include <support/shapes.h>

#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <thread>
#include <vector>

namespace {

using namespace pcl::cocone::test;
using pcl::cocone::Status;

/** Records the shares reported, and the threads that reported them. */
struct Recorder
{
  std::vector<double> shares;
  bool other_thread = false;
  std::thread::id caller = std::this_thread::get_id();
  double cancel_at = 2; // cancel at the first share at or beyond this

  std::function<bool(double)>
  callback()
  {
    return [this](double share) {
      shares.push_back(share);
      other_thread = other_thread || std::this_thread::get_id() != caller;
      return share < cancel_at;
    };
  }

  void
  expectRisingToOne(const std::string& label) const
  {
    ASSERT_GE(shares.size(), 3u) << label;
    for (std::size_t k = 1; k < shares.size(); ++k)
      EXPECT_LE(shares[k - 1], shares[k]) << label << " at report " << k;
    EXPECT_GE(shares.front(), 0.0) << label;
    EXPECT_DOUBLE_EQ(shares.back(), 1.0) << label;
    EXPECT_FALSE(other_thread) << label << ": reported from another thread";
    std::cout << "[ measured ] " << label << ": " << shares.size() << " reports"
              << std::endl;
  }
};

const pcl::PointCloud<pcl::PointXYZ>::Ptr&
hemisphere()
{
  // Over 65536 points, so that the triangulation reports as it goes.
  static const pcl::PointCloud<pcl::PointXYZ>::Ptr cloud =
      toCloud(sampleHemisphere(150000, 21).points);
  return cloud;
}

TEST(Progress, ClassesReportFromZeroToOneOnTheCallingThread)
{
  {
    Recorder recorder;
    pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
    cocone.setInputCloud(hemisphere());
    cocone.setProgressCallback(recorder.callback());
    std::vector<pcl::Vertices> polygons;
    cocone.reconstruct(polygons);
    EXPECT_FALSE(polygons.empty());
    recorder.expectRisingToOne("CoconeReconstruction");
  }
  {
    Recorder recorder;
    pcl::BoundarySampleEstimation<pcl::PointXYZ> boundary;
    boundary.setInputCloud(hemisphere());
    boundary.setProgressCallback(recorder.callback());
    pcl::PointCloud<pcl::Boundary> flags;
    boundary.compute(flags);
    EXPECT_EQ(flags.size(), hemisphere()->size());
    recorder.expectRisingToOne("BoundarySampleEstimation");
  }
  {
    Recorder recorder;
    pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
    decimation.setInputCloud(hemisphere());
    decimation.setProgressCallback(recorder.callback());
    pcl::Indices kept;
    decimation.filter(kept);
    EXPECT_FALSE(kept.empty());
    recorder.expectRisingToOne("VoronoiDecimation");
  }
}

// Cancelled early (during the triangulation) and late (in the last stage): the run
// fails with "cancelled" and leaves no result.
TEST(Progress, ReturningFalseCancels)
{
  for (const double at : {0.0, 0.2, 0.95}) {
    {
      Recorder recorder;
      recorder.cancel_at = at;
      pcl::CoconeReconstruction<pcl::PointXYZ> cocone;
      cocone.setInputCloud(hemisphere());
      cocone.setProgressCallback(recorder.callback());
      std::vector<pcl::Vertices> polygons;
      cocone.reconstruct(polygons);
      EXPECT_TRUE(polygons.empty()) << at;
      EXPECT_EQ(cocone.getErrorMessage(), "cancelled") << at;
      EXPECT_GE(recorder.shares.back(), at);
    }
    {
      Recorder recorder;
      recorder.cancel_at = at;
      pcl::BoundarySampleEstimation<pcl::PointXYZ> boundary;
      boundary.setInputCloud(hemisphere());
      boundary.setProgressCallback(recorder.callback());
      pcl::PointCloud<pcl::Boundary> flags;
      boundary.compute(flags);
      EXPECT_TRUE(flags.empty()) << at;
      EXPECT_EQ(boundary.getErrorMessage(), "cancelled") << at;
    }
    {
      Recorder recorder;
      recorder.cancel_at = at;
      pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
      decimation.setInputCloud(hemisphere());
      decimation.setProgressCallback(recorder.callback());
      pcl::Indices kept;
      decimation.filter(kept);
      EXPECT_TRUE(kept.empty()) << at;
      EXPECT_EQ(decimation.getErrorMessage(), "cancelled") << at;
    }
  }
}

// The core entries on their own.
TEST(Progress, CoreEntriesReportAndCancel)
{
  const std::vector<Eigen::Vector3d> points = toPoints(*hemisphere());
  Recorder building;
  pcl::cocone::VoronoiCocone voronoi;
  ASSERT_EQ(voronoi.compute(points, building.callback()), Status::ok);
  building.expectRisingToOne("compute()");

  Recorder meshing;
  std::vector<pcl::cocone::TriangleIndices> triangles;
  pcl::cocone::ReconstructionReport report;
  ASSERT_EQ(pcl::cocone::reconstructSurface(voronoi, {}, triangles, report,
                                            meshing.callback()),
            Status::ok);
  meshing.expectRisingToOne("reconstructSurface()");

  Recorder cancelling;
  cancelling.cancel_at = 0.5;
  std::string message;
  EXPECT_EQ(pcl::cocone::reconstructSurface(voronoi, {}, triangles, report,
                                            cancelling.callback(), &message),
            Status::internal_error);
  EXPECT_EQ(message, "cancelled");
  EXPECT_TRUE(triangles.empty());

  pcl::cocone::VoronoiCocone cancelled;
  Recorder at_once;
  at_once.cancel_at = 0;
  EXPECT_EQ(cancelled.compute(points, at_once.callback()), Status::internal_error);
  EXPECT_EQ(cancelled.errorMessage(), "cancelled");
  EXPECT_EQ(cancelled.size(), 0u);
}

} // namespace
