// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_voronoi_decimation: removes oversampling while keeping features (algorithm
// DECIMATE of Dey et al. 2001). The kept rows are copied from the input with all their
// fields, never moved or resampled, in input order.
//
// With -v the library's PCL_DEBUG lines (the diagram's stage timings, then the removal
// summary) show as the decimation runs. Finer progress would need the core's callback
// (pcl::cocone::VoronoiCocone::decimate), which pcl::VoronoiDecimation does not pass
// on.
#include "tool_common.h"

#include <pcl/cocone/parameters.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>

using namespace pcl::cocone::tools;

namespace {

CommandLine
commandLine()
{
  return CommandLine(
      {"pcl_voronoi_decimation",
       "removes oversampling while keeping every feature: samples with long, skinny "
       "Voronoi cells are dropped, flat regions are thinned much more than curved "
       "ones (algorithm DECIMATE of Dey et al., IEEE Visualization 2001).",
       "OUTPUT.pcd",
       {".pcd"},
       "binary PCD with the kept input rows, all their fields, in input order (points "
       "with a NaN coordinate are never kept)"},
      {ratioBoundOption(0.3, "samples with r_p/h_p below R are removed, smallest "
                             "first; useful range 0.25 to 0.4, larger removes more"),
       coconeAngleOption(),
       flagOption("-keep_rims",
                  "DECIMATE as published: keep the outermost row of an open surface at "
                  "its input density (by default rims are thinned like the rest)"),
       {"-relax", ValueKind::integer, "N",
        "rounds of relaxation after DECIMATE: the kept points are evened out at the "
        "same count (Lloyd's iteration over the input points; rims and sharp features "
        "stay); 0 gives DECIMATE's own points",
        10, "", pcl::cocone::kRelaxationIterationsRange},
       denoiseOption(),
       tilesOption(),
       threadsOption(),
       verboseOption()});
}

pcl::Indices
decimate(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& xyz, const CommandLine& cmd)
{
  pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
  decimation.setInputCloud(xyz);
  decimation.setRatioBound(cmd.value("-rho"));
  decimation.setCoconeAngle(cmd.value("-theta"));
  decimation.setThinRims(!cmd.flag("-keep_rims"));
  decimation.setRelaxationIterations(cmd.count("-relax"));
  decimation.setNumberOfThreads(cmd.count("-threads"));
  decimation.setNumberOfTiles(static_cast<unsigned>(cmd.count("-tiles")));
  decimation.setDenoise(denoiseMode(cmd));
  decimation.setProgressCallback(terminalProgress());
  if (cmd.verbose())
    printDetail("Parameters",
                "rho " + formatNumber(decimation.getRatioBound()) + ", theta " +
                    formatNumber(decimation.getCoconeAngle()) + " rad, rims " +
                    (decimation.getThinRims() ? "thinned" : "kept") + ", relaxation " +
                    std::to_string(decimation.getRelaxationIterations()) + " rounds");

  pcl::Indices kept;
  computeStage("the decimation", "points kept",
               [&](std::string& reason) -> std::optional<std::size_t> {
                 decimation.filter(kept);
                 // A valid cloud always keeps points; nothing kept means the diagram
                 // failed.
                 if (kept.empty()) {
                   reason = decimation.getErrorMessage();
                   return std::nullopt;
                 }
                 return kept.size();
               });
  printWarning(decimation.getWarningMessage());
  return kept;
}

} // namespace

int
main(int argc, char** argv)
{
  CommandLine cmd = commandLine();
  cmd.parse(argc, argv);

  const pcl::PCLPointCloud2 input = loadCloud(cmd.input(), cmd.verbose());
  const pcl::Indices kept = decimate(toXyz(input), cmd);

  pcl::PCLPointCloud2 output;
  pcl::copyPointCloud(input, kept, output);
  output.is_dense = true; // only finite points are kept
  saveCloud(cmd.output(), output);

  const std::size_t n = pointCount(input);
  pcl::console::print_info("kept %zu of %zu points (%s%% removed)\n", kept.size(), n,
                           formatPercent(n - kept.size(), n).c_str());
  return 0;
}
