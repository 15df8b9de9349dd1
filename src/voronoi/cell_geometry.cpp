// SPDX-License-Identifier: GPL-3.0-or-later
// The per-sample Voronoi geometry of the diagram (section 2 of the paper): poles, pole
// vectors, heights, cocone radii and cocone marks, read from CGAL's triangulation into
// flat arrays, which then replace it.
#include "voronoi/cell_geometry.h"

#include "voronoi/cocone_edge.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

/** The circumcenter of a finite cell (its Voronoi vertex). */
Eigen::Vector3d
circumcenter(CellHandle c)
{
  const Point center = CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                                          c->vertex(2)->point(), c->vertex(3)->point());
  return {center.x(), center.y(), center.z()};
}

/** The triangulation as flat arrays by cell number, finite cells first and the
 * infinite ones after them. The per-sample pass reads these instead of CGAL's cells,
 * which lie scattered in memory: cache misses on cell handles dominated the pass. */
struct CellTable
{
  std::vector<std::array<SampleIndex, 4>> samples; // kNoSample: the infinite vertex
  std::vector<std::array<std::uint32_t, 4>> neighbours; // the cell across facet i
  std::vector<Eigen::Vector3d> centers; // circumcenters of the finite cells
  std::size_t finite = 0;

  bool
  isFinite(std::uint32_t k) const
  {
    return k < finite;
  }

  /** The position of sample \a s (or kNoSample) in cell \a k; the cell has it. */
  int
  indexOf(std::uint32_t k, SampleIndex s) const
  {
    const std::array<SampleIndex, 4>& v = samples[k];
    assert(v[0] == s || v[1] == s || v[2] == s || v[3] == s);
    return v[0] == s ? 0 : v[1] == s ? 1 : v[2] == s ? 2 : 3;
  }

  /** The facet of cell \a k shared with its neighbour \a n. */
  int
  facetTowards(std::uint32_t k, std::uint32_t n) const
  {
    const std::array<std::uint32_t, 4>& c = neighbours[k];
    assert(c[0] == n || c[1] == n || c[2] == n || c[3] == n);
    return c[0] == n ? 0 : c[1] == n ? 1 : c[2] == n ? 2 : 3;
  }
};

/** What one pass over a vertex's Voronoi cell produces. */
struct CellGeometry
{
  Eigen::Vector3d pole_vector = Eigen::Vector3d::Zero();
  Eigen::Vector3d positive_pole = Eigen::Vector3d::Zero(); // centered frame
  Eigen::Vector3d negative_pole = Eigen::Vector3d::Zero(); // centered frame
  bool unbounded = false;
  double height = 0; // NaN without a negative pole
};

/** Unit outward normal of the convex-hull facet i of the finite cell k, whose
 * neighbour across it is infinite. */
Eigen::Vector3d
hullFacetNormal(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
                std::uint32_t k, int i)
{
  const std::array<SampleIndex, 4>& v = cells.samples[k];
  const Eigen::Vector3d& a = points[v[(i + 1) & 3]];
  const Eigen::Vector3d& b = points[v[(i + 2) & 3]];
  const Eigen::Vector3d& d = points[v[(i + 3) & 3]];
  Eigen::Vector3d normal = (b - a).cross(d - a);
  // Outward: away from the vertex of k opposite the facet.
  if (normal.dot(points[v[i]] - a) > 0)
    normal = -normal;
  const double length = normal.norm();
  return length > 0 ? Eigen::Vector3d(normal / length) : normal;
}

/** The poles, pole vector and height of the cell of sample \a s, from the cells of its
 * star. */
void
computePoles(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
             SampleIndex s, const std::uint32_t* star_begin,
             const std::uint32_t* star_end, CellGeometry& geometry)
{
  const Eigen::Vector3d& p = points[s];
  Eigen::Vector3d hull_normal_sum = Eigen::Vector3d::Zero();
  double farthest2 = -1;
  geometry.unbounded = false;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c)) {
      // The finite facet of an infinite cell is a convex-hull triangle at p.
      geometry.unbounded = true;
      const std::uint32_t inside = cells.neighbours[*c][cells.indexOf(*c, kNoSample)];
      hull_normal_sum +=
          hullFacetNormal(cells, points, inside, cells.facetTowards(inside, *c));
      continue;
    }
    const double d2 = (cells.centers[*c] - p).squaredNorm();
    if (d2 > farthest2) {
      farthest2 = d2;
      geometry.positive_pole = cells.centers[*c];
    }
  }
  if (geometry.unbounded) {
    const double length = hull_normal_sum.norm();
    if (length > 1e-12)
      geometry.pole_vector = hull_normal_sum / length;
    else if (farthest2 > 0) // opposite hull normals cancel: fall back to the far vertex
      geometry.pole_vector = (geometry.positive_pole - p).normalized();
    else
      geometry.pole_vector = Eigen::Vector3d::UnitZ();
    geometry.positive_pole.setConstant(std::numeric_limits<double>::infinity());
  }
  else {
    geometry.pole_vector = (geometry.positive_pole - p).normalized();
  }

  double negative2 = -1;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c))
      continue;
    const Eigen::Vector3d to_center = cells.centers[*c] - p;
    if (to_center.dot(geometry.pole_vector) >= 0)
      continue;
    const double d2 = to_center.squaredNorm();
    if (d2 > negative2) {
      negative2 = d2;
      geometry.negative_pole = to_center + p;
    }
  }
  // The geometry is reused from sample to sample: leave no stale pole behind.
  if (!(negative2 > 0))
    geometry.negative_pole.setConstant(std::numeric_limits<double>::quiet_NaN());
  geometry.height =
      negative2 > 0 ? std::sqrt(negative2) : std::numeric_limits<double>::quiet_NaN();
}

/** The cocone radius of sample \a s for the unit axis \a axis. Every Voronoi edge of
 * its cell is the dual of a Delaunay facet (c, i) of the star; each is visited once,
 * from its finite cell or from the cell of lower number (not address: the edge is
 * clipped from that side, and the rounding must not change from run to run). An edge
 * that meets the cocone marks the facet: bit i of marks[c][position of s in c]. */
double
computeCoconeRadius(const CellTable& cells, const std::vector<Eigen::Vector3d>& points,
                    SampleIndex s, const std::uint32_t* star_begin,
                    const std::uint32_t* star_end, const Eigen::Vector3d& axis,
                    double sin_theta, std::vector<std::array<std::uint8_t, 4>>& marks)
{
  const Eigen::Vector3d& p = points[s];
  double radius2 = 0;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c))
      continue; // its finite facet at s is visited from the finite side
    const int self = cells.indexOf(*c, s);
    for (int i = 0; i < 4; ++i) {
      if (i == self)
        continue; // the facet opposite s does not contain s
      const std::uint32_t n = cells.neighbours[*c][i];
      const bool ray = !cells.isFinite(n);
      if (!ray && n < *c)
        continue; // visited from n
      const Eigen::Vector3d start = cells.centers[*c] - p;
      const Eigen::Vector3d direction =
          ray ? hullFacetNormal(cells, points, *c, i)
              : Eigen::Vector3d(cells.centers[n] - p - start);
      const EdgeInCocone clip = clipVoronoiEdge(start, direction, ray, axis, sin_theta);
      if (!clip.meets)
        continue;
      marks[*c][self] |= static_cast<std::uint8_t>(1u << i);
      if (clip.unbounded)
        radius2 = std::numeric_limits<double>::infinity();
      else if (clip.max_distance2 > radius2)
        radius2 = clip.max_distance2;
    }
  }
  return std::sqrt(radius2);
}

} // namespace

/** Circumcenters, poles, heights, radii and cocone marks of every sample, and the
 * marked triangles with their incidence lists. Clears \a dt once its cells are read. */
void
computeGeometry(Delaunay& dt, DiagramState& d, double sin_theta)
{
  const std::size_t n = d.representative.size();

  // Number the cells: the finite ones in container order, then the infinite ones.
  // One pass: touching every cell is what costs at a million points.
  std::vector<CellHandle> all_cells, infinite_cells;
  all_cells.reserve(dt.number_of_cells());
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    if (dt.is_infinite(c)) {
      infinite_cells.push_back(c);
      continue;
    }
    c->cellIndex() = static_cast<std::uint32_t>(all_cells.size());
    all_cells.push_back(c);
  }
  const std::size_t finite_cells = all_cells.size();
  for (const CellHandle c : infinite_cells) {
    c->cellIndex() = static_cast<std::uint32_t>(all_cells.size());
    all_cells.push_back(c);
  }
  std::vector<CellHandle>().swap(infinite_cells);

  // The samples in the triangulation's vertex order, which is its insertion order, a
  // spatial one: neighbouring samples share the cells of their stars.
  std::vector<SampleIndex> samples_in_order;
  samples_in_order.reserve(d.unique_count);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    samples_in_order.push_back(v->info());

  // The star of every vertex at once (cells by sample, infinite cells after the
  // finite ones): passes over the cells instead of a search per vertex, which measured
  // twice as slow. The samples, neighbours and circumcenter of every cell are read
  // once, in parallel, so that these passes and the per-sample one scan flat arrays.
  CellTable cells;
  cells.finite = finite_cells;
  cells.centers.resize(finite_cells);
  cells.samples.resize(all_cells.size());
  cells.neighbours.resize(all_cells.size());
  const VertexHandle infinite = dt.infinite_vertex();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, all_cells.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const CellHandle c = all_cells[k];
                        for (int j = 0; j < 4; ++j) {
                          const VertexHandle v = c->vertex(j);
                          cells.samples[k][j] = v == infinite ? kNoSample : v->info();
                          cells.neighbours[k][j] = c->neighbor(j)->cellIndex();
                        }
                        if (k < finite_cells)
                          cells.centers[k] = circumcenter(c);
                      }
                    });
  // The table holds all that is read from here on: CGAL's triangulation, the largest
  // structure of the whole run, goes before the star lists are made.
  std::vector<CellHandle>().swap(all_cells);
  dt.clear();
  // Star lists in cell order, filled by a few blocks of cells at once: each block
  // counts its cells per sample, so it knows where in each list its own cells go.
  constexpr std::size_t kBlocks = 4;
  const std::size_t block_size = (cells.samples.size() + kBlocks - 1) / kBlocks;
  // Block b of the cells [0, count).
  const auto blockRange = [&](std::size_t b, std::size_t count) {
    return std::make_pair(std::min(b * block_size, count),
                          std::min((b + 1) * block_size, count));
  };
  std::vector<std::vector<std::uint32_t>> cursor(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    cursor[b].assign(n, 0);
    const auto [first, last] = blockRange(b, cells.samples.size());
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : cells.samples[k])
        if (s != kNoSample)
          ++cursor[b][s];
  });
  std::vector<std::uint32_t> star_offsets(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t at = star_offsets[i];
    for (std::size_t b = 0; b < kBlocks; ++b) // counts -> where block b starts
      at += std::exchange(cursor[b][i], at);
    star_offsets[i + 1] = at;
  }
  std::vector<std::uint32_t> star_cells(star_offsets[n]);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    const auto [first, last] = blockRange(b, cells.samples.size());
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : cells.samples[k])
        if (s != kNoSample)
          star_cells[cursor[b][s]++] = static_cast<std::uint32_t>(k);
  });
  std::vector<std::vector<std::uint32_t>>().swap(cursor);

  d.pole_vector.assign(n, Eigen::Vector3d::Zero());
  d.positive_pole.assign(n, Eigen::Vector3d::Zero());
  d.negative_pole.assign(n, Eigen::Vector3d::Zero());
  d.height.assign(n, std::numeric_limits<double>::quiet_NaN());
  d.radius.assign(n, std::numeric_limits<double>::quiet_NaN());
  d.unbounded.assign(n, 0);

  // marks[c][j] bit i: vertex j of cell c marks facet i of c. Only the thread handling
  // vertex j writes that byte, so no synchronisation is needed.
  std::vector<std::array<std::uint8_t, 4>> marks(finite_cells, {0, 0, 0, 0});
  const std::vector<Eigen::Vector3d>& points = d.centered; // the vertices' coordinates
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, samples_in_order.size(), 512),
      [&](const tbb::blocked_range<std::size_t>& range) {
        CellGeometry geometry;
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const SampleIndex s = samples_in_order[k];
          const std::uint32_t* star_begin = star_cells.data() + star_offsets[s];
          const std::uint32_t* star_end = star_cells.data() + star_offsets[s + 1];
          computePoles(cells, points, s, star_begin, star_end, geometry);
          d.pole_vector[s] = geometry.pole_vector;
          d.positive_pole[s] = geometry.positive_pole;
          d.negative_pole[s] = geometry.negative_pole;
          d.height[s] = geometry.height;
          d.unbounded[s] = geometry.unbounded ? 1 : 0;
          d.radius[s] = computeCoconeRadius(cells, points, s, star_begin, star_end,
                                            geometry.pole_vector, sin_theta, marks);
        }
      });

  // Collect the marked triangles, each from the cell that owns its facet (the same
  // rule computeCoconeRadius uses), in cell order: deterministic.
  // Most facets are marked by none of their vertices: those are skipped on the marks
  // alone, before their neighbouring cell is looked up. Blocks of cells in parallel,
  // joined in cell order.
  std::vector<std::vector<MarkedTriangle>> found(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    const auto [first, last] = blockRange(b, finite_cells);
    for (std::size_t k = first; k < last; ++k)
      for (int i = 0; i < 4; ++i) {
        MarkedTriangle triangle;
        triangle.marked_by = 0;
        for (int m = 0; m < 3; ++m) {
          const int j = (i + 1 + m) & 3;
          triangle.vertex[m] = cells.samples[k][j];
          if ((marks[k][j] >> i) & 1u)
            triangle.marked_by |= static_cast<std::uint8_t>(1u << m);
        }
        if (triangle.marked_by == 0)
          continue;
        const std::uint32_t nb = cells.neighbours[k][i];
        if (cells.isFinite(nb) && nb < k)
          continue;
        found[b].push_back(triangle);
      }
  });
  d.triangles.clear();
  std::size_t total = 0;
  for (const std::vector<MarkedTriangle>& block : found)
    total += block.size();
  d.triangles.reserve(total);
  for (std::vector<MarkedTriangle>& block : found) {
    d.triangles.insert(d.triangles.end(), block.begin(), block.end());
    std::vector<MarkedTriangle>().swap(block);
  }

  // Stitching and decimation ask the triangulation for neighbours later: they get the
  // cells' samples and the stars, not the rest of the table.
  std::vector<std::array<std::uint32_t, 4>>().swap(cells.neighbours);
  std::vector<Eigen::Vector3d>().swap(cells.centers);
  std::vector<std::array<std::uint8_t, 4>>().swap(marks);
  d.stars.cell_samples = std::move(cells.samples);
  d.stars.offsets = std::move(star_offsets);
  d.stars.cells = std::move(star_cells);

  // Incidence lists (CSR by sample).
  d.triangle_offsets.assign(n + 1, 0);
  for (const MarkedTriangle& t : d.triangles)
    for (const SampleIndex s : t.vertex)
      ++d.triangle_offsets[s + 1];
  for (std::size_t i = 0; i < n; ++i)
    d.triangle_offsets[i + 1] += d.triangle_offsets[i];
  d.triangle_ids.resize(d.triangle_offsets[n]);
  std::vector<std::uint32_t> fill(d.triangle_offsets.begin(),
                                  d.triangle_offsets.end() - 1);
  for (std::size_t t = 0; t < d.triangles.size(); ++t)
    for (const SampleIndex s : d.triangles[t].vertex)
      d.triangle_ids[fill[s]++] = static_cast<std::uint32_t>(t);
}

} // namespace detail
} // namespace cocone
} // namespace pcl
