# SPDX-License-Identifier: GPL-3.0-or-later
"""Shapes and mesh checks shared by the tests of the Python module.

The shapes are area-uniform random samples (white noise, not blue noise), generated
here with numpy, so that the tests need no data file and see the gaps and clusters
that real scans have.
"""
import collections

import numpy as np
import pytest


def sphere(n, seed=1):
    """n area-uniform random points on the unit sphere (normalized Gaussian vectors)."""
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


def hemisphere(n, seed=1):
    """n area-uniform random points on the upper unit hemisphere z >= 0. By
    Archimedes' theorem a height uniform in [0, 1] is area-uniform; the rim is the
    equator, so a point's height is its distance to the rim (to first order)."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(0.0, 1.0, n)
    phi = rng.uniform(0.0, 2.0 * np.pi, n)
    r = np.sqrt(1.0 - z * z)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def spacing(area, n):
    """sqrt(area / n): the sample spacing the tests measure distances in."""
    return np.sqrt(area / n)


def directed_edges(triangles):
    t = np.asarray(triangles)
    return np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])


def is_closed_oriented_manifold(triangles):
    """Every directed edge appears once and its reverse once: each undirected edge has
    exactly two triangles, consistently oriented (closed and edge-manifold)."""
    edges = directed_edges(triangles)
    counts = collections.Counter(map(tuple, edges.tolist()))
    return all(n == 1 and counts.get((b, a), 0) == 1 for (a, b), n in counts.items())


@pytest.fixture(scope="session")
def sphere_points():
    return sphere(2000, seed=7)


@pytest.fixture(scope="session")
def hemisphere_points():
    return hemisphere(3000, seed=3)
