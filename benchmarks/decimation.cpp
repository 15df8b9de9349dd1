// SPDX-License-Identifier: GPL-3.0-or-later
//
// Decimation section: pcl::VoronoiDecimation (ours) beside the paper's Table 2, its
// time and memory over rho, and the error of the reconstruction of the kept points at
// equal point counts against pcl::VoxelGrid, pcl::UniformSampling and CGAL's
// grid_simplify_point_set and hierarchy_simplify_point_set (each tuned by bisection on
// its parameter to the count ours keeps).
#include "bench_quality.h"
#include "sections.h"

#include <pcl/cocone/cocone_reconstruction.h>
#include <pcl/cocone/voronoi_decimation.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/filters/voxel_grid.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/grid_simplify_point_set.h>
#include <CGAL/hierarchy_simplify_point_set.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

namespace pcl {
namespace cocone {
namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;

/** hierarchy_simplify's cluster size cap is chosen so that the variation alone can
 * bring its count within this share of ours (the bisection then goes on). */
constexpr double kCountTolerance = 0.02;

using Points = std::vector<Eigen::Vector3d>;

// ---------------------------------------------------------------------------------
// The filters, each as "parameter -> kept points".

Points
fromCloud(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  Points out;
  out.reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud)
    out.emplace_back(p.x, p.y, p.z);
  return out;
}

Points
voxelGrid(const Input& input, double leaf)
{
  pcl::VoxelGrid<pcl::PointXYZ> filter;
  filter.setInputCloud(input.cloud);
  const float l = static_cast<float>(leaf);
  filter.setLeafSize(l, l, l);
  pcl::PointCloud<pcl::PointXYZ> out;
  filter.filter(out);
  return fromCloud(out);
}

Points
uniformSampling(const Input& input, double radius)
{
  pcl::UniformSampling<pcl::PointXYZ> filter;
  filter.setInputCloud(input.cloud);
  filter.setRadiusSearch(radius);
  pcl::PointCloud<pcl::PointXYZ> out;
  filter.filter(out);
  return fromCloud(out);
}

std::vector<Point3>
cgalPoints(const Input& input)
{
  std::vector<Point3> points;
  points.reserve(input.points.size());
  for (const Eigen::Vector3d& p : input.points)
    points.emplace_back(p.x(), p.y(), p.z());
  return points;
}

Points
fromCgal(const std::vector<Point3>& points, std::vector<Point3>::const_iterator end)
{
  Points out;
  for (auto it = points.cbegin(); it != end; ++it)
    out.emplace_back(it->x(), it->y(), it->z());
  return out;
}

Points
gridSimplify(const Input& input, double epsilon)
{
  std::vector<Point3> points = cgalPoints(input);
  const auto end = CGAL::grid_simplify_point_set(points, epsilon);
  return fromCgal(points, end);
}

Points
hierarchySimplify(const Input& input, unsigned size, double variation)
{
  std::vector<Point3> points = cgalPoints(input);
  const auto end = CGAL::hierarchy_simplify_point_set(
      points, CGAL::parameters::size(size).maximum_variation(variation));
  return fromCgal(points, end);
}

/** Geometric bisection of a parameter whose kept count decreases as it grows, towards
 * \a target: it stops at the exact count or where the bracket closes (a step of the
 * count), and returns the parameter of the closest count it met. Counts within 2% were
 * accepted at first, and left a peer up to 1.9% more points than ours; the errors
 * compared are of the order of that difference. */
double
bisect(const std::function<std::size_t(double)>& kept, double low, double high,
       std::size_t target, double limit_high = std::numeric_limits<double>::infinity())
{
  const auto off = [&](std::size_t c) {
    return std::abs(static_cast<double>(c) - static_cast<double>(target));
  };
  double best = low;
  double best_off = std::numeric_limits<double>::infinity();
  const auto visit = [&](double p) {
    const std::size_t c = kept(p);
    if (off(c) < best_off) {
      best_off = off(c);
      best = p;
    }
    return c;
  };
  for (int i = 0; i < 64 && visit(low) < target; ++i)
    low /= 2;
  for (int i = 0; i < 20 && visit(high) > target && high < limit_high; ++i)
    high = std::min(limit_high, high * 2);
  for (int i = 0; i < 60 && best_off > 0; ++i) {
    const double mid = std::sqrt(low * high);
    if (visit(mid) > target)
      low = mid;
    else
      high = mid;
    if (high / low < 1 + 1e-9)
      break;
  }
  return best;
}

/** Reconstructs \a kept with CoconeReconstruction and records the mesh and its
 * two-sided distance to the input's reference surface (in spacings of the full
 * input). */
void
recordReconstructionError(const Input& input, const Points& kept, Measurement& m)
{
  m.values["kept"] = static_cast<double>(kept.size());
  pcl::CoconeReconstruction<pcl::PointXYZ> reconstruction;
  reconstruction.setInputCloud(toCloud(kept));
  std::vector<pcl::Vertices> polygons;
  reconstruction.reconstruct(polygons);
  std::vector<TriangleIndices> triangles;
  for (const pcl::Vertices& p : polygons)
    if (p.vertices.size() == 3)
      triangles.push_back({static_cast<std::uint32_t>(p.vertices[0]),
                           static_cast<std::uint32_t>(p.vertices[1]),
                           static_cast<std::uint32_t>(p.vertices[2])});
  const MeshTopology topology = analyzeTriangleMesh(triangles);
  m.values["triangles"] = static_cast<double>(triangles.size());
  m.values["loops"] =
      topology.non_manifold_edges == 0 && topology.non_manifold_vertices == 0
          ? static_cast<double>(topology.boundary_loops.size())
          : kNaN;
  m.values["genus"] = static_cast<double>(topology.genus());
  const SurfaceDistance d = surfaceDistance(input, kept, triangles);
  m.values["d_hausdorff"] = d.hausdorff();
  m.values["d_mean"] = d.mean();
}

/** Ours with its defaults; \a as_published: rims kept (setThinRims(false)) and no
 * relaxation; \a relax false: rims thinned, no relaxation. */
void
runOurs(const Input& input, double rho, bool quality, Measurement& m,
        bool as_published = false, bool relax = true)
{
  pcl::VoronoiDecimation<pcl::PointXYZ> decimation;
  decimation.setInputCloud(input.cloud);
  decimation.setRatioBound(rho);
  decimation.setThinRims(!as_published);
  if (as_published || !relax)
    decimation.setRelaxationIterations(0);
  pcl::Indices kept;
  AlgorithmMeter meter;
  decimation.filter(kept);
  meter.stop(m);
  if (kept.empty()) {
    m.error = decimation.getErrorMessage().empty() ? "nothing kept"
                                                   : decimation.getErrorMessage();
    return;
  }
  m.values["kept"] = static_cast<double>(kept.size());
  if (!quality)
    return;
  Points points;
  points.reserve(kept.size());
  for (const pcl::index_t i : kept)
    points.push_back(input.points[static_cast<std::size_t>(i)]);
  recordReconstructionError(input, points, m);
}

/** Tunes a peer's parameter to keep \a target points (bisection inside this child):
 * records "p1" (and "p2" for hierarchy_simplify: the cluster size cap) and the text
 * "parameter". */
void
tunePeer(const Input& input, const std::string& peer, std::size_t target,
         Measurement& m)
{
  const double n = static_cast<double>(input.size());
  const double scale = input.spacing * std::sqrt(n / static_cast<double>(target));
  std::ostringstream parameter;
  if (peer == "VoxelGrid") {
    const double leaf = bisect([&](double p) { return voxelGrid(input, p).size(); },
                               0.5 * scale, 2 * scale, target);
    m.values["p1"] = leaf;
    parameter << "leaf " << sig(leaf / input.spacing, 3) << " sp";
  }
  else if (peer == "UniformSampling") {
    const double radius =
        bisect([&](double p) { return uniformSampling(input, p).size(); }, 0.5 * scale,
               2 * scale, target);
    m.values["p1"] = radius;
    parameter << "radius " << sig(radius / input.spacing, 3) << " sp";
  }
  else if (peer == "CGAL grid_simplify") {
    const double epsilon =
        bisect([&](double p) { return gridSimplify(input, p).size(); }, 0.5 * scale,
               2 * scale, target);
    m.values["p1"] = epsilon;
    parameter << "epsilon " << sig(epsilon / input.spacing, 3) << " sp";
  }
  else if (peer == "CGAL hierarchy_simplify") {
    // The count is set by the largest cluster size and the largest variation. Start
    // with a size cap of 4x the mean cluster size; shrink it while even the smallest
    // variation keeps too few points (flat parts split by size only), grow it while
    // even the largest variation keeps too many; then tune the variation.
    const double tolerance = kCountTolerance * static_cast<double>(target);
    unsigned size = std::max(2u, static_cast<unsigned>(std::ceil(4 * n / target)));
    const auto keptAt = [&](unsigned s, double v) {
      return static_cast<double>(hierarchySimplify(input, s, v).size());
    };
    for (int i = 0; i < 16 && size > 1 && keptAt(size, 1e-12) < target - tolerance; ++i)
      size = std::max(1u, size * 2 / 3);
    for (int i = 0; i < 12 && keptAt(size, 1.0 / 3.0) > target + tolerance; ++i)
      size *= 2;
    const double variation =
        bisect([&](double p) { return hierarchySimplify(input, size, p).size(); }, 1e-4,
               1.0 / 3.0, target, 1.0 / 3.0);
    m.values["p1"] = variation;
    m.values["p2"] = size;
    parameter << "size " << size << ", variation " << sig(variation, 3);
  }
  else
    m.error = "unknown peer " + peer;
  m.texts["parameter"] = parameter.str();
}

/** Runs a peer at its tuned parameters (a fresh child: the bisection's memory does not
 * hide this run's peak), then measures the reconstruction of what it kept. */
void
runPeer(const Input& input, const std::string& peer, const Measurement& tuned,
        Measurement& m)
{
  const double p1 = tuned.value("p1");
  Points kept;
  AlgorithmMeter meter;
  if (peer == "VoxelGrid")
    kept = voxelGrid(input, p1);
  else if (peer == "UniformSampling")
    kept = uniformSampling(input, p1);
  else if (peer == "CGAL grid_simplify")
    kept = gridSimplify(input, p1);
  else if (peer == "CGAL hierarchy_simplify")
    kept = hierarchySimplify(input, static_cast<unsigned>(tuned.value("p2")), p1);
  meter.stop(m);
  m.texts["parameter"] = tuned.text("parameter");
  recordReconstructionError(input, kept, m);
}

/** The reconstruction of all points: the error floor of every decimation. */
void
runAllPoints(const Input& input, Measurement& m)
{
  AlgorithmMeter meter;
  meter.stop(m);
  recordReconstructionError(input, input.points, m);
}

const std::vector<std::string>&
peers()
{
  static const std::vector<std::string> names = {
      "VoxelGrid", "UniformSampling", "CGAL grid_simplify", "CGAL hierarchy_simplify"};
  return names;
}

} // namespace

void
runDecimationSection(Context& context)
{
  Report& report = context.report;
  const double timeout = context.options.timeout;
  // Timed runs of ours (no quality), cached by input and rho.
  std::map<std::pair<std::string, double>, Measurement> timed;
  const auto timeOurs = [&](const Input& input, double rho) -> const Measurement& {
    const auto key = std::make_pair(input.name, rho);
    auto it = timed.find(key);
    if (it == timed.end()) {
      progress("decimation: " + input.name + " at rho " + fixed(rho, 2));
      it = timed
               .emplace(key,
                        bestOf(
                            Context::repeatsFor(input.size()),
                            [&](int, Measurement& m) { runOurs(input, rho, false, m); },
                            timeout))
               .first;
    }
    return it->second;
  };

  report.heading(2, "Decimation");
  report.paragraph("Ours: pcl::VoronoiDecimation (DECIMATE: remove the sample of "
                   "smallest r_p/h_p while "
                   "below rho; theta pi/8; rims thinned; then 10 rounds of relaxation "
                   "at the same count; "
                   "all cores). Times are of the filter alone.");

  // --- beside the paper's Table 2 -------------------------------------------------
  Table paper({"paper model", "paper before", "paper 0.3", "paper 0.4",
               "paper s 0.3/0.4", "our input", "before", "after 0.3", "after 0.4",
               "s 0.3", "s 0.4", "peak MB 0.3", "note"});
  for (const FileSpec& spec : dataFiles()) {
    if (!spec.paper_decimation || !context.selected(spec.name))
      continue;
    const Input* input = context.fileInput(spec.name);
    if (!input)
      continue;
    context.noteInput(*input);
    const PaperDecimationRow& p = *spec.paper_decimation;
    const Measurement& a = timeOurs(*input, 0.3);
    const Measurement& b = timeOurs(*input, 0.4);
    paper.add(
        {p.name, count(p.before), count(p.after_03), count(p.after_04),
         count(p.seconds_03) + " / " + count(p.seconds_04), input->name,
         count(static_cast<double>(input->unique)),
         a.ok ? count(a.value("kept")) + " (" +
                    percent(a.value("kept") / static_cast<double>(input->unique), 0) +
                    ")"
              : "failed: " + a.error,
         b.ok ? count(b.value("kept")) + " (" +
                    percent(b.value("kept") / static_cast<double>(input->unique), 0) +
                    ")"
              : "failed: " + b.error,
         seconds(a.seconds), seconds(b.seconds), sig(a.peak_mb, 3), input->note});
  }
  if (!paper.empty()) {
    report.heading(3, "Beside the paper's Table 2");
    report.paragraph(
        "The percentages are the share of the distinct input points kept. The "
        "paper's inputs were denser for MANNEQUIN, FOOT and ROCKER (see notes): "
        "denser inputs lose a larger share.");
    report.table(paper);
  }

  // --- time and memory over rho --------------------------------------------------
  Table timing({"input", "points", "rho", "kept", "s", "peak MB", "repeats"});
  double bunny_worst = kNaN;
  std::string bunny_note;
  if (context.selected("bunny"))
    if (const Input* bunny = context.fileInput("bunny")) {
      context.noteInput(*bunny);
      for (const double rho : {0.25, 0.3, 0.35, 0.4}) {
        const Measurement& m = timeOurs(*bunny, rho);
        timing.add({bunny->name, count(static_cast<double>(bunny->size())),
                    fixed(rho, 2), m.ok ? count(m.value("kept")) : "failed: " + m.error,
                    seconds(m.seconds), sig(m.peak_mb, 3), count(m.value("repeats"))});
        if (m.ok) {
          bunny_worst =
              std::isnan(bunny_worst) ? m.seconds : std::max(bunny_worst, m.seconds);
          bunny_note += (bunny_note.empty() ? "" : ", ") + fixed(rho, 2) + ": " +
                        seconds(m.seconds) + " s";
        }
      }
      if (!std::isnan(bunny_worst))
        context.setTarget("bunny decimation time",
                          "< 2 s at every rho from 0.25 to 0.4",
                          bunny_worst < 2 ? 1 : 0, bunny_note);
    }
  if (!context.options.quick && context.selected("torus-1M")) {
    const Input& torus = context.largeTorus();
    context.noteInput(torus);
    const Measurement& m = timeOurs(torus, 0.3);
    timing.add({torus.name, count(static_cast<double>(torus.size())), "0.30",
                m.ok ? count(m.value("kept")) : "failed: " + m.error,
                seconds(m.seconds), sig(m.peak_mb, 3), count(m.value("repeats"))});
    if (m.ok)
      context.setTarget("1M decimation time", "< 60 s at rho 0.3",
                        m.seconds < 60 ? 1 : 0,
                        seconds(m.seconds) + " s, peak " + sig(m.peak_mb, 3) +
                            " MB, kept " + count(m.value("kept")));
  }
  if (!timing.empty()) {
    report.heading(3, "Time and memory");
    report.table(timing);
  }

  // --- equal counts: reconstruction error ---------------------------------------
  std::vector<const Input*> inputs;
  if (context.selected("bunny"))
    if (const Input* bunny = context.fileInput("bunny"))
      inputs.push_back(bunny);
  for (const GeneratedShape& g : generatedShapes())
    if (context.selected(generatedName(g.name, 10000)))
      inputs.push_back(&context.generated(g.name, 10000));

  report.heading(3, "Reconstruction error at equal point counts");
  report.paragraph(
      "For each rho, ours keeps K points; each peer's parameter is tuned by bisection to "
      "the count closest to K that its parameter reaches (VoxelGrid: leaf size, it outputs "
      "voxel centroids, i.e. moved "
      "points; UniformSampling: radius, it keeps the input point nearest each voxel centre; "
      "CGAL grid_simplify_point_set: cell size; CGAL hierarchy_simplify_point_set: largest "
      "variation, with the cluster size capped at 4 n / K). The kept points are then "
      "reconstructed with CoconeReconstruction (default parameters) and the mesh is "
      "compared with the reference surface: H = two-sided Hausdorff distance, mean = mean "
      "of the two one-sided mean distances, both in mean spacings of the full input. "
      "'all points' is the reconstruction of the undecimated input (the floor). Bold: the "
      "smallest H and the smallest mean of the row group. Times are of the filter at the "
      "tuned parameter (single runs).");
  Table table({"input", "rho", "method", "kept", "parameter", "s", "peak MB",
               "triangles", "loops", "H", "mean"});
  std::size_t cases = 0, h_wins = 0, mean_wins = 0;
  std::vector<std::string> h_losses, mean_losses;
  for (const Input* input : inputs) {
    context.noteInput(*input);
    progress("decimation quality: " + input->name);
    const Measurement all =
        runIsolated([&](Measurement& m) { runAllPoints(*input, m); }, timeout);
    table.add({input->name, "-", "all points",
               count(static_cast<double>(input->size())), "", "", "",
               count(all.value("triangles")), count(all.value("loops")),
               sig(all.value("d_hausdorff"), 2), sig(all.value("d_mean"), 2)});
    for (const double rho : {0.3, 0.4}) {
      struct Row
      {
        std::string method;
        Measurement m;
        // Ours and the peers are ranked (bold for the best); DECIMATE as published is
        // shown beside them only.
        enum class Role
        {
          ours,
          shown,
          peer
        } role = Role::peer;
        bool
        ranked() const
        {
          return role != Role::shown;
        }
      };
      std::vector<Row> rows;
      rows.push_back(
          {"VoronoiDecimation (ours)",
           runIsolated([&](Measurement& m) { runOurs(*input, rho, true, m); }, timeout),
           Row::Role::ours});
      if (!rows.front().m.ok) {
        table.add({input->name, fixed(rho, 1), rows.front().method,
                   "failed: " + rows.front().m.error});
        continue;
      }
      const auto target = static_cast<std::size_t>(rows.front().m.value("kept"));
      // Without relaxation (the same count) and DECIMATE as published (rims kept
      // dense: shown unless closed, at its own count): shown, compared with nothing.
      rows.push_back(
          {"ours without relaxation",
           runIsolated(
               [&](Measurement& m) { runOurs(*input, rho, true, m, false, false); },
               timeout),
           Row::Role::shown});
      if (input->closed != 1)
        rows.push_back(
            {"ours as published (rims kept)",
             runIsolated([&](Measurement& m) { runOurs(*input, rho, true, m, true); },
                         timeout),
             Row::Role::shown});
      for (const std::string& peer : peers()) {
        const Measurement tuned = runIsolated(
            [&](Measurement& m) { tunePeer(*input, peer, target, m); }, timeout);
        if (!tuned.ok) {
          rows.push_back({peer, tuned});
          continue;
        }
        rows.push_back(
            {peer, runIsolated([&](Measurement& m) { runPeer(*input, peer, tuned, m); },
                               timeout)});
      }
      double best_h = std::numeric_limits<double>::infinity(), best_mean = best_h;
      for (const Row& r : rows)
        if (r.m.ok && r.ranked()) {
          if (!std::isnan(r.m.value("d_hausdorff")))
            best_h = std::min(best_h, r.m.value("d_hausdorff"));
          if (!std::isnan(r.m.value("d_mean")))
            best_mean = std::min(best_mean, r.m.value("d_mean"));
        }
      for (const Row& r : rows) {
        if (!r.m.ok) {
          table.add({input->name, fixed(rho, 1), r.method, "failed: " + r.m.error});
          continue;
        }
        const double h = r.m.value("d_hausdorff"), mean = r.m.value("d_mean");
        const double kept = r.m.value("kept");
        std::string kept_text = count(kept);
        if (r.role == Row::Role::peer)
          kept_text += " (" + (kept >= target ? std::string("+") : std::string("")) +
                       percent(kept / static_cast<double>(target) - 1, 1) + ")";
        table.add({input->name, fixed(rho, 1), r.method, kept_text,
                   &r == &rows.front() ? "rho " + fixed(rho, 1) : r.m.text("parameter"),
                   seconds(r.m.seconds), sig(r.m.peak_mb, 3),
                   count(r.m.value("triangles")), count(r.m.value("loops")),
                   h == best_h && r.ranked() ? "**" + sig(h, 2) + "**" : sig(h, 2),
                   mean == best_mean && r.ranked() ? "**" + sig(mean, 2) + "**"
                                                   : sig(mean, 2)});
      }
      // Ours against every peer that kept a comparable count.
      ++cases;
      const Measurement& ours = rows.front().m;
      bool h_ok = true, mean_ok = true;
      std::string h_who, mean_who;
      for (std::size_t i = 1; i < rows.size(); ++i) {
        const Measurement& peer = rows[i].m;
        if (!peer.ok || rows[i].role != Row::Role::peer)
          continue;
        if (!(ours.value("d_hausdorff") < peer.value("d_hausdorff"))) {
          h_ok = false;
          h_who += (h_who.empty() ? "" : "/") + rows[i].method;
        }
        if (!(ours.value("d_mean") < peer.value("d_mean"))) {
          mean_ok = false;
          mean_who += (mean_who.empty() ? "" : "/") + rows[i].method;
        }
      }
      const std::string label = input->name + " " + fixed(rho, 1);
      if (h_ok)
        ++h_wins;
      else
        h_losses.push_back(label + " (" + h_who + ")");
      if (mean_ok)
        ++mean_wins;
      else
        mean_losses.push_back(label + " (" + mean_who + ")");
    }
  }
  if (!table.empty())
    report.table(table);
  if (cases > 0) {
    const auto join = [](const std::vector<std::string>& items) {
      std::string s;
      for (const std::string& x : items)
        s += (s.empty() ? "" : "; ") + x;
      return s;
    };
    context.setTarget(
        "decimation error (Hausdorff)",
        "smaller two-sided Hausdorff error of the reconstruction than every "
        "peer filter at equal counts (bunny, generated shapes, rho 0.3 and 0.4)",
        h_wins == cases ? 1 : 0,
        "ours smallest in " + std::to_string(h_wins) + " of " + std::to_string(cases) +
            " cases" + (h_losses.empty() ? "" : "; not on: " + join(h_losses)));
    context.setTarget(
        "decimation error (mean)",
        "smaller mean two-sided error than every peer filter at equal counts",
        mean_wins == cases ? 1 : 0,
        "ours smallest in " + std::to_string(mean_wins) + " of " +
            std::to_string(cases) + " cases" +
            (mean_losses.empty() ? "" : "; not on: " + join(mean_losses)));
  }
}

} // namespace bench
} // namespace cocone
} // namespace pcl
