# SPDX-License-Identifier: GPL-3.0-or-later
"""decimate() and levels_of_detail()."""
import numpy as np

import pcl_cocone
from conftest import sphere


def test_decimation_returns_a_proper_subset(sphere_points):
    n = len(sphere_points)
    kept = pcl_cocone.decimate(sphere_points)
    assert kept.dtype == np.int32
    assert 4 <= len(kept) < n
    assert np.all(np.diff(kept) > 0)  # ascending, no repeat
    assert kept.min() >= 0 and kept.max() < n
    # Deterministic, and thinner at a larger rho.
    np.testing.assert_array_equal(pcl_cocone.decimate(sphere_points), kept)
    assert len(pcl_cocone.decimate(sphere_points, 0.4)) < len(kept)


def test_the_kept_points_still_make_a_closed_surface():
    points = sphere(4000, seed=5)
    kept = pcl_cocone.decimate(points, 0.3)
    mesh = pcl_cocone.reconstruct(points[kept])
    assert mesh.report["closed"] and mesh.report["genus"] == 0


def test_relaxation_keeps_the_size(sphere_points):
    relaxed = pcl_cocone.decimate(sphere_points)
    plain = pcl_cocone.decimate(sphere_points, relaxation_iterations=0)
    assert len(plain) == len(relaxed)


def test_levels_of_detail_are_nested(sphere_points):
    rhos = [0.4, 0.2, 0.3]
    levels = pcl_cocone.levels_of_detail(sphere_points, rhos)
    assert len(levels) == 3 and all(level.dtype == np.int32 for level in levels)
    by_rho = dict(zip(rhos, levels))
    assert set(by_rho[0.4]) < set(by_rho[0.3]) < set(by_rho[0.2])
    assert len(by_rho[0.2]) < len(sphere_points)
    # DECIMATE's own set: decimate() without relaxation.
    np.testing.assert_array_equal(
        by_rho[0.3], pcl_cocone.decimate(sphere_points, 0.3, relaxation_iterations=0))
    assert pcl_cocone.levels_of_detail(sphere_points, []) == []


def test_nan_points_are_never_kept(sphere_points):
    points = sphere_points.copy()
    points[0] = np.nan
    assert 0 not in pcl_cocone.decimate(points, 0.1)
