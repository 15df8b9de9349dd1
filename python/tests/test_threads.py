# SPDX-License-Identifier: GPL-3.0-or-later
"""Python threads: the GIL is released while the classes compute, and calls from
several threads at once give the results of one call alone."""
import concurrent.futures
import threading
import time

import numpy as np

import pcl_cocone
from conftest import hemisphere, sphere


def test_threads_at_once_give_the_same_results():
    inputs = [sphere(3000, seed=11), hemisphere(3000, seed=12)]
    alone = [pcl_cocone.reconstruct(points) for points in inputs]
    flags_alone = [pcl_cocone.boundary_samples(points) for points in inputs]
    kept_alone = [pcl_cocone.decimate(points) for points in inputs]

    def work(k):
        points = inputs[k % 2]
        return (k % 2, pcl_cocone.reconstruct(points, threads=1 + k % 2),
                pcl_cocone.boundary_samples(points), pcl_cocone.decimate(points))

    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        results = list(pool.map(work, range(8)))
    for which, mesh, flags, kept in results:
        np.testing.assert_array_equal(mesh.triangles, alone[which].triangles)
        np.testing.assert_array_equal(mesh.unused, alone[which].unused)
        np.testing.assert_array_equal(flags, flags_alone[which])
        np.testing.assert_array_equal(kept, kept_alone[which])


def test_the_gil_is_released_while_computing():
    points = sphere(60000, seed=13)
    done = threading.Event()
    elapsed = []

    def run():
        start = time.perf_counter()
        pcl_cocone.reconstruct(points)
        elapsed.append(time.perf_counter() - start)
        done.set()

    worker = threading.Thread(target=run)
    worker.start()
    # While the reconstruction runs, this thread keeps getting the interpreter: the
    # longest pause between two of its steps stays far below the reconstruction's
    # time (holding the GIL, the pause would be all of it).
    longest, last = 0.0, time.perf_counter()
    while not done.is_set():
        time.sleep(0.001)
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    worker.join()
    assert elapsed[0] > 0.2, "the cloud is too small to tell"
    assert longest < 0.5 * elapsed[0], (longest, elapsed[0])
