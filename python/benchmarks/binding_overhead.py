# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python binding's overhead on a reconstruction, against the C++ tool.

Two measures, on the same points and machine:
1. Within each Python call: the call's wall time against the time of
   CoconeReconstruction::reconstruct inside it (report["timings"]["reconstruct"],
   timed as the tool times its computing stage). The difference is the binding's own
   work: the conversion of the numpy array into the PCL cloud and the result's arrays.
   Both times come from the same run, so a loaded machine hardly blurs it.
2. Against the tool, in interleaved runs (tool, Python, Python, tool, ...), each in a
   fresh process: pcl_cocone_reconstruction prints the time of its stage "Computing
   the COCONE surface" (the same reconstruct: no loading, no writing); Python times
   pcl_cocone.reconstruct(points) as a user sees it (the report's topology, built on
   first use, is not asked for). Each pair gives a ratio Python / tool. On a machine
   shared with other builds this ratio carries their noise.

    PYTHONPATH=build/python /usr/bin/python3 python/benchmarks/binding_overhead.py \\
        --tool build/tools/pcl_cocone_reconstruction --points 1000000 --pairs 7

The points are a sphere of area-uniform random samples (seeded), written once as a
binary PCD that both sides read; --input takes any file the tools read instead.
"""
import argparse
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile

import numpy as np

PYTHON_RUN = r"""
import sys, time
import pcl_cocone
points = pcl_cocone.load_points(sys.argv[1])
start = time.perf_counter()
mesh = pcl_cocone.reconstruct(points)
elapsed = time.perf_counter() - start
inner = mesh.report["timings"]["reconstruct"]
print(f"{elapsed * 1000:.3f} {inner * 1000:.3f} {len(mesh.triangles)}")
"""


def write_binary_pcd(path, points):
    header = ("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
              "COUNT 1 1 1\nWIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\n"
              "DATA binary\n").format(n=len(points))
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(np.ascontiguousarray(points, dtype="<f4").tobytes())


def sphere(n, seed):
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1, keepdims=True)


def run_tool(tool, input_path, output_path):
    result = subprocess.run([tool, input_path, output_path], check=True,
                            capture_output=True, text=True)
    text = re.sub(r"\x1b\[[0-9;]*m", "", result.stdout)
    match = re.search(r"Computing the COCONE surface \[done, ([0-9.e+]+) ms : (\d+) "
                      r"triangles\]", text)
    if not match:
        sys.exit(f"no stage time in the tool's output:\n{text}")
    return float(match.group(1)), int(match.group(2))


def run_python(input_path):
    result = subprocess.run([sys.executable, "-c", PYTHON_RUN, input_path], check=True,
                            capture_output=True, text=True)
    milliseconds, inner_milliseconds, triangles = result.stdout.split()
    return float(milliseconds), float(inner_milliseconds), int(triangles)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tool", required=True, help="pcl_cocone_reconstruction")
    parser.add_argument("--points", type=int, default=1_000_000,
                        help="size of the generated sphere (default 1000000)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--input", help="a point file instead of the generated sphere")
    parser.add_argument("--pairs", type=int, default=5, help="tool/Python pairs")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as folder:
        input_path = args.input
        if not input_path:
            input_path = os.path.join(folder, "points.pcd")
            write_binary_pcd(input_path, sphere(args.points, args.seed))
        output_path = os.path.join(folder, "mesh.ply")
        ratios, inner_ratios = [], []
        source = args.input if args.input else f"{args.points} random sphere points"
        print(f"input {source}, {args.pairs} interleaved pairs, {os.cpu_count()} cores")
        print("pair  tool ms    python ms  (inside: reconstruct ms, ratio)  python/tool")
        for pair in range(args.pairs):
            # Alternate which side goes first, so that neither always runs on a machine
            # warmed (or loaded) by the other.
            if pair % 2 == 0:
                tool_ms, tool_triangles = run_tool(args.tool, input_path, output_path)
                python_ms, inner_ms, python_triangles = run_python(input_path)
            else:
                python_ms, inner_ms, python_triangles = run_python(input_path)
                tool_ms, tool_triangles = run_tool(args.tool, input_path, output_path)
            if tool_triangles != python_triangles:
                sys.exit(f"different results: tool {tool_triangles} triangles, Python "
                         f"{python_triangles}")
            ratios.append(python_ms / tool_ms)
            inner_ratios.append(python_ms / inner_ms)
            print(f"{pair + 1:<5} {tool_ms:<10.1f} {python_ms:<10.1f} ({inner_ms:<10.1f} "
                  f"{inner_ratios[-1]:.5f})       {ratios[-1]:.4f}", flush=True)
        print(f"triangles {tool_triangles}")
        print(f"within the call: python / reconstruct median "
              f"{statistics.median(inner_ratios):.5f} (min {min(inner_ratios):.5f}, max "
              f"{max(inner_ratios):.5f}): overhead "
              f"{100 * (statistics.median(inner_ratios) - 1):+.3f}%")
        print(f"against the tool: python / tool median {statistics.median(ratios):.4f} "
              f"(min {min(ratios):.4f}, max {max(ratios):.4f})")

if __name__ == "__main__":
    main()
