# SPDX-License-Identifier: GPL-3.0-or-later
"""The module itself: version, docstrings with units and ranges, PCL's console."""
import os
import pathlib
import re

import pytest

import pcl_cocone

FUNCTIONS = ["reconstruct", "boundary_samples", "voronoi_geometry", "decimate",
             "levels_of_detail", "load_points"]


def test_version_is_the_project_version():
    source = pathlib.Path(os.environ.get("PCL_COCONE_SOURCE_DIR",
                                         pathlib.Path(__file__).parents[2]))
    project = re.search(r"project\(pcl_cocone VERSION (\S+)",
                        (source / "CMakeLists.txt").read_text()).group(1)
    assert pcl_cocone.__version__ == project


@pytest.mark.parametrize("name", FUNCTIONS)
def test_every_function_is_documented(name):
    doc = getattr(pcl_cocone, name).__doc__
    assert "Parameters" in doc and "Returns" in doc and "Raises" in doc


def test_docstrings_give_unit_default_and_range():
    doc = pcl_cocone.reconstruct.__doc__
    for text in ("theta : float, radians, default pi/8", "(0, pi/2) = (0, 1.5708)",
                 "rho : float, dimensionless, default 0.99, range (0, 10]",
                 "alpha : float, radians, default pi/6, range (0, pi/2] = (0, 1.5708]",
                 "boundary_ratio : float, local sample spacings, default 2, "
                 "range [0.5, 1000]"):
        assert text in doc, text
    assert "band_rings : int, rings, default 0, range [0, 64]" in \
        pcl_cocone.boundary_samples.__doc__
    assert "relaxation_iterations : int, default 10, range [0, 1000]" in \
        pcl_cocone.decimate.__doc__


def test_verbosity_can_be_raised_and_restored():
    previous = pcl_cocone.set_verbosity("debug")
    assert previous == "always"  # the module's default: errors come as exceptions
    assert pcl_cocone.set_verbosity(previous) == "debug"
    with pytest.raises(ValueError, match="verbosity must be one of"):
        pcl_cocone.set_verbosity("loud")
