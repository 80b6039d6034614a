#!/usr/bin/env python3
"""Times two builds of `wideray_perf` against each other on a noisy machine.

    abba.py OLD NEW ROUNDS FILTER

Runs OLD and NEW one after the other, in the order OLD NEW, NEW OLD, OLD NEW, ... (ROUNDS rounds),
each with --benchmark_filter=FILTER and three repetitions, pinned to one CPU (CPU, default 0; "0,1"
for multithreaded benchmarks such as the builds), and prints per benchmark the ratio of the two
medians in every round and their geometric mean: above 1, NEW is faster. Keep a benchmark whose code
did not change in FILTER (`single` for a stream change, say): it shows how far the machine alone
moves the ratios. WIDERAY_SCENES defaults to ../shared/scenes; WIDERAY_TRAVERSAL_INPUT and
WIDERAY_TRAVERSAL_QUALITY pass through.
"""
import collections
import json
import math
import os
import subprocess
import sys
import tempfile


def medians(binary, benchmark_filter, cpu, env):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run(["taskset", "-c", cpu, binary, "--benchmark_filter=" + benchmark_filter,
                        "--benchmark_repetitions=3", "--benchmark_report_aggregates_only=true",
                        "--benchmark_out=" + out.name, "--benchmark_out_format=json"],
                       env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        text = open(out.name).read()
    results = json.loads(text)["benchmarks"] if text else []  # empty where the filter matched nothing
    return {b["run_name"]: b["real_time"] for b in results if b.get("aggregate_name") == "median"}


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    old, new, rounds, benchmark_filter = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    cpu = os.environ.get("CPU", "0")
    env = dict(os.environ)
    env.setdefault("WIDERAY_SCENES", "../shared/scenes")
    ratios = collections.defaultdict(list)
    for r in range(rounds):
        order = (old, new) if r % 2 == 0 else (new, old)
        times = {binary: medians(binary, benchmark_filter, cpu, env) for binary in order}
        for name, t in times[old].items():
            if name in times[new]:
                ratios[name].append(t / times[new][name])
        print("round %d of %d done" % (r + 1, rounds), file=sys.stderr)
    if not ratios:
        sys.exit("no benchmark matched " + benchmark_filter)
    for name, values in ratios.items():
        mean = math.exp(sum(math.log(v) for v in values) / len(values))
        print("%s: old / new %.3f  [%s]" % (name, mean, " ".join("%.3f" % v for v in values)))


if __name__ == "__main__":
    main()
