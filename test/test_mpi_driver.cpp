// SPDX-License-Identifier: GPL-3.0-or-later
// pcl_cocone_reconstruction_mpi run as a user runs it, under mpirun with 2 and 3
// processes on this one machine: the mesh it writes equals, byte for byte after the
// header's "written by" comment, the mesh pcl_cocone_reconstruction writes, whether
// the tiles were really spread over the processes or fell back to one tile on rank 0.
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/process.h"
#include "support/scratch_folder.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using pcl::cocone::test::readText;
using pcl::cocone::test::runTool;
using pcl::cocone::test::Shape;
using pcl::cocone::test::shellQuote;
using pcl::cocone::test::ToolRun;
namespace shapes = pcl::cocone::test;

const char* const kToolDir = PCL_COCONE_TOOL_DIR;
const char* const kMpiexec = PCL_COCONE_MPIEXEC;

class MpiDriver : public ::testing::Test
{
protected:
  static void
  SetUpTestSuite()
  {
    folder_ = std::make_unique<pcl::cocone::test::ScratchFolder>("pcl_cocone_mpi_");
    write("torus.pcd", shapes::sampleRandom(Shape::torus, 20000, 4).points);
    write("cylinder.pcd", shapes::sampleRandom(Shape::open_cylinder, 20000, 3).points);
  }

  static void
  TearDownTestSuite()
  {
    folder_.reset();
  }

  static fs::path
  path(const std::string& name)
  {
    return folder_->path() / name;
  }

  static void
  write(const std::string& name, const std::vector<Eigen::Vector3d>& points)
  {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    for (const Eigen::Vector3d& p : points)
      cloud.push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
    pcl::io::savePCDFileBinary(path(name).string(), cloud);
  }

  /** pcl_cocone_reconstruction with \a args. */
  static ToolRun
  single(const std::vector<std::string>& args)
  {
    return run("", "pcl_cocone_reconstruction", args);
  }

  /** pcl_cocone_reconstruction_mpi with \a args, under mpirun with \a processes. */
  static ToolRun
  distributed(unsigned processes, const std::vector<std::string>& args)
  {
    // Root in a container, and more processes than cores on this machine.
    return run(shellQuote(kMpiexec) + " --allow-run-as-root --oversubscribe -np " +
                   std::to_string(processes) + " ",
               "pcl_cocone_reconstruction_mpi", args);
  }

  static ToolRun
  run(const std::string& launcher, const std::string& tool,
      const std::vector<std::string>& args)
  {
    static int counter = 0;
    const std::string id = std::to_string(counter++);
    return runTool(launcher, fs::path(kToolDir) / tool, args, path("stdout_" + id),
                   path("stderr_" + id));
  }

  /** A PLY file without its "comment written by <program>" line. */
  static std::string
  meshBytes(const std::string& name)
  {
    std::string bytes = readText(path(name));
    const std::size_t comment = bytes.find("comment written by ");
    if (comment != std::string::npos)
      bytes.erase(comment, bytes.find('\n', comment) + 1 - comment);
    return bytes;
  }

  static std::unique_ptr<pcl::cocone::test::ScratchFolder> folder_;
};

std::unique_ptr<pcl::cocone::test::ScratchFolder> MpiDriver::folder_;

std::size_t
occurrences(const std::string& text, const std::string& what)
{
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos;
       at = text.find(what, at + 1))
    ++count;
  return count;
}

TEST_F(MpiDriver, ThreeProcessesWriteTheSingleProcessMesh)
{
  const ToolRun one =
      single({path("torus.pcd").string(), path("torus_1.ply").string()});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  // -v shows the tiles: one per process by default.
  const ToolRun three =
      distributed(3, {path("torus.pcd").string(), path("torus_3.ply").string(), "-v"});
  ASSERT_EQ(three.exit_code, 0) << three.out << three.err;
  EXPECT_NE(three.out.find("in 3 tiles"), std::string::npos) << three.out;
  // Only rank 0 reports.
  EXPECT_EQ(occurrences(three.out, "vertices used"), 1u) << three.out;
  EXPECT_NE(three.out.find("boundary loops 0, Euler characteristic 0, closed yes, "
                           "manifold yes"),
            std::string::npos)
      << three.out;
  const std::string expected = meshBytes("torus_1.ply");
  ASSERT_GT(expected.size(), 20000u * 12);
  EXPECT_TRUE(meshBytes("torus_3.ply") == expected) << "the meshes differ";
}

TEST_F(MpiDriver, OpenSurfaceOnTwoProcessesKeepsItsRims)
{
  const ToolRun one =
      single({path("cylinder.pcd").string(), path("cylinder_1.ply").string()});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const ToolRun two = distributed(
      2, {path("cylinder.pcd").string(), path("cylinder_2.ply").string(), "-v"});
  ASSERT_EQ(two.exit_code, 0) << two.out << two.err;
  EXPECT_NE(two.out.find("in 2 tiles"), std::string::npos) << two.out;
  EXPECT_NE(two.out.find("boundary loops 2,"), std::string::npos) << two.out;
  EXPECT_TRUE(meshBytes("cylinder_2.ply") == meshBytes("cylinder_1.ply"))
      << "the meshes differ";
}

TEST_F(MpiDriver, TilesThatOutgrowTheirHalosFallBackToTheSameMesh)
{
  const ToolRun one =
      single({path("torus.pcd").string(), path("torus_a.ply").string()});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const ToolRun three =
      distributed(3, {path("torus.pcd").string(), path("torus_b.ply").string(),
                      "-tiles", "64", "-v"});
  ASSERT_EQ(three.exit_code, 0) << three.out << three.err;
  EXPECT_NE(three.out.find("in 1 tiles"), std::string::npos) << three.out;
  EXPECT_TRUE(meshBytes("torus_b.ply") == meshBytes("torus_a.ply"))
      << "the meshes differ";
}

TEST_F(MpiDriver, BadInputFailsWithItsReason)
{
  // Every process reads the input and fails alike; mpirun then exits non-zero.
  const ToolRun missing =
      distributed(2, {path("missing.pcd").string(), path("never.ply").string()});
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("pcl_cocone_reconstruction_mpi: "), std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("no such file"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(path("never.ply")));
  const ToolRun option = distributed(
      2, {path("torus.pcd").string(), path("x.ply").string(), "-tiles", "x"});
  EXPECT_NE(option.exit_code, 0);
  EXPECT_NE(option.err.find("-tiles"), std::string::npos) << option.err;
}

TEST_F(MpiDriver, HelpPrintsOnceAndExitsZero)
{
  const ToolRun help = distributed(2, {"-h"});
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_EQ(occurrences(help.out, "Run it under mpirun"), 1u) << help.out;
  EXPECT_EQ(help.err.find("MPI_ABORT"), std::string::npos) << help.err;
}

} // namespace
