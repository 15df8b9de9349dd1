// SPDX-License-Identifier: GPL-3.0-or-later
// The mesher's parts one by one (src/reconstruction/), on small hand-made or generated
// inputs: the box grid, the least-area fill, and each stage of reconstructSurface.
#include "reconstruction/box_grid.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace {

using pcl::cocone::detail::Box;
using pcl::cocone::detail::BoxGrid;
using pcl::cocone::detail::boxesApart;
using Vector = Eigen::Vector3d;

// --- box grid --------------------------------------------------------------------

std::vector<std::uint32_t>
bruteForceOverlapping(const std::vector<Box>& boxes, const Box& query)
{
  std::vector<std::uint32_t> found;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    if (!boxesApart(boxes[i], query))
      found.push_back(i);
  return found;
}

TEST(BoxGrid, TouchingBoxesMeetAndSeparatedOnesDoNot)
{
  const Box unit{Vector(0, 0, 0), Vector(1, 1, 1)};
  EXPECT_FALSE(boxesApart(unit, {Vector(1, 1, 1), Vector(2, 2, 2)})); // a corner
  EXPECT_FALSE(boxesApart(unit, {Vector(1, 0.5, -3), Vector(5, 0.6, 3)})); // a face
  EXPECT_TRUE(boxesApart(unit, {Vector(1 + 1e-12, 0, 0), Vector(2, 1, 1)}));
  EXPECT_TRUE(boxesApart(unit, {Vector(0, 0, -2), Vector(1, 1, -1e-12)}));
}

// Random boxes of many sizes (some over more cells than the grid lists, some flat, some
// at negative coordinates), against queries from a point to wider than everything.
TEST(BoxGrid, FindsExactlyTheBoxesThatMeetAQuery)
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> position(-20, 20), size(0, 1);
  std::vector<Box> boxes;
  double edges = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vector low(position(random), position(random), position(random));
    Vector extent(size(random), size(random), size(random));
    if (i % 50 == 0)
      extent *= 40; // a long triangle: kept among the large ones
    if (i % 7 == 0)
      extent.z() = 0; // flat
    boxes.push_back({low, low + extent});
    edges += extent.norm();
  }
  // The touching cases, exactly on a cell's side and on a box's.
  boxes.push_back({Vector(0, 0, 0), Vector(1, 1, 1)});
  boxes.push_back({Vector(1, 1, 1), Vector(2, 2, 2)});
  BoxGrid grid(BoxGrid::cellSideFor(edges, boxes.size()));
  ASSERT_GT(grid.cellSide(), 0);
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    grid.insert(i, boxes[i]);

  std::vector<Box> queries = {{Vector(1, 1, 1), Vector(1, 1, 1)}, // a point
                              {Vector(-1, -1, -1), Vector(0, 0, 0)},
                              {Vector(-50, -50, -50), Vector(50, 50, 50)}}; // everything
  for (int q = 0; q < 300; ++q) {
    const Vector low(position(random), position(random), position(random));
    queries.push_back({low, low + 6 * Vector(size(random), size(random), size(random))});
  }
  const auto box_of = [&](std::uint32_t i) -> const Box& { return boxes[i]; };
  std::size_t found_any = 0;
  for (const Box& query : queries) {
    const std::vector<std::uint32_t> expected = bruteForceOverlapping(boxes, query);
    found_any += !expected.empty();

    std::vector<std::uint32_t> overlapping;
    grid.forEachOverlapping(query, box_of,
                            [&](std::uint32_t i) { overlapping.push_back(i); });
    std::sort(overlapping.begin(), overlapping.end());
    EXPECT_EQ(overlapping, expected); // each once: no repeats

    // forEachNear gives a superset (the entries of the cells met): sifted by box, the
    // same set.
    std::vector<std::uint32_t> near;
    grid.forEachNear(query, box_of, [&](std::uint32_t i) { near.push_back(i); });
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    EXPECT_TRUE(std::includes(near.begin(), near.end(), expected.begin(), expected.end()));
    near.erase(std::remove_if(near.begin(), near.end(),
                              [&](std::uint32_t i) { return boxesApart(boxes[i], query); }),
               near.end());
    EXPECT_EQ(near, expected);
  }
  EXPECT_GT(found_any, queries.size() / 2); // the queries are not all in empty space
}

TEST(BoxGrid, CellSideIsTwiceTheMeanEdge)
{
  EXPECT_DOUBLE_EQ(BoxGrid::cellSideFor(10, 5), 4);
  EXPECT_DOUBLE_EQ(BoxGrid::cellSideFor(0, 5), 1); // nothing to measure: any side
  EXPECT_DOUBLE_EQ(BoxGrid::cellSideFor(3, 0), 1);
}

} // namespace
