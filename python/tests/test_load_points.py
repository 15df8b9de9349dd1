# SPDX-License-Identifier: GPL-3.0-or-later
"""load_points(): the formats the tools read, written here, and the shared scans when
they are there."""
import os
import pathlib
import struct

import numpy as np
import pytest

import pcl_cocone

POINTS = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.5, 0.0],
                   [0.0, 0.0, -2.25], [0.5, 0.25, 0.125]])


def rows(points):
    return "".join(f"{x} {y} {z}\n" for x, y, z in points)


def write_pcd(path):
    path.write_text("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                    "COUNT 1 1 1\nWIDTH 5\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                    "POINTS 5\nDATA ascii\n" + rows(POINTS))


def write_ply(path):
    path.write_text("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n" +
                    rows(POINTS) + "3 0 1 2\n")


def write_obj(path):
    path.write_text("# points\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in POINTS) +
                    "f 1 2 3\n")


def write_off(path):
    path.write_text("OFF\n5 1 0\n" + rows(POINTS) + "3 0 1 2\n")


def write_xyz(path):
    path.write_text("# x y z\n" + rows(POINTS))


def write_las(path):
    """LAS 1.2, point format 0 (20-byte records), coordinates in steps of 1/8."""
    scale = 0.125
    header = bytearray(227)
    header[0:4] = b"LASF"
    header[24:26] = bytes([1, 2])
    struct.pack_into("<HIIBHI", header, 94, 227, 227, 0, 0, 20, len(POINTS))
    struct.pack_into("<6d", header, 131, scale, scale, scale, 0.0, 0.0, 0.0)
    records = b"".join(struct.pack("<3iH6x", *(round(c / scale) for c in p), 100)
                       for p in POINTS)
    path.write_bytes(bytes(header) + records)


WRITERS = {".pcd": write_pcd, ".ply": write_ply, ".obj": write_obj, ".off": write_off,
           ".xyz": write_xyz, ".pts": write_xyz, ".txt": write_xyz, ".XYZ": write_xyz,
           ".las": write_las}


@pytest.mark.parametrize("extension", WRITERS)
def test_every_format_the_tools_read(tmp_path, extension):
    path = tmp_path / f"points{extension}"
    WRITERS[extension](path)
    points = pcl_cocone.load_points(path)  # a pathlib.Path
    assert points.dtype == np.float32 and points.shape == (5, 3)
    np.testing.assert_array_equal(points, POINTS.astype(np.float32))
    np.testing.assert_array_equal(pcl_cocone.load_points(str(path)), points)


def test_a_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        pcl_cocone.load_points(tmp_path / "missing.xyz")


def test_a_folder_raises_os_error(tmp_path):
    with pytest.raises(IsADirectoryError):
        pcl_cocone.load_points(tmp_path)


@pytest.mark.parametrize("name, text, message", [
    ("points.abc", "1 2 3\n", "unknown extension"),
    ("empty.xyz", "# nothing\n", ""),
    ("broken.off", "OFF\n5 0 0\n1 2\n", ""),
    ("short.las", "LASF", "truncated"),
])
def test_unusable_contents_raise_value_error_with_the_reader_reason(tmp_path, name,
                                                                    text, message):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        pcl_cocone.load_points(path)


def test_laz_raises_value_error_that_says_how_to_convert(tmp_path):
    path = tmp_path / "scan.laz"
    write_las(path)
    data = bytearray(path.read_bytes())
    data[104] |= 0x80  # how LASzip marks compressed point data
    path.write_bytes(bytes(data))
    with pytest.raises(ValueError, match="LAZ.*las2las.*pdal translate"):
        pcl_cocone.load_points(path)


def data_dir():
    return pathlib.Path(os.environ.get("PCL_COCONE_DATA_DIR", "/nonexistent"))


def test_a_shared_scan_reconstructs():
    path = data_dir() / "bun_zipper_35947.ply"
    if not path.is_file():
        pytest.skip(f"{path} is absent (set PCL_COCONE_DATA_DIR to the folder of the "
                    "shared scans)")
    points = pcl_cocone.load_points(path)
    assert points.shape == (35947, 3)
    mesh = pcl_cocone.reconstruct(points)
    assert mesh.report["manifold"] and len(mesh.triangles) > 60000
