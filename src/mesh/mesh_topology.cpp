// SPDX-License-Identifier: GPL-3.0-or-later
// Combinatorial analysis of a triangle soup given as index triples.
#include <pcl/cocone/core/mesh_topology.h>

#include "common/disjoint_sets.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace pcl {
namespace cocone {

namespace {

using detail::DisjointSets;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/** Sorts a short range in place; the buckets of the edge table hold about six entries,
 * where std::sort's set-up costs more than the sort. */
void
sortSmall(std::uint64_t* begin, std::uint64_t* end)
{
  if (end - begin > 24) {
    std::sort(begin, end);
    return;
  }
  for (std::uint64_t* i = begin + 1; i < end; ++i) {
    const std::uint64_t value = *i;
    std::uint64_t* j = i;
    for (; j > begin && *(j - 1) > value; --j)
      *j = *(j - 1);
    *j = value;
  }
}

} // namespace

MeshTopology
analyzeTriangleMesh(const std::vector<TriangleIndices>& triangles)
{
  MeshTopology result;
  const std::size_t num_triangles = triangles.size();
  result.triangles = num_triangles;
  if (num_triangles == 0)
    return result;
  const std::size_t num_corners = 3 * num_triangles;

  // Compact vertex ids (0..V-1), so that every per-vertex table is dense. Indices may
  // be sparse in a huge range; then a sorted copy maps them instead of a direct table.
  std::vector<std::uint32_t> local(num_corners);
  std::vector<std::uint32_t> original; // compact id -> caller's index
  std::uint32_t max_index = 0;
  for (const TriangleIndices& t : triangles)
    max_index = std::max({max_index, t[0], t[1], t[2]});
  if (static_cast<std::size_t>(max_index) < 4 * num_corners + 1024) {
    std::vector<std::uint32_t> map(static_cast<std::size_t>(max_index) + 1, kNone);
    for (std::size_t c = 0; c < num_corners; ++c) {
      std::uint32_t& id = map[triangles[c / 3][c % 3]];
      if (id == kNone) {
        id = static_cast<std::uint32_t>(original.size());
        original.push_back(triangles[c / 3][c % 3]);
      }
      local[c] = id;
    }
  }
  else {
    original.resize(num_corners);
    for (std::size_t c = 0; c < num_corners; ++c)
      original[c] = triangles[c / 3][c % 3];
    std::sort(original.begin(), original.end());
    original.erase(std::unique(original.begin(), original.end()), original.end());
    for (std::size_t c = 0; c < num_corners; ++c)
      local[c] = static_cast<std::uint32_t>(
          std::lower_bound(original.begin(), original.end(), triangles[c / 3][c % 3]) -
          original.begin());
  }
  const std::size_t num_vertices = original.size();
  result.vertices = num_vertices;

  // A degenerate triangle has no proper edge and no fan: it counts in `triangles` and
  // its vertices in `vertices`, but takes no part in the edge, fan, orientation,
  // component and loop analysis below.
  std::vector<std::uint8_t> degenerate(num_triangles, 0);
  for (std::size_t t = 0; t < num_triangles; ++t) {
    const std::uint32_t* v = &local[3 * t];
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      degenerate[t] = 1;
      ++result.degenerate_triangles;
    }
  }

  // Edge table: half-edge h = 3 t + k goes from corner h to corner 3 t + (k + 1) % 3.
  // Half-edges are bucketed by their smaller vertex (counting sort, CSR) and each
  // bucket is sorted by (larger vertex, h): equal undirected edges become adjacent.
  auto next = [](std::size_t h) { return h - h % 3 + (h % 3 + 1) % 3; };
  std::vector<std::uint32_t> offset(num_vertices + 1, 0);
  for (std::size_t h = 0; h < num_corners; ++h)
    if (!degenerate[h / 3])
      ++offset[std::min(local[h], local[next(h)]) + 1];
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  std::vector<std::uint64_t> table(offset.back());
  {
    std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
    for (std::size_t h = 0; h < num_corners; ++h) {
      if (degenerate[h / 3])
        continue;
      const std::uint32_t a = local[h], b = local[next(h)];
      table[fill[std::min(a, b)]++] = (std::uint64_t(std::max(a, b)) << 32) | h;
    }
  }
  for (std::size_t v = 0; v < num_vertices; ++v)
    sortSmall(table.data() + offset[v], table.data() + offset[v + 1]);

  DisjointSets components(num_triangles);
  // Corners of one vertex joined through the edges at that vertex: one set per fan.
  DisjointSets fans(num_corners);
  std::vector<std::uint8_t> duplicate(num_triangles, 0);
  std::vector<std::uint32_t> boundary_halfedges;
  std::vector<std::uint64_t> scratch;

  auto halfedgeOf = [](std::uint64_t entry) {
    return static_cast<std::uint32_t>(entry & 0xffffffffu);
  };
  // The corner of half-edge h's triangle at vertex x (one of h's endpoints).
  auto cornerAt = [&](std::uint32_t h, std::uint32_t x) {
    return local[h] == x ? h : static_cast<std::uint32_t>(next(h));
  };
  // The vertex of h's triangle opposite to h.
  auto opposite = [&](std::uint32_t h) { return local[next(next(h))]; };

  for (std::size_t v = 0; v < num_vertices; ++v) {
    const std::uint32_t lo = static_cast<std::uint32_t>(v);
    std::size_t begin = offset[v];
    const std::size_t bucket_end = offset[v + 1];
    while (begin < bucket_end) {
      const std::uint64_t hi_bits = table[begin] >> 32;
      std::size_t end = begin + 1;
      while (end < bucket_end && (table[end] >> 32) == hi_bits)
        ++end;
      const std::uint32_t hi = static_cast<std::uint32_t>(hi_bits);
      const std::size_t count = end - begin;
      ++result.edges;

      const std::uint32_t h0 = halfedgeOf(table[begin]);
      if (count == 1)
        boundary_halfedges.push_back(h0);
      else if (count > 2)
        ++result.non_manifold_edges;
      else if (local[halfedgeOf(table[begin + 1])] == local[h0])
        ++result.inconsistently_oriented_edges;

      for (std::size_t i = begin + 1; i < end; ++i) {
        const std::uint32_t h = halfedgeOf(table[i]);
        components.unite(h0 / 3, h / 3);
        fans.unite(cornerAt(h0, lo), cornerAt(h, lo));
        fans.unite(cornerAt(h0, hi), cornerAt(h, hi));
      }

      // Two triangles with the same vertex set share all their edges, in particular
      // this one, with the same opposite vertex.
      if (count == 2) {
        const std::uint32_t h1 = halfedgeOf(table[begin + 1]);
        if (opposite(h0) == opposite(h1))
          duplicate[std::max(h0, h1) / 3] = 1;
      }
      else if (count > 2) {
        scratch.clear();
        for (std::size_t i = begin; i < end; ++i) {
          const std::uint32_t h = halfedgeOf(table[i]);
          scratch.push_back((std::uint64_t(opposite(h)) << 32) | (h / 3));
        }
        std::sort(scratch.begin(), scratch.end());
        for (std::size_t i = 1; i < scratch.size(); ++i)
          if ((scratch[i] >> 32) == (scratch[i - 1] >> 32))
            duplicate[scratch[i] & 0xffffffffu] = 1;
      }
      begin = end;
    }
  }

  result.boundary_edges = boundary_halfedges.size();
  result.duplicate_triangles =
      static_cast<std::size_t>(std::count(duplicate.begin(), duplicate.end(), 1));

  for (std::size_t t = 0; t < num_triangles; ++t)
    if (!degenerate[t] && components.find(static_cast<std::uint32_t>(t)) == t)
      ++result.components;

  // Every fan has exactly one root corner, a corner of the fan's vertex.
  std::vector<std::uint32_t> fan_count(num_vertices, 0);
  for (std::size_t c = 0; c < num_corners; ++c)
    if (!degenerate[c / 3] && fans.find(static_cast<std::uint32_t>(c)) == c)
      ++fan_count[local[c]];
  result.non_manifold_vertices = static_cast<std::size_t>(std::count_if(
      fan_count.begin(), fan_count.end(), [](std::uint32_t f) { return f > 1; }));

  if (result.non_manifold_edges > 0 || result.non_manifold_vertices > 0 ||
      boundary_halfedges.empty())
    return result;

  // With manifold edges and a single fan per vertex, the fan of a boundary vertex is a
  // path whose two ends are boundary edges: every boundary vertex has exactly two
  // boundary neighbours and lies on exactly one loop. The loops are followed through
  // these neighbours, starting along a triangle's direction, so an inconsistently
  // oriented boundary still closes.
  std::vector<std::uint32_t> neighbours(2 * num_vertices, kNone);
  auto link = [&](std::uint32_t a, std::uint32_t b) {
    std::uint32_t* slot = &neighbours[2 * a];
    if (slot[0] == kNone)
      slot[0] = b;
    else
      slot[1] = b;
  };
  for (const std::uint32_t h : boundary_halfedges) {
    link(local[h], local[next(h)]);
    link(local[next(h)], local[h]);
  }
  std::vector<std::uint8_t> visited(num_vertices, 0);
  for (const std::uint32_t h : boundary_halfedges) {
    const std::uint32_t start = local[h];
    if (visited[start])
      continue;
    std::vector<std::uint32_t> loop{original[start]};
    visited[start] = 1;
    std::uint32_t previous = start;
    std::uint32_t current = local[next(h)];
    while (current != start && current != kNone && !visited[current]) {
      loop.push_back(original[current]);
      visited[current] = 1;
      const std::uint32_t* slot = &neighbours[2 * current];
      const std::uint32_t following = slot[0] == previous ? slot[1] : slot[0];
      previous = current;
      current = following;
    }
    result.boundary_loops.push_back(std::move(loop));
  }
  return result;
}

} // namespace cocone
} // namespace pcl
