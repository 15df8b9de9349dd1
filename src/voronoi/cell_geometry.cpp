// SPDX-License-Identifier: GPL-3.0-or-later
// The per-sample Voronoi geometry of the diagram (section 2 of the paper): poles, pole
// vectors, heights, cocone radii and cocone marks, read from CGAL's triangulation into
// flat arrays, which then replace it.
#include "voronoi/cell_geometry.h"

#include "common/status_guard.h"
#include "voronoi/cocone_edge.h"

#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/constructions/kernel_ftC3.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/scalable_allocator.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace cocone {
namespace detail {

namespace {

/** Stars, cells and triangles are addressed with 32-bit offsets: refuses a cloud whose
 * triangulation has more entries than they reach (about 50M samples at 20 cells each,
 * 160M at the 6.5 of a scan). */
void
checkAddressable(std::size_t count, const char* what)
{
  if (count >= std::numeric_limits<std::uint32_t>::max())
    throw StageFailure{Status::too_many_points,
                       std::string("the triangulation has more ") + what +
                           " than 32-bit offsets address"};
}

/** A cell's samples in ascending order (kNoSample, the infinite vertex, last): the
 * name of the cell in every tile, whatever its number there. */
using CellKey = std::array<SampleIndex, 4>;

/** The circumcenter of a finite cell (its Voronoi vertex), from its vertices in
 * ascending sample order, \a key, so that it rounds the same in every tile. The
 * vertices are the triangulation's points: \a points of the samples, as inserted. */
Eigen::Vector3d
circumcenter(const std::vector<Eigen::Vector3d>& points, const CellKey& key)
{
  const auto at = [&](int j) {
    const Eigen::Vector3d& v = points[key[j]];
    return Point(v.x(), v.y(), v.z());
  };
  const Point p = at(0), q = at(1), r = at(2), s = at(3);
  double num_x, num_y, num_z, den;
  CGAL::determinants_for_circumcenterC3(p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), r.x(),
                                        r.y(), r.z(), s.x(), s.y(), s.z(), num_x, num_y,
                                        num_z, den);
  if (den != 0) { // CGAL's own formula, to the bit
    const double inv = 1 / (2 * den);
    return {p.x() + num_x * inv, p.y() - num_y * inv, p.z() + num_z * inv};
  }
  // Rounding cancelled the volume of a nearly flat cell (its vertices are not
  // coplanar: the triangulation's predicates are exact): construct it exactly.
  using ExactKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
  const auto exact = [](const Point& v) {
    return ExactKernel::Point_3(v.x(), v.y(), v.z());
  };
  const ExactKernel::Point_3 center =
      CGAL::circumcenter(exact(p), exact(q), exact(r), exact(s));
  return {CGAL::to_double(center.x()), CGAL::to_double(center.y()),
          CGAL::to_double(center.z())};
}

/** The triangulation as flat arrays by cell number, finite cells first and the
 * infinite ones after them. The per-sample pass reads these instead of CGAL's cells,
 * which lie scattered in memory: cache misses on cell handles dominated the pass. */
struct CellTable
{
  std::vector<std::array<SampleIndex, 4>> samples; // kNoSample: the infinite vertex
  std::vector<CellKey> keys; // the samples, ascending: orders cells across tiles
  const std::vector<SampleIndex>* sample_of = nullptr;  // local vertex -> sample
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

  /** Whether cell \a a comes before cell \a b in the order every tile agrees on. */
  bool
  before(std::uint32_t a, std::uint32_t b) const
  {
    return keys[a] < keys[b];
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
  // The facet's vertices in ascending order: the same rounding in every tile.
  std::array<SampleIndex, 3> f = {v[(i + 1) & 3], v[(i + 2) & 3], v[(i + 3) & 3]};
  const std::vector<SampleIndex>& sample_of = *cells.sample_of;
  std::sort(f.begin(), f.end(),
            [&](SampleIndex a, SampleIndex b) { return sample_of[a] < sample_of[b]; });
  const Eigen::Vector3d& a = points[f[0]];
  const Eigen::Vector3d& b = points[f[1]];
  const Eigen::Vector3d& d = points[f[2]];
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
  // Ties and sums go in the cross-tile cell order (CellTable::before), not in the
  // star's, which differs from tile to tile: the same bits in every tile.
  // A rim sample of an open scan can have dozens of hull facets: uncapped, per thread.
  thread_local std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> hull_normals;
  hull_normals.clear();
  Eigen::Vector3d hull_normal_sum = Eigen::Vector3d::Zero();
  double farthest2 = -1;
  std::uint32_t farthest = 0;
  geometry.unbounded = false;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c)) {
      // The finite facet of an infinite cell is a convex-hull triangle at p.
      geometry.unbounded = true;
      const std::uint32_t inside = cells.neighbours[*c][cells.indexOf(*c, kNoSample)];
      const Eigen::Vector3d normal =
          hullFacetNormal(cells, points, inside, cells.facetTowards(inside, *c));
      hull_normals.emplace_back(*c, normal);
      continue;
    }
    const double d2 = (cells.centers[*c] - p).squaredNorm();
    if (d2 > farthest2 || (d2 == farthest2 && cells.before(*c, farthest))) {
      farthest2 = d2;
      farthest = *c;
      geometry.positive_pole = cells.centers[*c];
    }
  }
  std::sort(
      hull_normals.begin(), hull_normals.end(),
      [&](const auto& a, const auto& b) { return cells.before(a.first, b.first); });
  for (const auto& hull_normal : hull_normals)
    hull_normal_sum += hull_normal.second;
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
  std::uint32_t negative = 0;
  for (const std::uint32_t* c = star_begin; c != star_end; ++c) {
    if (!cells.isFinite(*c))
      continue;
    const Eigen::Vector3d to_center = cells.centers[*c] - p;
    if (to_center.dot(geometry.pole_vector) >= 0)
      continue;
    const double d2 = to_center.squaredNorm();
    if (d2 > negative2 || (d2 == negative2 && cells.before(*c, negative))) {
      negative2 = d2;
      negative = *c;
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
 * from its finite cell or from the cell first in the cross-tile order (the edge is
 * clipped from that side, and the rounding must not change from run to run or from
 * tile to tile). An edge
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
      if (!ray && cells.before(n, *c))
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

void
computeTileGeometry(Delaunay& dt, const std::vector<Eigen::Vector3d>& points,
                    const std::vector<std::uint32_t>& tile_of, std::uint32_t tile,
                    double sin_theta, DiagramState& d, TileContribution& out)
{
  const auto owned = [&](SampleIndex s) {
    return s != kNoSample && tile_of[s] == tile;
  };

  // The local vertices, numbered in the triangulation's vertex order, which follows
  // the insertion (a spatial order, cut among threads): neighbouring samples mostly
  // share the cells of their
  // stars. Each vertex's info becomes its local number for the tables below.
  std::vector<SampleIndex> sample_of;
  sample_of.reserve(dt.number_of_vertices());
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    sample_of.push_back(v->info());
    v->info() = static_cast<SampleIndex>(sample_of.size() - 1);
  }
  const std::size_t m = sample_of.size();
  const auto sample = [&](SampleIndex local) {
    return local == kNoSample ? kNoSample : sample_of[local];
  };

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
  checkAddressable(4 * (all_cells.size() + infinite_cells.size()), "star entries");
  for (const CellHandle c : infinite_cells) {
    c->cellIndex() = static_cast<std::uint32_t>(all_cells.size());
    all_cells.push_back(c);
  }
  std::vector<CellHandle>().swap(infinite_cells);

  // The star of every vertex at once (cells by local vertex, infinite cells after the
  // finite ones): passes over the cells instead of a search per vertex, which measured
  // twice as slow. The vertices and neighbours of every cell are read once, in
  // parallel, so that these passes and the per-sample one scan flat arrays. The tables
  // hold local vertex numbers; keys and centers, sample indices.
  CellTable cells;
  cells.sample_of = &sample_of;
  cells.finite = finite_cells;
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
                      }
                    });
  // The table holds all that is read from here on: CGAL's triangulation, the largest
  // structure of the tile, goes before the rest of the table and the star lists are
  // made. Its cells come from TBB's scalable allocator, which keeps freed blocks for
  // reuse by its own allocations; handing them back to the system lets the vectors
  // below take their place instead of adding to the peak. With the keys and centers
  // made after the clear, the peak fell by a fifth (docs/performance.md).
  std::vector<CellHandle>().swap(all_cells);
  dt.clear();
  scalable_allocation_command(TBBMALLOC_CLEAN_ALL_BUFFERS, nullptr);

  // Keys and circumcenters, from the samples alone: the vertices of the triangulation
  // are the samples' points as inserted.
  cells.keys.resize(cells.samples.size());
  cells.centers.resize(finite_cells);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.samples.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        CellKey& key = cells.keys[k];
                        for (int j = 0; j < 4; ++j)
                          key[j] = sample(cells.samples[k][j]);
                        std::sort(key.begin(), key.end());
                        if (k < finite_cells)
                          cells.centers[k] = circumcenter(points, key);
                      }
                    });

  // Star lists by local vertex (counting sort by cell number).
  std::vector<std::uint32_t> star_offsets(m + 1, 0);
  for (const std::array<SampleIndex, 4>& cell : cells.samples)
    for (const SampleIndex v : cell)
      if (v != kNoSample)
        ++star_offsets[v + 1];
  for (std::size_t v = 0; v < m; ++v)
    star_offsets[v + 1] += star_offsets[v];
  std::vector<std::uint32_t> star_cells(star_offsets[m]);
  {
    std::vector<std::uint32_t> cursor(star_offsets.begin(), star_offsets.end() - 1);
    for (std::size_t k = 0; k < cells.samples.size(); ++k)
      for (const SampleIndex v : cells.samples[k])
        if (v != kNoSample)
          star_cells[cursor[v]++] = static_cast<std::uint32_t>(k);
  }
  std::vector<SampleIndex> own_vertices;
  for (std::size_t v = 0; v < m; ++v)
    if (owned(sample_of[v]))
      own_vertices.push_back(static_cast<SampleIndex>(v));

  // The points as the tables name them: by local vertex.
  std::vector<Eigen::Vector3d> local_points(m);
  for (std::size_t v = 0; v < m; ++v)
    local_points[v] = points[sample_of[v]];

  // marks[c][j] bit i: vertex j of cell c marks facet i of c. Only the thread handling
  // vertex j writes that byte, so no synchronisation is needed.
  std::vector<std::array<std::uint8_t, 4>> marks(finite_cells, {0, 0, 0, 0});
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, own_vertices.size(), 256),
      [&](const tbb::blocked_range<std::size_t>& range) {
        CellGeometry geometry;
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const SampleIndex v = own_vertices[k];
          const std::uint32_t* star_begin = star_cells.data() + star_offsets[v];
          const std::uint32_t* star_end = star_cells.data() + star_offsets[v + 1];
          computePoles(cells, local_points, v, star_begin, star_end, geometry);
          const SampleIndex s = sample_of[v];
          // Poles are kept in the frame of the samples, not of the local table.
          d.pole_vector[s] = geometry.pole_vector;
          d.positive_pole[s] = geometry.positive_pole;
          d.negative_pole[s] = geometry.negative_pole;
          d.height[s] = geometry.height;
          d.unbounded[s] = geometry.unbounded ? 1 : 0;
          d.radius[s] =
              computeCoconeRadius(cells, local_points, v, star_begin, star_end,
                                  geometry.pole_vector, sin_theta, marks);
        }
      });

  // The marks of this tile's samples, each facet from the cell that owns it (the same
  // rule computeCoconeRadius uses), under its ascending vertices: joinTiles merges
  // the marks the tiles of the other vertices give the same triangle. Most facets
  // are marked by none of their vertices: skipped on the marks alone. Blocks of cells
  // in parallel, joined in cell order.
  constexpr std::size_t kBlocks = 8;
  const std::size_t block_size = (finite_cells + kBlocks - 1) / kBlocks;
  std::vector<std::vector<MarkedTriangle>> found(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    const std::size_t first = std::min(b * block_size, finite_cells);
    const std::size_t last = std::min(first + block_size, finite_cells);
    for (std::size_t k = first; k < last; ++k)
      for (int i = 0; i < 4; ++i) {
        std::uint8_t bits = 0;
        std::array<std::pair<SampleIndex, bool>, 3> vertex;
        for (int j = 0, at = 0; j < 4; ++j) {
          if (j == i)
            continue;
          const bool marked = (marks[k][j] >> i) & 1u;
          vertex[at++] = {sample(cells.samples[k][j]), marked};
          bits |= marked ? 1 : 0;
        }
        if (bits == 0)
          continue;
        const std::uint32_t nb = cells.neighbours[k][i];
        if (cells.isFinite(nb) && cells.before(nb, static_cast<std::uint32_t>(k)))
          continue;
        std::sort(vertex.begin(), vertex.end());
        MarkedTriangle triangle;
        triangle.marked_by = 0;
        for (int j = 0; j < 3; ++j) {
          triangle.vertex[j] = vertex[j].first;
          if (vertex[j].second)
            triangle.marked_by |= static_cast<std::uint8_t>(1u << j);
        }
        found[b].push_back(triangle);
      }
  });
  std::size_t total = 0;
  for (const std::vector<MarkedTriangle>& block : found)
    total += block.size();
  out.marks.reserve(total);
  for (std::vector<MarkedTriangle>& block : found) {
    out.marks.insert(out.marks.end(), block.begin(), block.end());
    std::vector<MarkedTriangle>().swap(block);
  }
  // The cells this tile owns: those whose smallest sample is its own; all of them
  // when the tile is the whole cloud.
  if (own_vertices.size() == m) {
    out.cells = std::move(cells.keys);
  }
  else {
    for (const CellKey& key : cells.keys)
      if (owned(key[0]))
        out.cells.push_back(key);
  }
}

void
joinTiles(std::vector<TileContribution>& tiles, DiagramState& d)
{
  const std::size_t n = d.representative.size();

  // Cells: each comes from exactly one tile; their order does not matter (every query
  // on the stars sorts what it hands out).
  std::vector<CellKey> all_cells;
  if (tiles.size() == 1) {
    all_cells = std::move(tiles[0].cells);
  }
  else {
    std::size_t count = 0;
    for (const TileContribution& tile : tiles)
      count += tile.cells.size();
    all_cells.reserve(count);
    for (TileContribution& tile : tiles) {
      all_cells.insert(all_cells.end(), tile.cells.begin(), tile.cells.end());
      std::vector<CellKey>().swap(tile.cells);
    }
  }

  checkAddressable(4 * all_cells.size(), "star entries");
  // Stars (CSR by sample, cells ascending), filled by a few blocks of cells at once:
  // each block counts its cells per sample, so it knows where in each list its own
  // cells go.
  constexpr std::size_t kBlocks = 4;
  const std::size_t block_size = (all_cells.size() + kBlocks - 1) / kBlocks;
  const auto blockRange = [&](std::size_t b) {
    return std::make_pair(std::min(b * block_size, all_cells.size()),
                          std::min((b + 1) * block_size, all_cells.size()));
  };
  std::vector<std::vector<std::uint32_t>> cursor(kBlocks);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t b) {
    cursor[b].assign(n, 0);
    const auto [first, last] = blockRange(b);
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : all_cells[k])
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
    const auto [first, last] = blockRange(b);
    for (std::size_t k = first; k < last; ++k)
      for (const SampleIndex s : all_cells[k])
        if (s != kNoSample)
          star_cells[cursor[b][s]++] = static_cast<std::uint32_t>(k);
  });
  std::vector<std::vector<std::uint32_t>>().swap(cursor);
  d.stars.cell_samples = std::move(all_cells);
  d.stars.offsets = std::move(star_offsets);
  d.stars.cells = std::move(star_cells);
  // Marked triangles: the marks of one triangle's vertices may come from up to three
  // tiles; grouped by smallest vertex, sorted, merged.
  std::size_t mark_count = 0;
  for (const TileContribution& tile : tiles)
    mark_count += tile.marks.size();
  checkAddressable(3 * mark_count, "marked triangle incidences");
  std::vector<std::uint32_t> group(n + 1, 0);
  for (const TileContribution& tile : tiles)
    for (const MarkedTriangle& t : tile.marks)
      ++group[t.vertex[0] + 1];
  for (std::size_t i = 0; i < n; ++i)
    group[i + 1] += group[i];
  std::vector<MarkedTriangle> marks(group[n]);
  {
    std::vector<std::uint32_t> cursor(group.begin(), group.end() - 1);
    for (TileContribution& tile : tiles) {
      for (const MarkedTriangle& t : tile.marks)
        marks[cursor[t.vertex[0]]++] = t;
      std::vector<MarkedTriangle>().swap(tile.marks);
    }
  }
  std::vector<std::uint32_t> merged(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s) {
                        const auto first = marks.begin() + group[s];
                        const auto last = marks.begin() + group[s + 1];
                        std::sort(first, last,
                                  [](const MarkedTriangle& a, const MarkedTriangle& b) {
                                    return a.vertex < b.vertex;
                                  });
                        auto out = first;
                        for (auto t = first; t != last; ++t) {
                          if (out != first && (out - 1)->vertex == t->vertex)
                            (out - 1)->marked_by |= t->marked_by;
                          else
                            *out++ = *t;
                        }
                        merged[s + 1] = static_cast<std::uint32_t>(out - first);
                      }
                    });
  for (std::size_t i = 0; i < n; ++i)
    merged[i + 1] += merged[i];
  d.triangles.resize(merged[n]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t s = range.begin(); s != range.end(); ++s)
                        std::copy(marks.begin() + group[s],
                                  marks.begin() + group[s] +
                                      (merged[s + 1] - merged[s]),
                                  d.triangles.begin() + merged[s]);
                    });
  std::vector<MarkedTriangle>().swap(marks);

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
