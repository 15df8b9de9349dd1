# SPDX-License-Identifier: GPL-3.0-or-later
"""progress=: the classes' progress callbacks reach Python, a callback can cancel, and
Ctrl-C (KeyboardInterrupt) stops a running call, with or without a callback."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import pcl_cocone
from conftest import sphere

CALLS = {
    "reconstruct": lambda points, **kw: pcl_cocone.reconstruct(points, **kw),
    "boundary_samples": lambda points, **kw: pcl_cocone.boundary_samples(points, **kw),
    "voronoi_geometry": lambda points, **kw: pcl_cocone.voronoi_geometry(points, **kw),
    "decimate": lambda points, **kw: pcl_cocone.decimate(points, **kw),
    "levels_of_detail": lambda points, **kw: pcl_cocone.levels_of_detail(
        points, [0.3, 0.4], **kw),
}


@pytest.mark.parametrize("call", CALLS)
def test_progress_rises_to_one_and_changes_nothing(call, sphere_points):
    shares = []
    result = CALLS[call](sphere_points, progress=shares.append)
    assert len(shares) >= 3
    assert all(0.0 <= s <= 1.0 for s in shares)
    assert all(a <= b for a, b in zip(shares, shares[1:])), shares
    assert shares[-1] == 1.0
    # The same result as without a callback.
    alone = CALLS[call](sphere_points)
    if call == "reconstruct":
        np.testing.assert_array_equal(result.triangles, alone.triangles)
    elif call == "voronoi_geometry":
        np.testing.assert_array_equal(result["heights"], alone["heights"])
    elif call == "levels_of_detail":
        for a, b in zip(result, alone):
            np.testing.assert_array_equal(a, b)
    else:
        np.testing.assert_array_equal(result, alone)


@pytest.mark.parametrize("call", CALLS)
def test_returning_false_cancels(call, sphere_points):
    shares = []

    def stop_halfway(share):
        shares.append(share)
        return share < 0.5

    with pytest.raises(pcl_cocone.CancelledError, match="cancelled"):
        CALLS[call](sphere_points, progress=stop_halfway)
    # The call stopped at the first False.
    assert shares[-1] >= 0.5 and all(s < 0.5 for s in shares[:-1])
    assert issubclass(pcl_cocone.CancelledError, RuntimeError)


def test_none_and_true_go_on(sphere_points):
    mesh = pcl_cocone.reconstruct(sphere_points, progress=lambda share: True)
    assert len(mesh.triangles) == 2 * len(sphere_points) - 4
    mesh = pcl_cocone.reconstruct(sphere_points, progress=None)
    assert len(mesh.triangles) == 2 * len(sphere_points) - 4


@pytest.mark.parametrize("call", CALLS)
def test_an_exception_in_the_callback_propagates(call, sphere_points):
    class Stop(Exception):
        pass

    calls = []

    def fail_at_second_call(share):
        calls.append(share)
        if len(calls) == 2:
            raise Stop("from the callback")

    with pytest.raises(Stop, match="from the callback"):
        CALLS[call](sphere_points, progress=fail_at_second_call)
    assert len(calls) == 2


def test_a_progress_that_is_not_callable_raises_type_error(sphere_points):
    with pytest.raises(TypeError, match="progress"):
        pcl_cocone.reconstruct(sphere_points, progress=3)


def test_sigint_from_the_callback_raises_keyboard_interrupt(sphere_points):
    calls = []

    def interrupt(share):
        calls.append(share)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        pcl_cocone.reconstruct(sphere_points, progress=interrupt)
    assert len(calls) == 1


def test_ctrl_c_stops_a_running_call_without_a_callback():
    # SIGINT comes from another thread while the main thread computes without the
    # GIL. Without the module's hook, Python would run its handler only when the call
    # returns: the KeyboardInterrupt would come after the whole run. With it, the run
    # stops at its next progress report. A full run is timed first, and the signal
    # sent a fifth of the way in; the stop must come well before the end (the longest
    # gap between reports is about a quarter of a run). The full run is the longer of
    # two: under ctest -j2 the load changes from one run to the next, and one quick
    # timed run beside a slow interrupted one made this fail once. (The bound is
    # looser for it; a run that ignored the signal would still take the full time.)
    points = sphere(100000, seed=5)
    full = 0.0
    for _ in range(2):
        start = time.monotonic()
        pcl_cocone.reconstruct(points)
        full = max(full, time.monotonic() - start)

    timer = threading.Timer(0.2 * full, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pcl_cocone.reconstruct(points)
        stopped = time.monotonic() - start
    finally:
        timer.cancel()
        timer.join()
    assert stopped < 0.8 * full, (stopped, full)
