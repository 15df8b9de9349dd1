// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * \file
 * The benchmark's inputs: the paper's data sets and real scans read from the data
 * folder, analytic shapes sampled in process (test/support/shapes.h), and a 1M-sample
 * jittered torus; each with its reference surface where one is known (the analytic
 * surface, or the faces of a mesh file) and points spread over that reference for the
 * reference-to-reconstruction distance.
 */
#pragma once

#include <pcl/cocone/core/mesh_topology.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/clouds.h"
#include "support/shapes.h"

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pcl {
namespace cocone {
namespace bench {

/** \brief A row of the paper's Table 1 (reconstruction; 933 MHz Pentium III). */
struct PaperReconstructionRow
{
  std::string name;
  double points = 0;
  double triangles = 0;
  double seconds = 0;
};

/** \brief A row of the paper's Table 2 (decimation). */
struct PaperDecimationRow
{
  std::string name;
  double before = 0;
  double after_03 = 0;
  double after_04 = 0;
  double seconds_03 = 0;
  double seconds_04 = 0;
};

/** \brief One benchmark input. */
struct Input
{
  std::string name;   ///< short label, e.g. "cactus", "torus-100k"
  std::string source; ///< file name or how it was generated
  std::string kind;   ///< "paper data", "real scan", "generated"
  std::string note;   ///< how it differs from the paper's, where it does

  /** The finite points, in file order, duplicates kept, rounded to float (what a
   * pcl::PointXYZ cloud holds, so every method sees the same coordinates). */
  std::vector<Eigen::Vector3d> points;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud; ///< the same points as a PCL cloud
  std::size_t unique = 0;                    ///< distinct points
  double spacing = 0;  ///< mean distance to the nearest other sample
  double diagonal = 0; ///< bounding-box diagonal
  /** Noisy inputs: the largest distance of a sample from the true surface. A mesh
   * through the samples is at least this far from it somewhere. */
  double farthest_sample = 0;

  /** Analytic reference (generated shapes). */
  std::shared_ptr<const test::SampledShape> shape;
  /** Mesh reference (mesh files): vertices and triangles. */
  std::vector<Eigen::Vector3d> mesh_vertices;
  std::vector<TriangleIndices> mesh_triangles;
  /** Points spread evenly over the reference surface (empty without reference; set
   * before finishInput, it is kept). */
  std::vector<Eigen::Vector3d> reference_probes;

  /** What the reference surface is, where known: closed (1), open (0), unknown (-1). */
  int closed = -1;
  long genus = -1;          ///< -1 when unknown
  long boundary_loops = -1; ///< -1 when unknown

  std::optional<PaperReconstructionRow> paper;
  std::optional<PaperDecimationRow> paper_decimation;

  bool
  hasReference() const
  {
    return static_cast<bool>(shape) || !mesh_triangles.empty();
  }
  std::size_t
  size() const
  {
    return points.size();
  }
};

/** \brief A data file the benchmark uses, with what is known about it. */
struct FileSpec
{
  std::string name;
  std::string file;
  std::string kind;
  std::string note;
  std::optional<PaperReconstructionRow> paper;
  std::optional<PaperDecimationRow> paper_decimation;
  /** Topology of the sampled surface where it is known without faces (the data
   * folder's README) or where the samples leave open what the file's faces close:
   * closed (1), open (0) or unknown (-1), genus, boundary loops. When set, it replaces
   * the topology of the file's faces; the note says why. */
  int closed = -1;
  long genus = -1;
  long boundary_loops = -1;
};

/** \brief The data files of the benchmark (paper sets first, then real scans). */
std::vector<FileSpec> dataFiles();

/** \brief Reads \a spec from \a directory. False (with \a why) when the file is
 * missing or unreadable. */
bool loadFileInput(const std::string& directory, const FileSpec& spec, Input& input,
                   std::string& why);

/** \brief An analytic shape of test/support/shapes.h sampled as blue noise. */
using ShapeGenerator = test::SampledShape (*)(std::size_t, std::uint32_t);
Input
generatedInput(const std::string& shape_name, ShapeGenerator generate, std::size_t n);

/** \brief A torus (major radius 1, minor 0.35, as sampleTorus) sampled on a staggered
 * grid of about \a n points, even by area, with a uniform random jitter of 1e-5 of the
 * bounding-box diagonal in each coordinate (no four points co-spherical). Fast at any
 * size, unlike the blue-noise generator. */
Input jitteredTorusInput(std::size_t n);

/** \brief The generated shapes: name and generator. */
struct GeneratedShape
{
  std::string name;
  ShapeGenerator generate;
};
std::vector<GeneratedShape> generatedShapes();

/** \brief The sizes the generated shapes are sampled at: 10k and 100k points, and 1M
 * unless \a quick. */
std::vector<std::size_t> generatedSizes(bool quick);

/** \brief The name of a generated input: "sphere-10k", "sphere-1M". */
std::string generatedName(const std::string& shape, std::size_t n);

/** \brief An analytic shape sampled as a scanner does rather than as blue noise
 * (test::sampleRandom, seed 1): \a n area-uniform random points, with their close
 * pairs and wide gaps. Named by randomName; its reference probes are another random
 * sample of the same surface (seed 7, \a probes points). */
Input randomInput(test::Shape shape, std::size_t n, std::size_t probes);

/** \brief The name of a random input: "random-open-cylinder-1M". */
std::string randomName(test::Shape shape, std::size_t n);

/** \brief randomInput with scanner noise: isotropic Gaussian displacements of standard
 * deviation \a sigma_in_spacings mean spacings (test::withGaussianNoise, seed 7). The
 * reference surface stays the true one. Named "noisy-torus-100k-0.3". */
Input noisyInput(test::Shape shape, std::size_t n, double sigma_in_spacings,
                 std::size_t probes);

/** \brief The noisy inputs: the five shapes of issue 23 (torus, genus 3, hemisphere,
 * open cylinder, cube) at 100k random samples, noise of 0.1, 0.3 and 0.5 spacings. */
struct NoisySpec
{
  test::Shape shape;
  std::size_t n;
  double sigma_in_spacings;
};
std::vector<NoisySpec> noisyInputs();
std::string noisyName(const NoisySpec& spec);

/** \brief The sizes the shapes are randomly sampled at: 100k points, and 1M and 4M
 * unless \a quick. */
std::vector<std::size_t> randomSizes(bool quick);

/** \brief Computes the derived fields of an input whose points are set: cloud, unique
 * count, spacing, diagonal, reference probes (about \a probes points). */
void finishInput(Input& input, std::size_t probes);

/** A point set as a pcl::PointXYZ cloud (the tests' helper). */
using test::toCloud;

} // namespace bench
} // namespace cocone
} // namespace pcl
