# SPDX-License-Identifier: GPL-3.0-or-later
"""Bad input raises TypeError or ValueError with the class's message, in every
function, and never crashes."""
import math

import numpy as np
import pytest

import pcl_cocone
from conftest import sphere

FUNCTIONS = {
    "reconstruct": pcl_cocone.reconstruct,
    "boundary_samples": pcl_cocone.boundary_samples,
    "voronoi_geometry": pcl_cocone.voronoi_geometry,
    "decimate": pcl_cocone.decimate,
    "levels_of_detail": lambda points, **kw: pcl_cocone.levels_of_detail(
        points, [0.3], **kw),
}


def coplanar(n=200, seed=1):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.random((n, 2)), np.full(n, 0.5)])


def collinear(n=50):
    t = np.linspace(0, 1, n)
    return np.column_stack([t, 2 * t, -t])


BAD_VALUES = {
    # BoundarySampleEstimation refuses an empty cloud before it builds the diagram.
    "empty": (np.zeros((0, 3)), "at least 4|the input cloud is empty"),
    "all NaN": (np.full((10, 3), np.nan), "at least 4"),
    "three points": (np.eye(3), "at least 4"),
    "four copies of one point": ([[1.0, 2.0, 3.0]] * 4, "4 distinct"),
    "coplanar": (coplanar(), "coplanar"),
    "collinear": (collinear(), "collinear"),
    "infinite": (np.full((6, 3), np.inf), "at least 4"),
}

BAD_SHAPES = {
    "two columns": np.zeros((10, 2)),
    "four columns": np.zeros((10, 4)),
    "one point": np.zeros(3),
    "three dimensions": np.zeros((2, 4, 3)),
    "scalar": 1.5,
    "ragged": [[0.0, 1.0, 2.0], [3.0, 4.0]],
}

BAD_TYPES = {
    "strings": np.array([["a", "b", "c"]] * 5),
    "objects": np.array([[object()] * 3] * 5),
    "complex": np.ones((5, 3), dtype=complex),
    "booleans": np.ones((5, 3), dtype=bool),
    "None": None,
    "a string": "points.xyz",
    "a dict": {"x": 1},
}


@pytest.mark.parametrize("function", FUNCTIONS.values(), ids=FUNCTIONS.keys())
@pytest.mark.parametrize("points, message", BAD_VALUES.values(), ids=BAD_VALUES.keys())
def test_clouds_without_a_voronoi_diagram_raise_the_class_message(function, points,
                                                                  message):
    with pytest.raises(ValueError, match=message):
        function(points)


@pytest.mark.parametrize("function", FUNCTIONS.values(), ids=FUNCTIONS.keys())
@pytest.mark.parametrize("points", BAD_SHAPES.values(), ids=BAD_SHAPES.keys())
def test_wrong_shapes_raise_value_error(function, points):
    with pytest.raises(ValueError):
        function(points)


@pytest.mark.parametrize("function", FUNCTIONS.values(), ids=FUNCTIONS.keys())
@pytest.mark.parametrize("points", BAD_TYPES.values(), ids=BAD_TYPES.keys())
def test_non_numeric_input_raises_type_error(function, points):
    with pytest.raises(TypeError):
        function(points)


def test_shape_message_names_the_shape():
    with pytest.raises(ValueError, match=r"\(N, 3\), got \(10, 2\)"):
        pcl_cocone.reconstruct(np.zeros((10, 2)))


OUT_OF_RANGE = [
    # function, keyword, value, the setter's message
    ("reconstruct", "theta", 0.0, r"CoconeReconstruction::setCoconeAngle\] theta = 0 "
                                  r"is outside \(0, 1\.5708\)"),
    ("reconstruct", "theta", math.pi / 2, "setCoconeAngle"),
    ("reconstruct", "rho", -1.0, r"CoconeReconstruction::setRatioBound\] rho = -1 is "
                                 r"outside \(0, 10\]"),
    ("reconstruct", "rho", 10.5, "setRatioBound"),
    ("reconstruct", "rho", math.nan, "rho = nan"),
    ("reconstruct", "alpha", 2.0, r"CoconeReconstruction::setNormalAngle\] alpha = 2"),
    ("reconstruct", "boundary_ratio", 0.25, r"setTrueBoundaryRatio\] ratio = 0.25 is "
                                            r"outside \[0\.5, 1000\]"),
    ("reconstruct", "boundary_ratio", math.inf, "setTrueBoundaryRatio"),
    ("reconstruct", "threads", -1, "threads = -1"),
    ("boundary_samples", "rho", 0.0, r"BoundarySampleEstimation::setRatioBound\]"),
    ("boundary_samples", "alpha", -0.1, r"BoundarySampleEstimation::setNormalAngle\]"),
    ("boundary_samples", "theta", 3.0, r"BoundarySampleEstimation::setCoconeAngle\]"),
    ("boundary_samples", "band_rings", 65, r"setBoundaryBandRings\] rings = 65 is "
                                           r"outside \[0, 64\]"),
    ("boundary_samples", "band_rings", -1, r"setBoundaryBandRings\] rings = -1"),
    ("voronoi_geometry", "theta", -1.0, r"BoundarySampleEstimation::setCoconeAngle\]"),
    ("voronoi_geometry", "threads", -4, "threads = -4"),
    ("decimate", "rho", 0.0, r"VoronoiDecimation::setRatioBound\] rho = 0 is outside"),
    ("decimate", "theta", 1.6, r"VoronoiDecimation::setCoconeAngle\]"),
    ("decimate", "relaxation_iterations", 1001,
     r"setRelaxationIterations\] iterations = 1001 is outside \[0, 1000\]"),
    ("decimate", "relaxation_iterations", -1, "setRelaxationIterations"),
    ("levels_of_detail", "theta", 0.0, r"VoronoiDecimation::setCoconeAngle\]"),
]


@pytest.mark.parametrize("name, keyword, value, message", OUT_OF_RANGE,
                         ids=[f"{f}-{k}={v}" for f, k, v, _ in OUT_OF_RANGE])
def test_out_of_range_parameters_raise_the_setter_message(name, keyword, value,
                                                          message):
    with pytest.raises(ValueError, match=message):
        FUNCTIONS[name](sphere(100), **{keyword: value})


@pytest.mark.parametrize("rhos", [[0.3, 0.0], [11.0], [math.nan]])
def test_levels_of_detail_refuse_a_bad_rho(rhos):
    with pytest.raises(ValueError, match=r"computeLevelsOfDetail\] rho = .* is outside"):
        pcl_cocone.levels_of_detail(sphere(100), rhos)


def test_a_parameter_of_the_wrong_type_raises_type_error():
    with pytest.raises(TypeError):
        pcl_cocone.reconstruct(sphere(100), rho="large")
    with pytest.raises(TypeError):
        pcl_cocone.reconstruct(sphere(100), 0.5)  # parameters are keyword-only


def test_the_largest_valid_values_are_accepted():
    points = sphere(300)
    pcl_cocone.reconstruct(points, rho=10, alpha=math.pi / 2, boundary_ratio=1000)
    pcl_cocone.boundary_samples(points, band_rings=64)
    pcl_cocone.decimate(points, 10, relaxation_iterations=0)
