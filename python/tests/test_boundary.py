# SPDX-License-Identifier: GPL-3.0-or-later
"""boundary_samples() and voronoi_geometry()."""
import math

import numpy as np
import pytest

import pcl_cocone
from conftest import hemisphere, spacing


def rim_sectors(points, flags, sectors=24):
    angle = np.arctan2(points[flags, 1], points[flags, 0])
    return len(set(((angle + np.pi) / (2 * np.pi) * sectors).astype(int) % sectors))


def test_hemisphere_flags_lie_on_its_rim(hemisphere_points):
    points = hemisphere_points
    h = spacing(2 * math.pi, len(points))
    published = pcl_cocone.boundary_samples(points, rim_row_completion=False)
    assert published.dtype == np.bool_ and published.shape == (len(points),)
    # BOUNDARY as published: a part of the outermost row, all around the rim.
    assert np.all(points[published, 2] < 1.5 * h)
    assert rim_sectors(points, published) >= 20
    # The completed row (default) is wider on random samples, whose rim is ragged,
    # but stays at the rim.
    flags = pcl_cocone.boundary_samples(points)
    assert flags.sum() > published.sum()
    assert np.all(flags[published])
    assert np.all(points[flags, 2] < 6 * h)
    assert np.mean(points[flags, 2] < 2 * h) > 0.8
    assert rim_sectors(points, flags) == 24


def test_closed_sphere_has_no_flags(sphere_points):
    assert not pcl_cocone.boundary_samples(sphere_points).any()


def test_band_rings_widen_the_flags(hemisphere_points):
    flags = pcl_cocone.boundary_samples(hemisphere_points)
    band = pcl_cocone.boundary_samples(hemisphere_points, band_rings=2)
    assert band.sum() > flags.sum() and np.all(band[flags])


def test_voronoi_geometry_of_a_sphere(sphere_points):
    n = len(sphere_points)
    geometry = pcl_cocone.voronoi_geometry(sphere_points)
    assert set(geometry) == {"pole_vectors", "heights", "cocone_radii", "ratios",
                             "valid", "far_indices", "warning"}
    poles = geometry["pole_vectors"]
    assert poles.shape == (n, 3) and poles.dtype == np.float32
    assert geometry["valid"].all()
    np.testing.assert_allclose(np.linalg.norm(poles, axis=1), 1, atol=1e-5)
    # Pole vectors are normals up to sign: along the radius on a sphere.
    cosine = np.abs(np.einsum("ij,ij->i", poles, sphere_points))
    assert np.median(cosine) > 0.99
    # Heights estimate the local feature size, 1 on the unit sphere (the inner pole
    # lies near the centre).
    assert 0.7 < np.median(geometry["heights"]) < 1.3
    ratios = geometry["ratios"]
    np.testing.assert_allclose(ratios, geometry["cocone_radii"] / geometry["heights"],
                               rtol=1e-4)
    assert geometry["heights"].shape == geometry["cocone_radii"].shape == (n,)


def test_voronoi_geometry_marks_skipped_points_invalid(sphere_points):
    points = sphere_points.copy()
    points[5] = np.nan
    geometry = pcl_cocone.voronoi_geometry(points)
    assert not geometry["valid"][5] and geometry["valid"].sum() == len(points) - 1
    assert np.isnan(geometry["heights"][5]) and np.isnan(geometry["pole_vectors"][5]).all()


def test_theta_changes_the_cocone_radii(sphere_points):
    narrow = pcl_cocone.voronoi_geometry(sphere_points, theta=0.1)["cocone_radii"]
    wide = pcl_cocone.voronoi_geometry(sphere_points, theta=0.7)["cocone_radii"]
    assert np.median(wide) > np.median(narrow)


@pytest.mark.parametrize("sigma", [0.1, 0.3])
def test_noisy_hemisphere_flags_its_rim_not_its_noise(sigma):
    """Scanner noise along the normal (sigma in sample spacings) on a random
    hemisphere: with the default denoise='auto', at least 95% of the flags lie within
    3 spacings of the rim and every stretch of the rim has one; as given
    (denoise='off'), the noise itself is flagged (measured: 13% and 6% of the flags
    near the rim, against 98.7% and 95.1% with auto)."""
    n = 30000
    step = spacing(2 * math.pi, n)
    rng = np.random.default_rng(7)
    points = hemisphere(n, seed=3) * (1 + rng.normal(0, sigma * step, n))[:, None]
    flags = pcl_cocone.boundary_samples(points)
    # The rim is the equator: a sample's distance to it is its height, to first order.
    near_rim = np.abs(points[flags, 2]) <= 3 * step
    assert near_rim.mean() >= 0.95
    angles = np.arctan2(points[flags, 1], points[flags, 0])[near_rim]
    sectors = np.floor((angles + math.pi) / (2 * math.pi) * 64).astype(int)
    assert len(np.unique(sectors)) == 64
    raw = pcl_cocone.boundary_samples(points, denoise="off")
    assert (np.abs(points[raw, 2]) <= 3 * step).mean() < 0.5
