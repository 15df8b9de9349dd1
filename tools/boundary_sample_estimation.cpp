// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_boundary_sample_estimation: flags the samples near undersampling (algorithm
// BOUNDARY of Dey et al. 2001) and writes them as a boundary_point field next to the
// input's own fields, one row per input point, so that the output lines up with the
// input row for row.
#include "tool_common.h"

#include <pcl/cocone/boundary_sample_estimation.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

using namespace pcl::cocone::tools;

namespace {

CommandLine
commandLine()
{
  return CommandLine(
      {"pcl_boundary_sample_estimation",
       "flags the samples near undersampling (boundaries, sharp features, thin or "
       "sparsely sampled parts) from the shape of their Voronoi cells: algorithm "
       "BOUNDARY of Dey et al., IEEE Visualization 2001.",
       "OUTPUT.pcd",
       {".pcd"},
       "binary PCD with one row per input point, in input order: the input's fields "
       "plus boundary_point (1 for a boundary sample; 0 also for NaN points)"},
      {ratioBoundOption(0.99, "ratio bound of the flatness test r_p/h_p <= R; "
                              "smaller values flag more samples"),
       normalAngleOption(),
       coconeAngleOption(),
       {"-band", ValueKind::integer, "K",
        "also flag K rings of cocone neighbours around the boundary samples, for a "
        "band like pcl::BoundaryEstimation's; 0 is BOUNDARY as published",
        0, "", pcl::cocone::kBandRingsRange},
       flagOption(
           "-no_rim_completion",
           "flag only what BOUNDARY as published flags: a quarter to a half of the outermost "
           "row along a rim (by default the row is completed from those flags)"),
       flagOption(
           "-rgb",
           "also write an rgb field: red for boundary samples, grey for the others, so "
           "that pcl_viewer shows them as in the paper's figure 4"),
       denoiseOption(),
       tilesOption(),
       threadsOption(),
       verboseOption()});
}

pcl::PointCloud<pcl::Boundary>
compute(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& xyz, const CommandLine& cmd)
{
  pcl::BoundarySampleEstimation<pcl::PointXYZ, pcl::Boundary> estimation;
  estimation.setInputCloud(xyz);
  estimation.setRatioBound(cmd.value("-rho"));
  estimation.setNormalAngle(cmd.value("-alpha"));
  estimation.setCoconeAngle(cmd.value("-theta"));
  estimation.setBoundaryBandRings(cmd.count("-band"));
  estimation.setRimRowCompletion(!cmd.flag("-no_rim_completion"));
  estimation.setNumberOfThreads(cmd.count("-threads"));
  estimation.setNumberOfTiles(static_cast<unsigned>(cmd.count("-tiles")));
  estimation.setDenoise(denoiseMode(cmd));
  estimation.setProgressCallback(terminalProgress());
  if (cmd.verbose())
    printDetail("Parameters",
                "rho " + formatNumber(estimation.getRatioBound()) + ", alpha " +
                    formatNumber(estimation.getNormalAngle()) + " rad, theta " +
                    formatNumber(estimation.getCoconeAngle()) + " rad, rim row " +
                    (estimation.getRimRowCompletion() ? "completed" : "as published") +
                    ", band " + std::to_string(estimation.getBoundaryBandRings()) +
                    " rings");

  pcl::PointCloud<pcl::Boundary> flags;
  computeStage("boundary samples", "boundary samples",
               [&](std::string& reason) -> std::optional<std::size_t> {
                 estimation.compute(flags);
                 // Every failure (e.g. coplanar input) leaves the output empty.
                 if (flags.size() != xyz->size()) {
                   reason = estimation.getErrorMessage();
                   return std::nullopt;
                 }
                 return estimation.getNumberOfBoundarySamples();
               });
  printWarning(estimation.getWarningMessage());

  if (cmd.verbose()) {
    const std::vector<std::uint8_t>& valid = estimation.getValidity();
    std::vector<float> ratios;
    for (std::size_t i = 0; i < valid.size(); ++i)
      if (valid[i])
        ratios.push_back(estimation.getRatios()[i]);
    printDetail("Finite points", std::to_string(ratios.size()));
    if (!ratios.empty()) {
      auto middle = ratios.begin() + ratios.size() / 2;
      std::nth_element(ratios.begin(), middle, ratios.end());
      printDetail("Median r_p/h_p", formatNumber(*middle, 4));
    }
  }
  return flags;
}

/** The new fields as a cloud of the input's shape: rgb (with -rgb) and boundary_point.
 * rgb is packed into a float as in pcl::PointXYZRGB (alpha 255), so that pcl_viewer
 * colours by it. */
pcl::PCLPointCloud2
flagFields(const pcl::PointCloud<pcl::Boundary>& flags,
           const pcl::PCLPointCloud2& input, bool rgb)
{
  pcl::PCLPointCloud2 extra;
  extra.width = input.width;
  extra.height = input.height;
  extra.is_bigendian = input.is_bigendian;
  extra.is_dense = true;
  if (rgb)
    extra.fields.push_back({"rgb", 0, pcl::PCLPointField::FLOAT32, 1});
  const std::uint32_t flag_offset = rgb ? 4 : 0;
  extra.fields.push_back({"boundary_point", flag_offset, pcl::PCLPointField::UINT8, 1});
  extra.point_step = flag_offset + 1;
  extra.row_step = extra.point_step * extra.width;
  extra.data.resize(flags.size() * extra.point_step);

  const auto pack = [](std::uint32_t r, std::uint32_t g, std::uint32_t b) {
    return (255u << 24) | (r << 16) | (g << 8) | b;
  };
  const std::uint32_t red = pack(255, 0, 0);
  const std::uint32_t grey = pack(160, 160, 160);
  for (std::size_t i = 0; i < flags.size(); ++i) {
    std::uint8_t* row = &extra.data[i * extra.point_step];
    if (rgb)
      std::memcpy(row, flags[i].boundary_point ? &red : &grey, 4);
    row[flag_offset] = flags[i].boundary_point;
  }
  return extra;
}

} // namespace

int
main(int argc, char** argv)
{
  CommandLine cmd = commandLine();
  cmd.parse(argc, argv);
  const bool rgb = cmd.flag("-rgb");

  const pcl::PCLPointCloud2 input = loadCloud(cmd.input(), cmd.verbose());
  const pcl::PointCloud<pcl::Boundary> flags = compute(toXyz(input), cmd);

  // The new fields replace same-named ones of the input (e.g. when a tool output is
  // processed again); concatenateFields puts its second cloud's fields first.
  std::vector<std::string> replaced{"boundary_point"};
  if (rgb)
    replaced.insert(replaced.end(), {"rgb", "rgba"});
  pcl::PCLPointCloud2 output;
  if (!pcl::concatenateFields(flagFields(flags, input, rgb),
                              withoutFields(input, replaced), output))
    fail("internal error: cannot add the boundary_point field");
  saveCloud(cmd.output(), output);

  std::size_t boundary = 0;
  for (const pcl::Boundary& flag : flags)
    boundary += flag.boundary_point;
  pcl::console::print_info("%zu boundary samples of %zu points (%s%%)\n", boundary,
                           flags.size(), formatPercent(boundary, flags.size()).c_str());
  return 0;
}
