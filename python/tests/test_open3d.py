# SPDX-License-Identifier: GPL-3.0-or-later
"""Open3D both ways: a PointCloud in, a TriangleMesh out (python3-open3d 0.16)."""
import subprocess
import sys

import numpy as np
import pytest

import pcl_cocone

o3d = pytest.importorskip("open3d", reason="Open3D is not installed "
                          "(Debian: apt-get install python3-open3d)")


def test_round_trip_gives_a_watertight_edge_manifold_mesh(sphere_points):
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(sphere_points))
    mesh = pcl_cocone.reconstruct(cloud)
    triangle_mesh = mesh.to_open3d()
    assert isinstance(triangle_mesh, o3d.geometry.TriangleMesh)
    assert len(triangle_mesh.vertices) == len(sphere_points)
    assert len(triangle_mesh.triangles) == 2 * len(sphere_points) - 4
    assert triangle_mesh.is_edge_manifold(allow_boundary_edges=False)
    assert triangle_mesh.is_vertex_manifold()
    assert triangle_mesh.is_watertight()
    assert triangle_mesh.is_orientable()
    np.testing.assert_array_equal(np.asarray(triangle_mesh.triangles), mesh.triangles)
    np.testing.assert_allclose(np.asarray(triangle_mesh.vertices), sphere_points)
    # Outward: Open3D's signed volume of the closed mesh is that of the unit ball.
    assert triangle_mesh.get_volume() == pytest.approx(4 / 3 * np.pi, rel=0.05)


def test_open3d_points_are_copied(sphere_points):
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(sphere_points))
    mesh = pcl_cocone.reconstruct(cloud)
    before = mesh.vertices.copy()
    cloud.points = o3d.utility.Vector3dVector(np.zeros((10, 3)))  # Open3D reallocates
    np.testing.assert_array_equal(mesh.vertices, before)


def test_every_function_takes_an_open3d_cloud(hemisphere_points):
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(hemisphere_points))
    np.testing.assert_array_equal(pcl_cocone.boundary_samples(cloud),
                                  pcl_cocone.boundary_samples(hemisphere_points))
    np.testing.assert_array_equal(pcl_cocone.decimate(cloud),
                                  pcl_cocone.decimate(hemisphere_points))
    assert pcl_cocone.voronoi_geometry(cloud)["valid"].all()
    assert len(pcl_cocone.levels_of_detail(cloud, [0.3])) == 1


def test_an_open_surface_goes_to_open3d_with_its_boundary(hemisphere_points):
    triangle_mesh = pcl_cocone.reconstruct(hemisphere_points).to_open3d()
    assert triangle_mesh.is_edge_manifold(allow_boundary_edges=True)
    assert not triangle_mesh.is_watertight()


def test_the_module_does_not_import_open3d():
    # Importing open3d takes seconds and pulls in much; only to_open3d() needs it.
    code = ("import sys, numpy, pcl_cocone; "
            "pcl_cocone.reconstruct(numpy.random.default_rng(1).normal(size=(50, 3))); "
            "sys.exit('open3d' in sys.modules)")
    subprocess.run([sys.executable, "-c", code], check=True)
