// SPDX-License-Identifier: GPL-3.0-or-later
// VoronoiCocone (core/voronoi_cocone.h): the Delaunay triangulation of the samples, its
// per-sample geometry (cell_geometry.cpp) and the queries on what it keeps.
#include "common/parallel.h"
#include "common/progress.h"
#include "common/status_guard.h"
#include "voronoi/cell_geometry.h"
#include "voronoi/cgal_delaunay.h"
#include "voronoi/voronoi_cocone_impl.h"

#include <pcl/cocone/core/denoise.h>
#include <pcl/cocone/parameters.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace pcl {
namespace cocone {

// ---------------------------------------------------------------------------------
using namespace detail;

VoronoiCocone::VoronoiCocone(const VoronoiParameters& parameters)
  : impl_(new Impl), parameters_(parameters)
{}
VoronoiCocone::~VoronoiCocone() = default;
VoronoiCocone::VoronoiCocone(VoronoiCocone&&) noexcept = default;
VoronoiCocone& VoronoiCocone::operator=(VoronoiCocone&&) noexcept = default;

Status
VoronoiCocone::setCoconeAngle(double theta)
{
  if (!kCoconeAngleRange.contains(theta))
    return Status::invalid_parameter;
  parameters_.cocone_angle = theta;
  return Status::ok;
}

double
VoronoiCocone::getCoconeAngle() const
{
  return parameters_.cocone_angle;
}

void
VoronoiCocone::setNumberOfThreads(unsigned threads)
{
  parameters_.threads = threads;
}

unsigned
VoronoiCocone::getNumberOfThreads() const
{
  return parameters_.threads;
}

const VoronoiCocone::Timings&
VoronoiCocone::timings() const
{
  return impl_->timings;
}

Status
VoronoiCocone::status() const
{
  return impl_->status;
}

const std::string&
VoronoiCocone::errorMessage() const
{
  return impl_->message;
}

std::size_t
VoronoiCocone::size() const
{
  return impl_->representative.size();
}

std::size_t
VoronoiCocone::numUniqueSamples() const
{
  return impl_->unique_count;
}

SampleIndex
VoronoiCocone::representative(SampleIndex i) const
{
  return impl_->representative[i];
}

double
VoronoiCocone::typicalSpacing() const
{
  const DiagramState& d = *impl_;
  if (d.stars.empty() || d.unique_count == 0)
    return 0;
  constexpr std::size_t kProbes = 1024;
  const std::size_t n = d.representative.size();
  const std::size_t stride = std::max<std::size_t>(1, n / kProbes);
  SampleMarks seen;
  std::vector<SampleIndex> neighbours;
  std::vector<double> nearest;
  for (std::size_t i = 0; i < n; i += stride) {
    const SampleIndex s = d.representative[i];
    neighbours.clear();
    d.stars.appendNeighbours(s, seen, neighbours);
    double best = std::numeric_limits<double>::infinity();
    for (const SampleIndex q : neighbours)
      best = std::min(best, (d.centered[q] - d.centered[s]).squaredNorm());
    if (std::isfinite(best))
      nearest.push_back(best);
  }
  if (nearest.empty())
    return 0;
  const auto middle = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), middle, nearest.end());
  return std::sqrt(*middle);
}

const std::vector<Eigen::Vector3d>&
VoronoiCocone::centeredPoints() const
{
  return impl_->centered;
}

const std::vector<Eigen::Vector3d>&
VoronoiCocone::centeredInputPoints() const
{
  return impl_->input_centered.empty() ? impl_->centered : impl_->input_centered;
}

bool
VoronoiCocone::denoised() const
{
  return !impl_->input_centered.empty();
}

const NoiseEstimate&
VoronoiCocone::noiseEstimate() const
{
  return impl_->noise;
}

unsigned
VoronoiCocone::smoothingRounds() const
{
  return impl_->smoothing_rounds;
}

void
VoronoiCocone::setDenoise(DenoiseMode mode)
{
  parameters_.denoise = mode;
}

DenoiseMode
VoronoiCocone::getDenoise() const
{
  return parameters_.denoise;
}

const Eigen::Vector3d&
VoronoiCocone::offset() const
{
  return impl_->offset;
}

const Eigen::Vector3d&
VoronoiCocone::poleVector(SampleIndex i) const
{
  return impl_->pole_vector[impl_->representative[i]];
}

bool
VoronoiCocone::positivePoleAtInfinity(SampleIndex i) const
{
  return impl_->unbounded[impl_->representative[i]] != 0;
}

Eigen::Vector3d
VoronoiCocone::positivePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (impl_->unbounded[r])
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  return impl_->positive_pole[r] + impl_->offset;
}

Eigen::Vector3d
VoronoiCocone::negativePole(SampleIndex i) const
{
  const SampleIndex r = impl_->representative[i];
  if (!(impl_->height[r] > 0))
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return impl_->negative_pole[r] + impl_->offset;
}

double
VoronoiCocone::height(SampleIndex i) const
{
  return impl_->height[impl_->representative[i]];
}

double
VoronoiCocone::coconeRadius(SampleIndex i) const
{
  return impl_->radius[impl_->representative[i]];
}

double
VoronoiCocone::ratio(SampleIndex i) const
{
  return impl_->ratio(impl_->representative[i]);
}

const std::vector<MarkedTriangle>&
VoronoiCocone::markedTriangles() const
{
  return impl_->triangles;
}

IndexRange
VoronoiCocone::trianglesAround(SampleIndex i) const
{
  if (impl_->triangle_offsets.empty())
    return {};
  const SampleIndex r = impl_->representative[i];
  const std::uint32_t* base = impl_->triangle_ids.data();
  return {base + impl_->triangle_offsets[r], base + impl_->triangle_offsets[r + 1]};
}

void
VoronoiCocone::coconeNeighbours(SampleIndex i,
                                std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  const SampleIndex r = impl_->representative[i];
  for (const std::uint32_t t : trianglesAround(r)) {
    const MarkedTriangle& triangle = impl_->triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (triangle.vertex[k] != r || !triangle.isMarkedBy(k))
        continue;
      for (int other = 0; other < 3; ++other)
        if (other != k)
          neighbours.push_back(triangle.vertex[other]);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
}

void
VoronoiCocone::delaunayNeighbours(SampleIndex i,
                                  std::vector<SampleIndex>& neighbours) const
{
  neighbours.clear();
  if (impl_->stars.empty())
    return;
  // Several threads may ask at once: per-thread scratch, which stops allocating after
  // a thread's first calls.
  thread_local SampleMarks seen;
  impl_->stars.appendNeighbours(impl_->representative[i], seen, neighbours);
  std::sort(neighbours.begin(), neighbours.end());
}

void
VoronoiCocone::delaunayTrianglesAmong(
    const std::vector<SampleIndex>& samples,
    std::vector<std::array<SampleIndex, 3>>& triangles) const
{
  triangles.clear();
  const DelaunayStars& stars = impl_->stars;
  if (stars.empty())
    return;
  // Several threads may ask at once (one hole each): per-thread scratch.
  thread_local SampleMarks is_member;
  thread_local std::vector<SampleIndex> members;
  members.clear();
  is_member.clear();
  for (const SampleIndex s : samples)
    if (is_member.mark(impl_->representative[s]))
      members.push_back(impl_->representative[s]);
  // kNoSample (the infinite vertex) is never marked.
  for (const SampleIndex s : members) {
    for (std::uint32_t k = stars.offsets[s]; k < stars.offsets[s + 1]; ++k) {
      const std::array<SampleIndex, 4>& cell = stars.cell_samples[stars.cells[k]];
      // Most cells at a hole's rim have only s and one other member: no facet of
      // three members, told without looking at the facets.
      int in_cell = 0;
      for (const SampleIndex w : cell)
        in_cell += is_member.isMarked(w);
      if (in_cell < 3)
        continue;
      for (int i = 0; i < 4; ++i) {
        if (cell[i] == s)
          continue; // the facet opposite s does not contain it
        std::array<SampleIndex, 3> t;
        int m = 0;
        bool keep = true;
        for (int j = 0; j < 4 && keep; ++j) {
          if (j == i)
            continue;
          if (!is_member.isMarked(cell[j]))
            keep = false;
          else
            t[m++] = cell[j];
        }
        // Report each triangle from its smallest vertex; it lies in two cells, so the
        // repeats go after sorting.
        if (!keep)
          continue;
        std::sort(t.begin(), t.end());
        if (t[0] == s)
          triangles.push_back(t);
      }
    }
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
}

namespace {

/** compute() without its outer guard: each stage that allocates much runs in a guard of
 * its own, whose message names it. */
Status
buildDiagram(DiagramState& d, const VoronoiParameters& parameters,
             const std::vector<Eigen::Vector3d>& points,
             const ProgressCallback& callback)
{
  // The triangulation takes about three quarters of compute(), the geometry the rest.
  const StageProgress progress(callback, 0, 1);
  const StageProgress triangulation = progress.part(0, 0.75);
  d = DiagramState();
  const auto fail = [&](Status status, const std::string& message) {
    DiagramState fresh;
    fresh.status = status;
    fresh.message = message;
    d = std::move(fresh);
    return status;
  };

  if (!isValid(parameters))
    return fail(Status::invalid_parameter,
                "the cocone angle " + std::to_string(parameters.cocone_angle) +
                    " is outside " + kCoconeAngleRange.text());
  const std::size_t n = points.size();
  if (n >= static_cast<std::size_t>(kNoSample))
    return fail(Status::too_many_points,
                "more points than 32-bit sample indices address");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      std::ostringstream message;
      message << "point " << i << " has a non-finite coordinate";
      return fail(Status::non_finite_input, message.str());
    }
    sum += points[i];
  }
  if (n < 4)
    return fail(Status::too_few_points,
                "need at least 4 points for a 3D Voronoi diagram, got " +
                    std::to_string(n));
  // Decide the dimension on the points as given, with exact predicates: translating
  // them to their centroid rounds each coordinate, which can lift exactly coplanar
  // points off their plane by 1e-15 and hide the degeneracy from the triangulation.
  {
    const auto at = [&](std::size_t i) {
      return Point(points[i].x(), points[i].y(), points[i].z());
    };
    std::size_t second = 1, third = 0, fourth = 0;
    while (second < n && at(second) == at(0))
      ++second;
    for (std::size_t i = second + 1; i < n && third == 0; ++i)
      if (!CGAL::collinear(at(0), at(second), at(i)))
        third = i;
    for (std::size_t i = third + 1; third != 0 && i < n && fourth == 0; ++i)
      if (CGAL::orientation(at(0), at(second), at(third), at(i)) != CGAL::COPLANAR)
        fourth = i;
    if (second == n)
      return fail(Status::too_few_points, "need at least 4 distinct points, got 1");
    if (third == 0)
      return fail(Status::degenerate_dimension,
                  "all points are collinear: no 3D Voronoi cell to measure");
    if (fourth == 0)
      return fail(Status::degenerate_dimension,
                  "all points are coplanar: no 3D Voronoi cell to measure");
  }

  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  // Scanner noise (core/denoise.h): the diagram of a noisy cloud is built on a smoothed
  // copy, while every result stays indexed by the samples as given.
  const Clock::time_point denoise_start = Clock::now();
  std::vector<Eigen::Vector3d> smoothed;
  if (parameters.denoise != DenoiseMode::off) {
    std::string denoise_message;
    const Status denoise_status =
        runGuarded("the noise handling", &denoise_message, [&] {
          d.noise = estimateNoise(points, parameters.threads);
          if (parameters.denoise == DenoiseMode::on ||
              d.noise.relative_noise > kNoiseThreshold) {
            SmoothedSamples copy = smoothSamples(points, parameters.threads);
            d.smoothing_rounds = copy.rounds;
            smoothed = std::move(copy.points);
          }
          return Status::ok;
        });
    if (denoise_status != Status::ok)
      return fail(denoise_status, denoise_message);
  }
  const bool denoised = !smoothed.empty();
  const std::vector<Eigen::Vector3d>& geometry = denoised ? smoothed : points;
  d.timings.denoise = seconds_since(denoise_start);
  if (parameters.denoise != DenoiseMode::off)
    PCL_DEBUG(
        "[pcl::cocone::VoronoiCocone::compute] noise %.4f spacings (threshold %g): "
        "%s, %u smoothing rounds, %.3f s\n",
        d.noise.relative_noise, kNoiseThreshold, denoised ? "smoothed" : "as given",
        d.smoothing_rounds, d.timings.denoise);

  const Clock::time_point start = Clock::now();
  // The triangulation lives only through compute(): the geometry keeps what the
  // queries after it read (Impl::stars) and frees it.
  Delaunay dt;
  std::string message;
  Status status = runGuarded("the Delaunay triangulation", &message, [&] {
    runInArena(parameters.threads, [&] {
      d.offset = sum / static_cast<double>(n);
      d.centered.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        d.centered[i] = geometry[i] - d.offset;
      if (denoised) {
        d.input_centered.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          d.input_centered[i] = points[i] - d.offset;
      }

      // Insert in CGAL's spatial order (a Hilbert curve on random rounds), far faster
      // than input order. This is CGAL's own bulk insertion of points with info, with
      // the sort run on every core: the same order, hence the same triangulation.
      {
        std::vector<Point> input(n);
        for (std::size_t i = 0; i < n; ++i)
          input[i] = Point(d.centered[i].x(), d.centered[i].y(), d.centered[i].z());
        std::vector<std::size_t> order(n);
        std::iota(order.begin(), order.end(), std::size_t(0));
        using SortTraits = CGAL::Spatial_sort_traits_adapter_3<
            Kernel, CGAL::Pointer_property_map<Point>::type>;
        CGAL::spatial_sort<CGAL::Parallel_if_available_tag>(
            order.begin(), order.end(), SortTraits(CGAL::make_property_map(input)));
        VertexHandle hint;
        std::size_t inserted = 0;
        for (const std::size_t i : order) {
          hint = dt.insert(input[i], hint);
          if (hint != VertexHandle())
            hint->info() = static_cast<SampleIndex>(i);
          if ((++inserted & 0xffffu) == 0)
            triangulation.report(double(inserted) / double(n));
        }
      }

      // Identical points collapse into one vertex. Map every input point to the
      // smallest index of its group, so nothing is lost or renumbered.
      std::vector<VertexHandle> owner(n);
      for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        owner[v->info()] = v;
      d.unique_count = dt.number_of_vertices();
      Delaunay::Cell_handle hint;
      for (std::size_t i = 0; i < n; ++i) {
        if (owner[i] != VertexHandle())
          continue;
        Delaunay::Locate_type type;
        int li, lj;
        const Point query(d.centered[i].x(), d.centered[i].y(), d.centered[i].z());
        hint = dt.locate(query, type, li, lj, hint);
        if (type != Delaunay::VERTEX)
          throw std::runtime_error(
              "a point missing from the triangulation is no vertex");
        owner[i] = hint->vertex(li);
        // CGAL kept whichever copy its spatial sort met first; name the group after
        // its smallest index instead.
        owner[i]->info() =
            std::min<SampleIndex>(owner[i]->info(), static_cast<SampleIndex>(i));
      }
      d.representative.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        d.representative[i] = owner[i]->info();
    });
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);

  if (d.unique_count < 4)
    return fail(Status::too_few_points, "need at least 4 distinct points, got " +
                                            std::to_string(d.unique_count));
  if (dt.dimension() < 3) {
    const int dim = dt.dimension();
    return fail(Status::degenerate_dimension,
                std::string("all points are ") + (dim == 2 ? "coplanar" : "collinear") +
                    ": no 3D Voronoi cell to measure");
  }

  d.timings.delaunay = seconds_since(start);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] Delaunay triangulation of %zu samples (%zu "
            "distinct): %.3f s\n",
            n, d.unique_count, d.timings.delaunay);
  const Clock::time_point geometry_start = Clock::now();
  status = runGuarded("the Voronoi geometry", &message, [&] {
    progress.report(0.75);
    runInArena(parameters.threads,
               [&] { computeGeometry(dt, d, std::sin(parameters.cocone_angle)); });
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  d.timings.geometry = seconds_since(geometry_start);
  PCL_DEBUG("[pcl::cocone::VoronoiCocone] poles, radii and cocone marks: %.3f s, %zu "
            "marked triangles\n",
            d.timings.geometry, d.triangles.size());
  status = runGuarded("the Voronoi geometry", &message, [&] {
    progress.report(1);
    return Status::ok;
  });
  if (status != Status::ok)
    return fail(status, message);
  d.status = Status::ok;
  d.message.clear();
  return Status::ok;
}

} // namespace

Status
VoronoiCocone::compute(const std::vector<Eigen::Vector3d>& points,
                       const ProgressCallback& progress)
{
  std::string message;
  const Status status = runGuarded("building the diagram", &message, [&] {
    return buildDiagram(*impl_, parameters_, points, progress);
  });
  if (impl_->status != status) {
    // Something failed after the stages' own guards: forget the half-built diagram.
    *impl_ = Impl();
    impl_->status = status;
    impl_->message = std::move(message);
  }
  return status;
}

} // namespace cocone
} // namespace pcl
