#!/usr/bin/python3
"""The Python call's cost against the C++ call: mesh_ccd on a million-candidate
list (the built-in cloth scene's step 76 after the swept-box broad phase),
steady state (each side reuses its result: out= in Python, a kept
BatchResult in C++), the same options (the defaults: conservative mode, one
result per candidate, every thread) and the same arrays in one process.

    PYTHONPATH=build/python:build/python/bench /usr/bin/python3 python/bench/overhead.py [--calls 301]

The two sides alternate call by call (which goes first alternating too),
so that a neighbour's load falls on both; each side's figure is its median
call (and its best), and the overhead the median of the paired differences.
Last, the same calls on empty candidate lists measure the call's fixed cost
apart from the work, which the neighbours' noise hides in the full call. The C++ side
(bench/timing_module.cpp) times mesh_ccd alone; the Python side times the
whole batchccd.mesh_ccd call as a script sees it.
"""
import argparse
import statistics
import tempfile
import time

import numpy as np

import batchccd
import batchccd_timing


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--candidates", type=int, default=1_000_000)
    parser.add_argument("--calls", type=int, default=301)
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        batchccd_timing.write_cloth_scene(directory, args.candidates)
        scene = batchccd.read_scene(directory)
    x0, x1 = np.asfortranarray(scene["x0"]), np.asfortranarray(scene["x1"])  # as an Eigen matrix holds them
    faces, vf, ee = scene["faces"], scene["vertex_face"], scene["edge_edge"]
    cpp = batchccd_timing.CppCaller(x0, x1, faces, vf, ee, args.threads)

    result = batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf, edge_edge=ee, threads=args.threads)  # warm-up
    cpp.call()
    python_seconds, cpp_seconds = [], []

    def python_call():
        start = time.perf_counter()
        batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf, edge_edge=ee, threads=args.threads, out=result)
        return time.perf_counter() - start

    for call in range(args.calls):
        # Which side goes first alternates too, against any order effect.
        if call % 2:
            python_seconds.append(python_call())
            cpp_seconds.append(cpp.call())
        else:
            cpp_seconds.append(cpp.call())
            python_seconds.append(python_call())
    assert result.earliest_toi == cpp.earliest_toi() and result.counters["hits"] == cpp.hits()

    print(f"{result.counters['candidates']:,} candidates ({len(vf):,} vertex-face, {len(ee):,} edge-edge), "
          f"{result.counters['hits']} hits, {args.calls} calls a side, threads={args.threads}")
    cpp_median, python_median = statistics.median(cpp_seconds), statistics.median(python_seconds)
    print(f"C++    median {cpp_median * 1e3:8.3f} ms, best {min(cpp_seconds) * 1e3:8.3f} ms")
    print(f"Python median {python_median * 1e3:8.3f} ms, best {min(python_seconds) * 1e3:8.3f} ms")
    print(f"Python / C++: median {python_median / cpp_median:.4f}, best {min(python_seconds) / min(cpp_seconds):.4f}")
    # Neighbours move single calls by more than the overhead: the median of
    # the paired differences (each Python call against the C++ call beside it)
    # is the steadier figure.
    difference = statistics.median(p - c for p, c in zip(python_seconds, cpp_seconds))
    print(f"median paired difference {difference * 1e6:+.1f} us = {difference / cpp_median * 100:+.2f} % of the C++ call")

    # The fixed cost apart from the work: the same call on empty candidate
    # lists (the same positions and faces, which both sides still check).
    no_vf, no_ee = vf[:0], ee[:0]
    cpp_empty = batchccd_timing.CppCaller(x0, x1, faces, no_vf, no_ee, args.threads)
    empty_python, empty_cpp = [], []
    for _ in range(20 * args.calls):
        empty_cpp.append(cpp_empty.call())
        start = time.perf_counter()
        batchccd.mesh_ccd(x0, x1, faces, vertex_face=no_vf, edge_edge=no_ee, threads=args.threads, out=result)
        empty_python.append(time.perf_counter() - start)
    fixed = statistics.median(empty_python) - statistics.median(empty_cpp)
    print(f"empty lists: C++ median {statistics.median(empty_cpp) * 1e6:.1f} us, Python "
          f"{statistics.median(empty_python) * 1e6:.1f} us: the Python call adds {fixed * 1e6:.1f} us "
          f"= {fixed / cpp_median * 100:.3f} % of the million-candidate C++ call")


if __name__ == "__main__":
    main()
