#!/usr/bin/env python3
"""Rays per second through the Python bindings against the C++ API, on the same rays and mesh.

    PYTHONPATH=build/python python3 scripts/library_bench.py [MESH] [--rays N] [--runs R] [--build DIR]

The Python path is what a user times: numpy origins and directions in, numpy t, prim_id, u, v out
(conversion included). The C++ path (build/wideray_library_bench) traces the same rays through
Scene::intersect with Threading::Parallel. Both trace on every core; medians of R runs after a warm-up.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import wideray


def rays_through(vertices, count, seed=7):
    """Rays from random points on the bounding sphere toward random points in the mesh's box
    (incoherent, most hit)."""
    rng = np.random.default_rng(seed)
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    center, radius = (low + high) / 2, np.linalg.norm(high - low) / 2
    on_sphere = rng.normal(size=(count, 3))
    on_sphere /= np.linalg.norm(on_sphere, axis=1, keepdims=True)
    origins = (center + 1.5 * radius * on_sphere).astype(np.float32)
    targets = low + (high - low) * rng.random((count, 3))
    return origins, (targets - origins).astype(np.float32)


def main():
    default_mesh = os.path.join(os.environ.get("WIDERAY_SCENES", "../shared/scenes"), "stanford-bunny", "bun_zipper.ply")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", default=default_mesh)
    parser.add_argument("--rays", type=int, default=1_000_000)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--build", default="build")
    args = parser.parse_args()

    vertices, faces = wideray.load_mesh(args.mesh)
    origins, directions = rays_through(vertices, args.rays)
    scene = wideray.Scene(vertices, faces)
    scene.build()
    python_seconds = []
    for run in range(args.runs + 1):
        start = time.perf_counter()
        t, prim_id, u, v = scene.intersect(origins, directions)
        if run:
            python_seconds.append(time.perf_counter() - start)
    hit_fraction = float((prim_id >= 0).mean())

    with tempfile.NamedTemporaryFile(suffix=".f32") as rays_file:
        np.hstack([origins, directions]).astype(np.float32).tofile(rays_file.name)
        out = subprocess.run([os.path.join(args.build, "wideray_library_bench"), args.mesh, rays_file.name,
                              str(args.runs)], check=True, capture_output=True, text=True).stdout
    cpp = json.loads(out)

    py_median, cpp_median = statistics.median(python_seconds), statistics.median(cpp["seconds"])
    print(f"mesh {args.mesh}: {len(faces)} triangles; {args.rays} rays ({hit_fraction:.0%} hit); "
          f"wideray {wideray.__version__}, {wideray.best_isa()}, {os.cpu_count()} hardware threads")
    print(f"{'path':8} {'median s':>9} {'Mrays/s':>8}")
    for name, seconds in (("C++", cpp_median), ("Python", py_median)):
        print(f"{name:8} {seconds:9.4f} {args.rays / seconds / 1e6:8.2f}")
    print(f"Python / C++ rate: {cpp_median / py_median:.2f}")


if __name__ == "__main__":
    sys.exit(main())
