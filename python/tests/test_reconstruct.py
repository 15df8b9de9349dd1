# SPDX-License-Identifier: GPL-3.0-or-later
"""reconstruct(): closed and open surfaces, the Mesh's parts, the accepted inputs."""
import math

import numpy as np
import pytest

import pcl_cocone
from conftest import hemisphere, is_closed_oriented_manifold, sphere, spacing


@pytest.mark.parametrize("n, seed", [(1000, 1), (2000, 2), (4000, 3)])
def test_random_sphere_is_closed_with_2n_minus_4_triangles(n, seed):
    mesh = pcl_cocone.reconstruct(sphere(n, seed))
    # Euler: a closed genus-0 triangulation of n vertices has 2n - 4 triangles.
    assert mesh.triangles.shape == (2 * n - 4, 3)
    assert mesh.triangles.dtype == np.int32
    assert len(mesh.unused) == 0
    assert mesh.boundary_loops == []
    assert is_closed_oriented_manifold(mesh.triangles)
    report = mesh.report
    assert report["closed"] and report["manifold"]
    assert report["genus"] == 0 and report["components"] == 1
    assert report["euler_characteristic"] == 2
    assert report["vertices_used"] == n and report["triangles"] == 2 * n - 4


def test_sphere_faces_outward(sphere_points):
    mesh = pcl_cocone.reconstruct(sphere_points)
    v = sphere_points[mesh.triangles]
    normals = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    assert np.all(np.einsum("ij,ij->i", normals, v.mean(axis=1)) > 0)


def test_hemisphere_keeps_its_rim_open(hemisphere_points):
    n = len(hemisphere_points)
    h = spacing(2 * math.pi, n)
    mesh = pcl_cocone.reconstruct(hemisphere_points)
    assert len(mesh.boundary_loops) == 1
    loop = mesh.boundary_loops[0]
    assert loop.dtype == np.int32
    assert np.all(hemisphere_points[loop, 2] < 1.5 * h)  # the loop runs along the rim
    assert mesh.report["manifold"] and not mesh.report["closed"]
    assert mesh.report["boundary_loops"] == 1 and mesh.report["genus"] == 0
    # The flags of the mesh are BOUNDARY's as published: the samples at the rim.
    assert mesh.boundary_samples.dtype == np.bool_
    assert mesh.boundary_samples.shape == (n,)
    assert mesh.boundary_samples.any()
    assert np.all(hemisphere_points[mesh.boundary_samples, 2] < 1.5 * h)


def test_mesh_parts_and_report(hemisphere_points):
    mesh = pcl_cocone.reconstruct(hemisphere_points)
    assert mesh.vertices is not None and mesh.vertices.shape == hemisphere_points.shape
    assert np.shares_memory(mesh.vertices, hemisphere_points)  # not copied
    assert mesh.unused.dtype == np.int32
    for array in (mesh.triangles, mesh.unused, mesh.boundary_samples):
        assert not array.flags.writeable
    report = mesh.report
    for key in ("boundary_samples", "candidate_triangles", "lid_triangles",
                "pruned_triangles", "walked_triangles", "pinch_removed_triangles",
                "stitched_holes", "stitched_triangles", "inserted_samples",
                "crossing_triangles", "open_boundary_loops", "unused_points",
                "vertices_used", "triangles", "boundary_loops",
                "euler_characteristic", "closed", "manifold", "components", "genus",
                "distinct_samples", "distinct_boundary_samples",
                "too_sparse_for_boundary_detection", "timings", "far_indices",
                "warning"):
        assert key in report, key
    assert report["boundary_samples"] == mesh.boundary_samples.sum()
    assert report["triangles"] == len(mesh.triangles)
    timings = report["timings"]
    assert set(timings) == {"boundary", "candidates", "pruning", "walk", "stitching",
                            "finishing", "restore", "reconstruct"}
    stages = sum(seconds for stage, seconds in timings.items() if stage != "reconstruct")
    assert 0 < stages <= timings["reconstruct"]
    assert report["warning"] == "" and len(report["far_indices"]) == 0
    assert mesh.report is report  # built once
    assert "Mesh" in repr(mesh)


def test_far_points_are_left_out_with_a_warning(sphere_points):
    points = np.vstack([sphere_points, [[1e7, 0, 0]]])
    with pytest.warns(RuntimeWarning, match="median radius"):
        mesh = pcl_cocone.reconstruct(points)
    far = len(sphere_points)
    assert list(mesh.report["far_indices"]) == [far]
    assert far in mesh.unused
    assert "left out" in mesh.report["warning"]


def test_nan_points_are_unused(sphere_points):
    points = sphere_points.copy()
    points[[3, 10]] = np.nan
    mesh = pcl_cocone.reconstruct(points)
    assert {3, 10} <= set(mesh.unused.tolist())
    assert not np.isin(mesh.triangles, [3, 10]).any()


def test_parameters_reach_the_class(hemisphere_points):
    plain = pcl_cocone.reconstruct(hemisphere_points, boundary_detection=False)
    assert not plain.boundary_samples.any()
    # A huge true-boundary ratio stitches the hemisphere's opening shut.
    shut = pcl_cocone.reconstruct(hemisphere_points, boundary_ratio=1000)
    assert shut.boundary_loops == [] and shut.report["closed"]
    assert shut.report["stitched_holes"] >= 1
    open_ = pcl_cocone.reconstruct(hemisphere_points, boundary_ratio=1000,
                                   stitching=False)
    assert len(open_.boundary_loops) >= 1


def test_defaults_are_the_classes():
    import inspect
    # pybind11 puts the signature on the first line of the docstring.
    signature = pcl_cocone.reconstruct.__doc__.splitlines()[0]
    assert f"theta: float = {math.pi / 8!r}" in signature
    assert "rho: float = 0.99" in signature
    assert f"alpha: float = {math.pi / 6!r}" in signature
    assert "boundary_ratio: float = 2.0" in signature
    assert "threads: int = 0" in signature
    assert "(0, 10]" in pcl_cocone.reconstruct.__doc__
    assert "[0.5, 1000]" in pcl_cocone.reconstruct.__doc__
    assert "rho: float = 0.3" in pcl_cocone.decimate.__doc__.splitlines()[0]
    assert "relaxation_iterations: int = 10" in pcl_cocone.decimate.__doc__
    assert "band_rings: int = 0" in pcl_cocone.boundary_samples.__doc__
    assert inspect.isbuiltin(pcl_cocone.reconstruct)


def to_list(points):
    return points.tolist()


@pytest.mark.parametrize("convert", [
    lambda p: p.astype(np.float32),
    np.asfortranarray,
    lambda p: np.ascontiguousarray(p[::-1])[::-1],  # negative row stride
    lambda p: np.column_stack([p, p])[:, :3],        # rows of 6, a strided view
    lambda p: p.astype(">f8"),                       # big endian
    to_list,
], ids=["float32", "fortran", "reversed", "strided", "big-endian", "list"])
def test_any_memory_order_gives_the_same_mesh(sphere_points, convert):
    reference = pcl_cocone.reconstruct(sphere_points.astype(np.float32))
    mesh = pcl_cocone.reconstruct(convert(sphere_points))
    np.testing.assert_array_equal(mesh.triangles, reference.triangles)


def test_integer_points_are_converted():
    grid = np.array([[x, y, z] for x in range(3) for y in range(3) for z in range(3)],
                    dtype=np.int64)
    corners = grid[(grid == 1).sum(axis=1) == 0]  # the 8 corners of a cube
    # Eight corners are all boundary samples: the class warns that the cloud is too
    # sparse for boundary detection.
    with pytest.warns(RuntimeWarning, match="too sparse for boundary detection"):
        mesh = pcl_cocone.reconstruct(corners * 10)
    assert mesh.vertices.dtype == np.float64
    assert mesh.report["too_sparse_for_boundary_detection"]


def test_extreme_parameters_are_named_as_the_reason(sphere_points):
    # alpha 0.001 flags every sample of any cloud: the warning blames the value, not
    # the cloud.
    with pytest.warns(RuntimeWarning, match=r"alpha=0\.001 \(default 0\.523599\)"):
        mesh = pcl_cocone.reconstruct(sphere_points, alpha=0.001)
    assert "too sparse" not in mesh.report["warning"]
    assert mesh.report["too_sparse_for_boundary_detection"]


def noisy_torus(n, sigma_in_spacings, seed=4):
    """n area-uniform random points on a torus (R 1, r 0.35), moved along their
    normals by Gaussian noise of sigma_in_spacings sample spacings."""
    rng = np.random.default_rng(seed)
    big, small = 1.0, 0.35
    u, v = [], []
    while len(u) < n:  # rejection by the area element (big + small cos v)
        uu = rng.uniform(0, 2 * np.pi, 2 * n)
        vv = rng.uniform(0, 2 * np.pi, 2 * n)
        keep = rng.uniform(0, 1, 2 * n) < (big + small * np.cos(vv)) / (big + small)
        u.extend(uu[keep]), v.extend(vv[keep])
    u, v = np.array(u[:n]), np.array(v[:n])
    normal = np.column_stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)])
    centre = np.column_stack([big * np.cos(u), big * np.sin(u), np.zeros(n)])
    step = spacing(4 * np.pi ** 2 * big * small, n)
    offset = small + rng.normal(0, sigma_in_spacings * step, n)
    return centre + offset[:, None] * normal


def test_denoise_reaches_the_class():
    """'auto' smooths a noisy scan's diagram (closed torus through every point), 'off'
    does not, a clean cloud is the same either way, and a bad name is refused."""
    noisy = noisy_torus(20000, 0.5)
    smoothed = pcl_cocone.reconstruct(noisy)
    assert smoothed.report["closed"] and smoothed.report["genus"] == 1
    assert len(smoothed.unused) == 0
    # Unsmoothed, the noise makes most samples boundary samples.
    with pytest.warns(RuntimeWarning, match="too sparse for boundary detection"):
        raw = pcl_cocone.reconstruct(noisy, denoise="off")
    assert not np.array_equal(raw.triangles, smoothed.triangles)
    clean = sphere(3000)
    assert np.array_equal(pcl_cocone.reconstruct(clean).triangles,
                          pcl_cocone.reconstruct(clean, denoise="off").triangles)
    for call in (pcl_cocone.reconstruct, pcl_cocone.boundary_samples,
                 pcl_cocone.decimate, pcl_cocone.voronoi_geometry):
        assert "denoise: str = 'auto'" in call.__doc__.splitlines()[0]
        with pytest.raises(ValueError, match="denoise = 'maybe'"):
            call(clean, denoise="maybe")
