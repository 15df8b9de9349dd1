# SPDX-License-Identifier: GPL-3.0-or-later
"""Mesh.save(): the tool's writer (pcl_cocone_io's saveMesh), read back by the
module's own reader and by Open3D."""
import os

import numpy as np
import pytest

import pcl_cocone
from conftest import is_closed_oriented_manifold


def faces_of_ascii(path):
    """The triangles of an OBJ (1-based 'f' lines) or a legacy VTK (POLYGONS rows)."""
    lines = path.read_text().splitlines()
    if path.suffix == ".obj":
        return np.array([[int(v) - 1 for v in line.split()[1:]]
                         for line in lines if line.startswith("f ")])
    start = next(i for i, line in enumerate(lines) if line.startswith("POLYGONS"))
    count = int(lines[start].split()[1])
    rows = [list(map(int, line.split())) for line in lines[start + 1:start + 1 + count]]
    assert all(row[0] == 3 for row in rows)
    return np.array([row[1:] for row in rows])


@pytest.mark.parametrize("name", ["mesh.ply", "mesh.obj", "mesh.vtk", "MESH.PLY"])
def test_save_writes_the_vertices_and_triangles(tmp_path, sphere_points, name):
    mesh = pcl_cocone.reconstruct(sphere_points)
    path = tmp_path / name
    mesh.save(path)  # a pathlib.Path; str works too
    points = pcl_cocone.load_points(path) if path.suffix.lower() != ".vtk" else None
    if points is not None:
        # Every input row is finite here, so vertex i is input row i, as float32.
        np.testing.assert_array_equal(points, sphere_points.astype(np.float32))
    if path.suffix.lower() == ".ply":
        return  # the faces of a PLY are checked through Open3D below
    np.testing.assert_array_equal(faces_of_ascii(path), mesh.triangles)


def test_non_finite_and_far_rows_are_dropped_and_the_rest_renumbered(tmp_path,
                                                                     sphere_points):
    points = np.insert(sphere_points, [5, 100, 100], np.nan, axis=0)
    points = np.insert(points, 50, [1e7, 1e7, 1e7], axis=0)  # far beyond the sphere
    with pytest.warns(RuntimeWarning, match="left out"):
        mesh = pcl_cocone.reconstruct(points)
    np.testing.assert_array_equal(mesh.report["far_indices"], [50])
    path = tmp_path / "mesh.obj"
    mesh.save(str(path))
    kept = np.isfinite(points).all(axis=1)
    kept[50] = False
    np.testing.assert_array_equal(pcl_cocone.load_points(path),
                                  points[kept].astype(np.float32))
    # Row r of the input is vertex new_id[r] of the file.
    new_id = np.cumsum(kept) - 1
    np.testing.assert_array_equal(faces_of_ascii(path), new_id[mesh.triangles])
    assert is_closed_oriented_manifold(faces_of_ascii(path))


def test_open3d_reads_the_saved_ply_as_the_same_closed_mesh(tmp_path, sphere_points):
    o3d = pytest.importorskip("open3d", reason="Open3D is not installed "
                              "(Debian: apt-get install python3-open3d)")
    mesh = pcl_cocone.reconstruct(sphere_points)
    path = tmp_path / "mesh.ply"
    mesh.save(path)
    read = o3d.io.read_triangle_mesh(str(path))
    np.testing.assert_array_equal(np.asarray(read.triangles), mesh.triangles)
    np.testing.assert_allclose(np.asarray(read.vertices), sphere_points, atol=1e-6)
    assert read.is_watertight() and read.is_edge_manifold(allow_boundary_edges=False)
    assert read.get_volume() == pytest.approx(4 / 3 * np.pi, rel=0.05)


def test_a_missing_folder_raises_os_error_and_writes_nothing(tmp_path, sphere_points):
    mesh = pcl_cocone.reconstruct(sphere_points)
    with pytest.raises(OSError, match="cannot write .*missing"):
        mesh.save(tmp_path / "missing" / "mesh.ply")
    assert not (tmp_path / "missing").exists()


def test_a_folder_we_may_not_write_raises_os_error(tmp_path, sphere_points):
    if os.geteuid() == 0:
        pytest.skip("root may write anywhere")
    mesh = pcl_cocone.reconstruct(sphere_points)
    folder = tmp_path / "locked"
    folder.mkdir(mode=0o500)
    try:
        with pytest.raises(OSError, match="Permission denied"):
            mesh.save(folder / "mesh.ply")
    finally:
        folder.chmod(0o700)
    assert list(folder.iterdir()) == []


def test_an_unknown_extension_raises_value_error(tmp_path, sphere_points):
    mesh = pcl_cocone.reconstruct(sphere_points)
    with pytest.raises(ValueError, match=r"expected \.ply, \.vtk, \.obj"):
        mesh.save(tmp_path / "mesh.stl")
    assert list(tmp_path.iterdir()) == []


def test_a_path_that_is_no_path_raises_type_error(sphere_points):
    mesh = pcl_cocone.reconstruct(sphere_points)
    with pytest.raises(TypeError):
        mesh.save(42)
