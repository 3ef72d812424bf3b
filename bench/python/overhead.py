#!/usr/bin/env python3
"""The Python call's overhead over the C++ call: edgefront.geodesic_distance (numpy in, numpy out,
argument checks, GIL release) against the C++ edgefront::geodesic_distance on views of the same
numpy buffers (timed inside the extension, so the same binary, process, mesh and cache state).

    PYTHONPATH=build/python /usr/bin/python3 bench/python/overhead.py [--repeats 15] [--methods mdf,fast,dijkstra,windows]
    PYTHONPATH=build/python /usr/bin/python3 bench/python/overhead.py --callgrind --methods mdf,dijkstra

The mesh is a torus (R = 1, r = 0.35) of 250 x 200 quads: 50,000 vertices, 100,000 faces. Each method runs `repeats` rounds; a round times the
Python call and the C++ call once each, alternating which goes first; the figure is the ratio of
the minima (the least disturbed run of each) and the median of per-round ratios.
Prints a Markdown table. Timings on a loaded machine scatter by several percent either way; with
--callgrind the script counts instructions instead (three runs under valgrind: mesh + Python call,
mesh + C++ call, mesh only), which does not depend on the load.
"""

import argparse
import os
import platform
import re
import statistics
import subprocess
import sys
import time

import numpy as np

import edgefront as ef
from edgefront import _edgefront

def torus(nu, nv, R=1.0, r=0.35):
    """A torus of nu x nv quads split into 2 nu nv triangles (closed, outward)."""
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    V = np.stack([(R + r * np.cos(vv)) * np.cos(uu), (R + r * np.cos(vv)) * np.sin(uu), r * np.sin(vv)], axis=-1)
    V = V.reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = i * nv + j
    b = ((i + 1) % nu) * nv + j
    c = ((i + 1) % nu) * nv + (j + 1) % nv
    d = i * nv + (j + 1) % nv
    F = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return V, F.astype(np.int32)


def one_call(which, method):
    """Builds the mesh and makes one call (the Python function, the C++ call, or none)."""
    V, F = torus(250, 200)
    if which == "py":
        ef.geodesic_distance(V, F, [0], method=method)
    elif which == "cpp":
        _edgefront._time_cpp_geodesic_distance(V, F, [0], method, 1)


def callgrind(method):
    """Instructions (valgrind --tool=callgrind, load-independent) of three runs of this script:
    mesh + Python call, mesh + C++ call, mesh only; the calls' costs are the differences."""
    ir = {}
    for which in ["none", "cpp", "py"]:
        r = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", sys.executable,
                            __file__, "--one", which, "--methods", method],
                           capture_output=True, text=True, env=dict(os.environ, PYTHONHASHSEED="0"))
        m = re.search(r"Collected : (\d+)", r.stderr)
        if r.returncode != 0 or not m:
            raise SystemExit(f"callgrind failed: {r.stderr[-2000:]}")
        ir[which] = int(m.group(1))
    cpp, py = ir["cpp"] - ir["none"], ir["py"] - ir["none"]
    print(f"| {method} | {cpp:,} | {py:,} | {py - cpp:+,} | {100 * (py / cpp - 1):+.3f}% |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--one", choices=["py", "cpp", "none"], help=argparse.SUPPRESS)
    ap.add_argument("--callgrind", action="store_true",
                    help="count instructions with valgrind instead of timing (slow: minutes)")
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--methods", default="mdf,fast,dijkstra,windows")
    args = ap.parse_args()
    if args.one:
        one_call(args.one, args.methods)
        return
    if args.callgrind:
        print("instructions (callgrind) of one call on the torus 250 x 200 (100,000 faces), beyond building the mesh:")
        print()
        print("| method | C++ call | Python call | difference | overhead |")
        print("|---|---|---|---|---|")
        for method in args.methods.split(","):
            callgrind(method)
        return
    V, F = torus(250, 200)
    print(f"mesh: torus 250 x 200: {len(V)} vertices, {len(F)} faces; "
          f"V float64, F int32; {args.repeats} rounds; {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the start")
    print()
    print("| method | C++ min (ms) | Python min (ms) | overhead (ratio of minima) | median of per-round ratios |")
    print("|---|---|---|---|---|")
    for method in args.methods.split(","):
        ef.geodesic_distance(V, F, [0], method=method)  # warm up (first-touch of pages, caches)
        py, cpp, ratios = [], [], []
        for i in range(args.repeats):
            order = [0, 1] if i % 2 == 0 else [1, 0]
            t = [0.0, 0.0]
            for which in order:
                if which == 0:
                    t0 = time.perf_counter()
                    d = ef.geodesic_distance(V, F, [0], method=method)
                    t[0] = time.perf_counter() - t0
                    assert d.shape == (len(V),)
                else:
                    t[1] = _edgefront._time_cpp_geodesic_distance(V, F, [0], method, 1)[0]
            py.append(t[0])
            cpp.append(t[1])
            ratios.append(t[0] / t[1])
        print(f"| {method} | {min(cpp) * 1e3:.1f} | {min(py) * 1e3:.1f} | {100 * (min(py) / min(cpp) - 1):+.2f}% "
              f"| {100 * (statistics.median(ratios) - 1):+.2f}% |")
    # The fixed cost of the Python layer (argument checks, numpy wrapping, GIL release), in
    # microseconds: a small torus, many calls, min of each.
    Vs, Fs = torus(10, 10)
    py, cpp = [], []
    for i in range(2000):
        t0 = time.perf_counter()
        ef.geodesic_distance(Vs, Fs, [0])
        py.append(time.perf_counter() - t0)
        cpp.append(_edgefront._time_cpp_geodesic_distance(Vs, Fs, [0], "mdf", 1)[0])
    print(f"\nfixed cost of the Python layer (torus 10 x 10, {len(Fs)} faces, mdf, min of 2000 calls): "
          f"C++ {min(cpp) * 1e6:.1f} us, Python {min(py) * 1e6:.1f} us, difference {(min(py) - min(cpp)) * 1e6:.1f} us")
    print(f"load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
