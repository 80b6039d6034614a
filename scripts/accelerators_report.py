#!/usr/bin/env python3
"""Turns the JSON of `wideray bench --accel ...` into docs/accelerators.md: per scene, each structure's
build time, memory, Mrays/s on primary, shadow and diffuse rays and work per ray; then the course's
claims about the structures checked against those numbers.

    accelerators_report.py --bench B --command CMD... --markdown MD

Python 3 standard library only.
"""
import argparse
import statistics

from performance_report import load, machine_section, md_table, mrays, wrap_command, write

KINDS = ("primary", "shadow", "diffuse")
# (label, accel, kernel): the wide BVHs with their SIMD single-ray kernel and their plain-loop
# reference, then the course's structures, each traced one ray at a time.
ROWS = (
    ("bvh8 single", "bvh8", "single"), ("bvh8 scalar", "bvh8", "scalar"),
    ("bvh4 single", "bvh4", "single"), ("bvh4 scalar", "bvh4", "scalar"),
    ("bvh2", "bvh2", "single"), ("skip", "skip", "single"), ("kdtree", "kdtree", "single"),
    ("grid", "grid", "single"), ("hgrid", "hgrid", "single"), ("rgrid", "rgrid", "single"),
)
# The structures whose traversal is plain scalar code: the fair field for the course's claims.
SCALAR = ("bvh8 scalar", "bvh4 scalar", "bvh2", "skip", "kdtree", "grid", "hgrid", "rgrid")


def index(bench):
    results, builds = {}, {}
    for r in bench["results"]:
        if r["backend"] == "wideray" and r.get("quality", "fast") == "fast":
            results[(r["scene"], r.get("accel", "bvh8"), r["kernel"], r["ray_kind"])] = r
    for b in bench["builds"]:
        if b["backend"] == "wideray" and b["quality"] == "fast":
            builds[(b["scene"], b.get("accel", "bvh8"))] = b
    scenes = []
    for r in bench["results"]:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    return results, builds, scenes


def scene_section(scene, results, builds):
    rows = []
    for label, accel, kernel in ROWS:
        b = builds.get((scene, accel))
        if b is None:
            continue
        row = [label, "%.1f" % (b["seconds"] * 1e3), "%.1f" % (b["bytes"] / 1e6)]
        for kind in KINDS:
            r = results.get((scene, accel, kernel, kind))
            row.append(mrays(r["mrays_per_s"]) if r else "-")
        for kind in ("primary", "diffuse"):
            r = results.get((scene, accel, kernel, kind))
            if r and "nodes_per_ray" in r:
                row.append("%.1f / %.2f / %.1f / %.1f" % (r["nodes_per_ray"], r["leaves_per_ray"],
                                                         r["primitives_per_ray"], r.get("mailbox_hits_per_ray", 0)))
            else:
                row.append("-")
        rows.append(row)
    first = next(r for r in results.values() if r["scene"] == scene)
    header = ("structure", "build ms", "MB", "primary Mrays/s", "shadow", "diffuse",
              "primary: nodes or cells / leaves / tests / mailbox hits per ray", "diffuse: the same")
    return "### %s (%s, %d triangles)\n\n%s" % (scene, "interior" if first["workload"] == "scene" else "framed",
                                                  first["triangles"], md_table(header, rows))


def speed(results, scene, label, kind):
    accel, kernel = next((a, k) for l, a, k in ROWS if l == label)
    r = results.get((scene, accel, kernel, kind))
    return r["mrays_per_s"] if r else None


def build_ms(builds, scene, label):
    accel = next(a for l, a, _ in ROWS if l == label)
    b = builds.get((scene, accel))
    return b["seconds"] * 1e3 if b else None


def claims_section(results, builds, scenes):
    cells = [(s, k) for s in scenes for k in KINDS]
    fastest = {}
    for s, k in cells:
        speeds = {l: speed(results, s, l, k) for l in SCALAR}
        speeds = {l: v for l, v in speeds.items() if v}
        if speeds:
            fastest[(s, k)] = max(speeds, key=speeds.get)
    kd_first = sum(1 for v in fastest.values() if v == "kdtree")
    wins = sorted(((sum(1 for v in fastest.values() if v == l), l) for l in SCALAR), reverse=True)
    kd_vs_bvh2 = [speed(results, s, "kdtree", k) / speed(results, s, "bvh2", k) for s, k in cells
                  if speed(results, s, "kdtree", k) and speed(results, s, "bvh2", k)]
    kd_build = [build_ms(builds, s, "kdtree") / build_ms(builds, s, "bvh2") for s in scenes
                if build_ms(builds, s, "kdtree") and build_ms(builds, s, "bvh2")]
    grid_build = [build_ms(builds, s, "grid") / build_ms(builds, s, "bvh2") for s in scenes
                  if build_ms(builds, s, "grid") and build_ms(builds, s, "bvh2")]
    grid_rank = []
    for s, k in cells:
        speeds = sorted((v, l) for l in SCALAR if (v := speed(results, s, l, k)))
        labels = [l for _, l in reversed(speeds)]
        if "grid" in labels:
            grid_rank.append(labels.index("grid") + 1)
    hier = [max(speed(results, s, "hgrid", k), speed(results, s, "rgrid", k)) / speed(results, s, "grid", k)
            for s, k in cells if speed(results, s, "grid", k) and speed(results, s, "hgrid", k) and speed(results, s, "rgrid", k)]
    skip = {k: [speed(results, s, "skip", k) / speed(results, s, "bvh2", k) for s in scenes
                if speed(results, s, "skip", k) and speed(results, s, "bvh2", k)] for k in KINDS}
    med = lambda xs: statistics.median(xs) if xs else float("nan")
    lines = ["## The course's claims, checked", ""]
    lines.append(
        "- **kd-trees are fastest to traverse and slow to build.** Among the structures traced by plain scalar "
        "code (%s), the kd-tree is the fastest in %d of %d scene and ray-kind cells; against the binary BVH it "
        "traces %.2fx as many rays per second (median; from %.2fx to %.2fx). Its build takes %.1fx as long as "
        "the binary BVH's (median over the scenes). Cells in which each scalar structure is the fastest: %s." % (
            ", ".join(SCALAR), kd_first, len(fastest), med(kd_vs_bvh2), min(kd_vs_bvh2, default=0),
            max(kd_vs_bvh2, default=0), med(kd_build),
            ", ".join("%s %d" % (l, n) for n, l in wins if n)))
    lines.append(
        "- **Grids are fast to build, middle fast to traverse, and need hierarchy.** The uniform grid builds in "
        "%.2fx the binary BVH's time (median); among the %d scalar structures its rank (1 = fastest) is %s over "
        "the %d cells (median; best %d); the better of the hierarchical and recursive grids traces %.2fx as many rays as the uniform "
        "grid (median; %.2fx at best)." % (med(grid_build), len(SCALAR), "%g" % med(grid_rank), len(grid_rank), min(grid_rank, default=0),
                                          med(hier), max(hier, default=0)))
    lines.append(
        "- **Skip-pointer trees suit single-threaded code but cannot visit children in any order.** Against the "
        "binary BVH with its stack, the stackless skip tree traces %s (median over the scenes)." % ", ".join(
            "%.2fx on %s rays" % (med(v), k) for k, v in skip.items()))
    return "\n".join(lines)


def commands_section(commands):
    body = "\n".join(wrap_command(c) for c in commands)
    return ("## Commands\n\n`make bench-accelerators` (the last step of `make bench`) ran this from the repository "
            "root after a Release build; `scripts/accelerators_report.py` wrote this file from its JSON. Mrays/s are "
            "medians of the runs after a warm-up, on every thread of the machine.\n\n```sh\n%s\n```" % body)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", required=True)
    parser.add_argument("--command", action="append", default=[])
    parser.add_argument("--markdown", required=True)
    parser.add_argument("--why", help="a Markdown file with the explanations, appended after the claims")
    args = parser.parse_args()
    bench = load(args.bench)
    results, builds, scenes = index(bench)
    parts = ["# Acceleration structures side by side", "",
             "Generated by `make bench` (`scripts/accelerators_report.py`) from `out/accelerators.json`. Every "
             "structure returns the same hits, bit for bit (tests/test_accelerators.cpp); they differ in what "
             "they cost. All of ours trace one ray at a time here: the wide BVHs with their SIMD `single` "
             "kernel and their plain-loop `scalar` reference, the course's structures with their scalar "
             "kernels (`--accel` on render, info and bench). Builds are our fast ones (object splits).",
             "", machine_section(bench, None), "", commands_section(args.command), "",
             "## Per scene", "",
             "Work per ray: inner nodes visited (grids: cells walked), leaves (cells with primitives) entered, "
             "primitive tests (a BVH leaf block counts its 4 slots), and tests the mailbox saved.", ""]
    for scene in scenes:
        parts += [scene_section(scene, results, builds), ""]
    parts += [claims_section(results, builds, scenes), ""]
    if args.why:
        with open(args.why) as f:
            parts += [f.read()]
    write(args.markdown, "\n".join(parts) + "\n")


if __name__ == "__main__":
    main()
