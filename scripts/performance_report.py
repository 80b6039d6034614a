#!/usr/bin/env python3
"""Turns the JSON written by `wideray bench --json` into docs/performance.md and its bar chart.

    performance_report.py merge OUT IN...
        Joins several bench runs (the thread-scaling runs, one per thread count) into one file.
    performance_report.py report --bench B --scaling S --command CMD... --markdown MD --chart SVG
        Writes the report (machine, commands, Mrays/s ours vs Embree, builds, thread scaling) and an
        SVG bar chart of the best kernel of each backend per scene and ray kind.

Python 3 standard library only, so that `make bench` needs nothing beyond python3.
"""
import argparse
import json
import math
import os
import sys
from collections import OrderedDict
from xml.sax.saxutils import escape

RAY_KINDS = ("primary", "shadow", "diffuse", "bounce")
OUR_KERNELS = ("scalar", "single", "packet4", "packet8", "packet16", "packet256", "stream", "drst", "single+cache",
               "packet4+cache", "packet8+cache", "packet16+cache", "packet256+cache")
ANALYSIS_FILE = "performance-analysis.md"


# ----------------------------------------------------------------------------------------------
# Reading and merging bench JSON


def load(path):
    with open(path) as f:
        return json.load(f)


def merge(out_path, in_paths):
    """One document holding every run's results and builds; each build record gains `threads`."""
    docs = [load(p) for p in in_paths]
    if not docs:
        sys.exit("merge: no input files")
    machine = dict(docs[0]["machine"])
    machine["threads"] = sorted({d["machine"]["threads"] for d in docs})
    merged = {"machine": machine, "size": docs[0]["size"], "results": [], "builds": []}
    for d in docs:
        merged["results"].extend(d["results"])
        for b in d["builds"]:
            merged["builds"].append(dict(b, threads=d["machine"]["threads"]))
    temp = out_path + ".tmp"
    with open(temp, "w") as f:
        json.dump(merged, f, indent=2)
        f.write("\n")
    os.replace(temp, out_path)


def embree_counterpart(our_kernel, ray_kind):
    """The Embree entry point `wideray bench` compares one of our kernels with."""
    # packet256 has no Embree counterpart of its size: it is compared with Embree's widest packet. A
    # kernel with the shadow cache (+cache) is compared with the entry point of the kernel without it.
    our_kernel = our_kernel.removesuffix("+cache")
    name = {"scalar": "rtcIntersect1", "single": "rtcIntersect1",
            "packet256": "rtcIntersect16", "stream": "rtcIntersect1M", "drst": "rtcIntersect1M"}.get(our_kernel)
    if name is None and our_kernel.startswith("packet"):
        name = "rtcIntersect" + our_kernel[len("packet"):]
    if name and ray_kind == "shadow":
        name = name.replace("Intersect", "Occluded")
    return name


def scenes_in_order(records):
    return list(OrderedDict((r["scene"], None) for r in records))


def index_results(results):
    """(scene, ray kind, backend) -> {kernel label: record}; ours are labelled with the ISA when
    several ISAs were measured (bench --all-isas). Every kernel keeps the faster of its builds (ours:
    fast or high quality, 8 or 16 wide; Embree's: medium or high; the record's "quality" and "accel")."""
    isas = {r["isa"] for r in results if r["backend"] == "wideray"}
    table = {}
    for r in results:
        label = r["kernel"]
        if r["backend"] == "wideray" and len(isas) > 1:
            label = "%s (%s)" % (r["kernel"], r["isa"])
        records = table.setdefault((r["scene"], r["ray_kind"], r["backend"]), {})
        if label not in records or r["mrays_per_s"] > records[label]["mrays_per_s"]:
            records[label] = r
    return table


def build_name(record, default):
    """The build a record was measured on: its quality, and the width of ours where not the 8-wide BVH."""
    name = record.get("quality", default)
    if record.get("accel", "bvh8") not in ("bvh8", "embree"):
        name += ", " + record["accel"]
    return name


def build_label(label, record):
    """A kernel with the build it was fastest on."""
    return "%s, %s" % (label, build_name(record, "")) if "quality" in record else label


def workload(record):
    """"scene" for scene files seen from their own camera (interiors), "framed" for bare meshes."""
    return record.get("workload", "framed")


def best(records):
    """The (label, record) with the most Mrays/s, or None."""
    if not records:
        return None
    return max(records.items(), key=lambda item: item[1]["mrays_per_s"])


# ----------------------------------------------------------------------------------------------
# Markdown


def mrays(value):
    return "%.1f" % value if value >= 10 else "%.2f" % value


def ratio(ours, theirs):
    if not theirs:
        return "n/a"
    r = ours / theirs
    text = "%.2f×" % r
    return "**%s**" % text if r >= 1.0 else text


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(" --- " for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def machine_section(bench, scaling):
    m = bench["machine"]
    rows = [
        ("CPU", m["cpu"]),
        ("hardware threads", m["cores"]),
        ("threads used (comparison)", m["threads"]),
        ("our ISA", m["isa"]),
        ("image size (rays per set)", bench["size"]),
    ]
    if scaling:
        rows.append(("threads used (scaling)", ", ".join(str(t) for t in scaling["machine"]["threads"])))
    return "## Machine\n\n" + md_table(("", ""), rows)


def wrap_command(command, width=100):
    """Breaks a long command line between words with backslash-newlines, which the shell ignores."""
    lines, line = [], ""
    for word in command.split(" "):
        if line and len(line) + 1 + len(word) > width - 2:
            lines.append(line + " \\")
            line = "   "
        line = word if not line else line + " " + word
    return "\n".join(lines + [line])


def commands_section(commands):
    body = "\n".join(wrap_command(c) for c in commands)
    return ("## Commands\n\n`make bench` ran these commands from the repository root, after a Release build, "
            "then `scripts/performance_report.py report` wrote this file:\n\n```sh\n%s\n```" % body)


METHOD = """## How the rays are made

Every kernel, ours and Embree's, traces the same ray set in the same process with the same threads
(oneTBB, 4096 rays per task), flush-to-zero and denormals-are-zero in every task (run inside a
oneTBB arena made after setting them: oneTBB gives each task the mode its arena captured). Each
measurement is one warm-up and then the median of the timed runs; builds too.

- A scene file gives the camera and the first point light. A bare mesh (OBJ, PLY, glTF) is framed by
  this rule: c = center and R = half the diagonal of the mesh bounds; eye = c + normalize(0.3, 0.25,
  1.0) * 1.2R; look at c; up (0, 1, 0); vertical field of view 50 degrees; point light at
  c + (0.5R, 2R, 0.7R).
- **primary**: one ray through each pixel center, in 16x16 tiles in Hilbert order and Morton order
  inside a tile (coherent).
- **shadow**: from each primary hit toward the light, any-hit, tnear = 1e-3 R, tfar = the distance to
  the light (coherent).
- **diffuse**: from each primary hit, one cosine-weighted direction about the geometric normal turned
  toward the camera, tnear = 1e-3 R, seeded by the pixel (incoherent).
- **bounce**: the rays of bounces 2 to 4 of the path tracer (`"integrator": "path"`) at one sample
  per pixel from the same camera, over the scene's materials, tile after tile as the renderer traces
  them (incoherent: origins all over the scene, directions sampled from the materials).

Our kernels traverse an 8-wide BVH (our fast build). Embree builds once at `RTC_BUILD_QUALITY_MEDIUM`
and once at `RTC_BUILD_QUALITY_HIGH` (spatial splits); every Embree entry point traces both, is called
with the coherent flag for primary and shadow rays, and the faster of its two builds is the one we are
compared with. Ratios are ours / Embree: above 1 (bold) we are faster."""


def summary_section(bench, table, chart_name):
    rows = {"scene": [], "framed": []}
    for scene in scenes_in_order(bench["results"]):
        for kind in RAY_KINDS:
            ours = best(table.get((scene, kind, "wideray")))
            theirs = best(table.get((scene, kind, "embree")))
            if not ours or not theirs:
                continue
            rows[workload(ours[1])].append((scene, "{:,}".format(ours[1]["triangles"]), kind,
                                            "%s (%s)" % (mrays(ours[1]["mrays_per_s"]), build_label(*ours)),
                                            "%s (%s)" % (mrays(theirs[1]["mrays_per_s"]), build_label(*theirs)),
                                            ratio(ours[1]["mrays_per_s"], theirs[1]["mrays_per_s"])))
    header = ("scene", "triangles", "rays", "ours, Mrays/s (kernel, build)", "Embree, Mrays/s (kernel, build)",
              "ours / Embree")
    parts = ["## Best against best\n\nMrays/s of the fastest kernel of each backend for each scene and ray kind; "
             "every kernel is traced on each build (ours: fast and high quality, 8 and 16 children per node, "
             "the 16-wide BVH named where it was faster; Embree's: medium and high) "
             "and the faster counts "
             "(chart: [%s](%s))." % (chart_name, chart_name)]
    if rows["scene"]:
        parts.append("### Interior views (scene files with their own cameras)\n\n" + md_table(header, rows["scene"]))
    if rows["framed"]:
        parts.append("### Framed meshes (seen from outside)\n\n" + md_table(header, rows["framed"]))
    parts.append("![Mrays/s, best kernel of each backend](%s)" % chart_name)
    return "\n\n".join(parts)


def our_labels(table, scene):
    """Our kernel labels measured on a scene, in the registry's order."""
    labels = []
    for kind in RAY_KINDS:
        for label in table.get((scene, kind, "wideray"), {}):
            if label not in labels:
                labels.append(label)
    return sorted(labels, key=lambda l: (OUR_KERNELS.index(l.split(" ")[0]) if l.split(" ")[0] in OUR_KERNELS else 99, l))


def kernel_section(bench, table):
    parts = ["## Kernel against kernel\n\nMrays/s. Each of our kernels next to its Embree counterpart: single "
             "ray and the scalar reference against `rtcIntersect1`, packetK against `rtcIntersectK` "
             "(`rtcOccludedK` for shadow rays), packet256 against `rtcIntersect16`, stream against "
             "`rtcIntersect1M`. Each number is that of the kernel's fastest build (ours: fast or high quality, "
             "8 or 16 children per node, the 16-wide BVH named where it was faster; Embree's: medium or high)."]
    for scene in scenes_in_order(bench["results"]):
        header = ["ours", "Embree"]
        for kind in RAY_KINDS:
            header += ["%s ours" % kind, "%s Embree" % kind, "%s ratio" % kind]
        labels = our_labels(table, scene)
        rows = []
        for label in labels:
            kernel = label.split(" ")[0]
            row = [label, embree_counterpart(kernel, "primary") or ""]
            for kind in RAY_KINDS:
                ours = table.get((scene, kind, "wideray"), {}).get(label)
                theirs = table.get((scene, kind, "embree"), {}).get(embree_counterpart(kernel, kind))
                row += ["%s (%s)" % (mrays(ours["mrays_per_s"]), build_name(ours, "fast")) if ours else "",
                        "%s (%s)" % (mrays(theirs["mrays_per_s"]), theirs.get("quality", "medium")) if theirs else "",
                        ratio(ours["mrays_per_s"], theirs["mrays_per_s"]) if ours and theirs else ""]
            rows.append(row)
        triangles = next(r["triangles"] for r in bench["results"] if r["scene"] == scene)
        parts.append("### %s (%s triangles)\n\n%s" % (scene, "{:,}".format(triangles), md_table(header, rows)))
    return "\n\n".join(parts)


def work_section(bench, table):
    """Our kernels' work per ray (bench --counters), next to their speed."""
    if not any("nodes_per_ray" in r for r in bench["results"]):
        return None
    parts = ["## Work per ray\n\nOur kernels' traversal work (`wideray bench --counters`), "
             "per ray: inner nodes whose children were box-tested, leaves entered, triangle slots tested (a "
             "4-triangle block counts 4), for the build each kernel was fastest on. Packet kernels count a node "
             "for every ray active when the packet visits it; packet256 counts interval tests of inner nodes for "
             "every unfinished ray of the 256. Shadow rays stop at the first occluder; the kernels with the shadow cache (`+cache`) are not counted."]
    for scene in scenes_in_order(bench["results"]):
        header = ["ours"]
        for kind in RAY_KINDS:
            header += ["%s Mrays/s" % kind, "%s nodes" % kind, "%s leaves" % kind, "%s triangles" % kind]
        labels = our_labels(table, scene)
        rows = []
        for label in labels:
            row = [label]
            for kind in RAY_KINDS:
                r = table.get((scene, kind, "wideray"), {}).get(label)
                if r and "nodes_per_ray" in r:
                    row += [mrays(r["mrays_per_s"]), "%.1f" % r["nodes_per_ray"], "%.2f" % r["leaves_per_ray"],
                            "%.1f" % r["primitives_per_ray"]]
                else:
                    row += ["", "", "", ""]
            rows.append(row)
        parts.append("### %s\n\n%s" % (scene, md_table(header, rows)))
    return "\n\n".join(parts)


def builds_by_scene(builds):
    out = OrderedDict()
    for b in builds:
        width = "" if b.get("accel", "bvh8") in ("bvh8", "embree") else b["accel"] + "-"
        out.setdefault(b["scene"], {})[b["backend"] + "-" + width + b.get("quality", "fast")] = b
    return out


def build_section(bench):
    rows = []
    for scene, b in builds_by_scene(bench["builds"]).items():
        ours, ours_high = b.get("wideray-fast"), b.get("wideray-high")
        medium, high = b.get("embree-medium"), b.get("embree-high")
        if not ours:
            continue

        def ms(x):
            return "%.1f" % (x["seconds"] * 1e3) if x else ""

        def mb(x):
            return "%.1f" % (x["bytes"] / 1e6) if x else ""

        def faster(theirs, mine):
            return "%.2f×" % (theirs["seconds"] / mine["seconds"]) if theirs and mine and mine["seconds"] > 0 else ""

        def refs(x):
            return "%.3f" % (x["references"] / ours["references"]) if x and "references" in x and ours.get("references") else ""

        rows.append((scene, ms(ours), mb(ours), ms(ours_high), mb(ours_high), refs(ours_high), ms(medium), mb(medium),
                     ms(high), mb(high), faster(medium, ours), faster(high, ours_high),
                     "%.2f×" % (ours["bytes"] / medium["bytes"]) if medium and medium["bytes"] else ""))
    return ("## Builds and memory\n\nBuild time on all threads of the comparison run (the median of as many "
            "builds as timed runs, after a warm-up build, the builders taken in turn), and the memory of the "
            "acceleration structure (ours: binned SAH binary BVH collapsed to 8 wide, with leaf triangle "
            "blocks; high quality adds spatial splits, references per triangle say how many triangles "
            "they duplicate; the 16-wide BVH, also traced, is the same binary build collapsed to 16 wide, "
            "its builds in the JSON). Build speed ratios are Embree's time / ours, fast against medium and high "
            "against high (above 1 we build faster); the memory ratio is ours (fast) / Embree medium "
            "(below 1 we use less).\n\n"
            + md_table(("scene", "ours fast ms", "ours fast MB", "ours high ms", "ours high MB",
                        "high: references per triangle", "Embree medium ms", "Embree medium MB", "Embree high ms",
                        "Embree high MB", "build speed: fast vs medium", "build speed: high vs high",
                        "memory vs medium"), rows))


def scaling_section(scaling):
    thread_counts = scaling["machine"]["threads"]
    top = max(thread_counts)
    table = {}
    for r in scaling["results"]:
        kernel = build_label(r["kernel"], r) if r["backend"] == "embree" else r["kernel"]
        table.setdefault((r["scene"], r["ray_kind"], r["backend"], kernel), {})[r["threads"]] = r
    rows = []
    for scene in scenes_in_order(scaling["results"]):
        for kind in RAY_KINDS:
            for backend in ("wideray", "embree"):
                # The kernel that is fastest with all threads, followed down to one thread.
                candidates = {k[3]: v for k, v in table.items() if k[:3] == (scene, kind, backend) and top in v}
                if not candidates:
                    continue
                kernel = max(candidates, key=lambda k: candidates[k][top]["mrays_per_s"])
                runs = candidates[kernel]
                one = runs.get(1, {}).get("mrays_per_s")
                for t in thread_counts:
                    if t not in runs:
                        continue
                    speed = runs[t]["mrays_per_s"]
                    speedup = speed / one if one else None
                    rows.append((scene, kind, "%s %s" % ("ours" if backend == "wideray" else "Embree", kernel), t,
                                 mrays(speed), "%.2f×" % speedup if speedup else "",
                                 "%.0f%%" % (100 * speedup / t) if speedup else ""))
    build_rows = []
    builds = {}
    for b in scaling["builds"]:
        who = ("ours " if b["backend"] == "wideray" else "Embree ") + b.get("quality", "fast")
        builds.setdefault((b["scene"], who), {})[b["threads"]] = b["seconds"]
    for (scene, who), by_threads in builds.items():
        one = by_threads.get(1)
        for t in thread_counts:
            if t in by_threads:
                speedup = one / by_threads[t] if one and by_threads[t] > 0 else None
                build_rows.append((scene, who, t, "%.1f" % (by_threads[t] * 1e3),
                                   "%.2f×" % speedup if speedup else "",
                                   "%.0f%%" % (100 * speedup / t) if speedup else ""))
    return ("## Thread scaling\n\nThe same comparison with 1 to %d threads. Speed-up is against one thread; "
            "parallel efficiency is speed-up / threads. Each backend is shown with its kernel that is fastest "
            "on all %d threads.\n\n" % (top, top)
            + md_table(("scene", "rays", "kernel", "threads", "Mrays/s", "speed-up", "efficiency"), rows)
            + "\n\nBVH builds:\n\n"
            + md_table(("scene", "builder", "threads", "ms", "speed-up", "efficiency"), build_rows))


def markdown(bench, scaling, commands, chart_name):
    table = index_results(bench["results"])
    sections = [
        "# Performance: wideray against Embree\n\n"
        "Generated by `make bench` (scripts/performance_report.py) from the JSON that `wideray bench` writes; "
        "do not edit by hand, rerun it. Where we win and lose, and why, is discussed in "
        "[%s](%s), written by hand." % (ANALYSIS_FILE, ANALYSIS_FILE),
        machine_section(bench, scaling),
        commands_section(commands),
        METHOD,
        summary_section(bench, table, chart_name),
        kernel_section(bench, table),
        work_section(bench, table),
        build_section(bench),
    ]
    sections = [section for section in sections if section]
    if scaling:
        sections.append(scaling_section(scaling))
    return "\n\n".join(sections) + "\n"


# ----------------------------------------------------------------------------------------------
# SVG bar chart: one panel per ray kind, two bars (ours, Embree) per scene, each panel to its own
# linear scale.

OURS_COLOR, EMBREE_COLOR = "#2f6db5", "#e08a2c"
PANEL_WIDTH, LABEL_WIDTH, ROW_HEIGHT, BAR_HEIGHT = 390, 170, 46, 16
TOP, BOTTOM = 96, 40


def axis_scale(value):
    """The axis end (the smallest of 1, 2, 5 or 10 times a power of ten that is >= value) and a
    number of grid intervals that gives round tick values."""
    if value <= 0:
        return 1.0, 5
    power = 10.0 ** math.floor(math.log10(value))
    step = next(s for s in (1, 2, 5, 10) if s * power >= value)
    return step * power, 4 if step == 2 else 5


def text(x, y, content, size=12, anchor="start", weight="normal", color="#222"):
    return ('<text x="%.1f" y="%.1f" font-size="%d" text-anchor="%s" font-weight="%s" fill="%s">%s</text>'
            % (x, y, size, anchor, weight, color, escape(content)))


def chart(bench):
    table = index_results(bench["results"])
    scenes = scenes_in_order(bench["results"])
    kinds = [k for k in RAY_KINDS if any((s, k, "wideray") in table for s in scenes)]
    width = LABEL_WIDTH + len(kinds) * PANEL_WIDTH + 20
    height = TOP + len(scenes) * ROW_HEIGHT + BOTTOM
    m = bench["machine"]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d" '
           'font-family="DejaVu Sans, Helvetica, Arial, sans-serif">' % (width, height, width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           text(10, 22, "Mrays/s, best kernel of each backend (higher is better)", 16, weight="bold"),
           text(10, 42, "%s, %d threads, our ISA %s, %s rays per set" % (m["cpu"], m["threads"], m["isa"],
                                                                          bench["size"]), 12, color="#555")]
    legend_x = width - 250
    out.append('<rect x="%d" y="12" width="14" height="12" fill="%s"/>' % (legend_x, OURS_COLOR))
    out.append(text(legend_x + 20, 22, "wideray", 12))
    out.append('<rect x="%d" y="12" width="14" height="12" fill="%s"/>' % (legend_x + 100, EMBREE_COLOR))
    out.append(text(legend_x + 120, 22, "Embree", 12))
    for row, scene in enumerate(scenes):
        y = TOP + row * ROW_HEIGHT
        if row % 2 == 0:
            out.append('<rect x="0" y="%d" width="%d" height="%d" fill="#f4f4f4"/>' % (y, width, ROW_HEIGHT))
        out.append(text(LABEL_WIDTH - 8, y + ROW_HEIGHT / 2 + 4, scene, 12, anchor="end"))
    for column, kind in enumerate(kinds):
        x0 = LABEL_WIDTH + column * PANEL_WIDTH
        bars = {s: (best(table.get((s, kind, "wideray"))), best(table.get((s, kind, "embree")))) for s in scenes}
        top_value = max([b[1]["mrays_per_s"] for pair in bars.values() for b in pair if b] + [0])
        scale_max, intervals = axis_scale(top_value * 1.25)  # room for the value labels
        plot_width = PANEL_WIDTH - 30
        out.append(text(x0 + plot_width / 2, TOP - 24, kind + " rays", 14, anchor="middle", weight="bold"))
        axis_y = TOP + len(scenes) * ROW_HEIGHT
        for i in range(intervals + 1):
            value = scale_max * i / intervals
            x = x0 + plot_width * i / intervals
            out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ccc" stroke-width="1"/>'
                       % (x, TOP - 8, x, axis_y))
            out.append(text(x, axis_y + 16, ("%g" % value), 11, anchor="middle", color="#555"))
        for row, scene in enumerate(scenes):
            ours, theirs = bars[scene]
            y = TOP + row * ROW_HEIGHT + (ROW_HEIGHT - 2 * BAR_HEIGHT) / 2
            for i, (entry, color) in enumerate(((ours, OURS_COLOR), (theirs, EMBREE_COLOR))):
                if not entry:
                    continue
                value = entry[1]["mrays_per_s"]
                w = plot_width * value / scale_max
                out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%d" fill="%s"><title>%s</title></rect>'
                           % (x0, y + i * BAR_HEIGHT, w, BAR_HEIGHT - 2, color,
                              escape("%s %s %s: %.2f Mrays/s" % (scene, kind, entry[0], value))))
                label = mrays(value)
                if i == 0 and theirs and theirs[1]["mrays_per_s"] > 0:
                    label += "  (%.2f×)" % (value / theirs[1]["mrays_per_s"])
                out.append(text(x0 + w + 4, y + i * BAR_HEIGHT + BAR_HEIGHT - 5, label, 11))
        out.append(text(x0 + plot_width / 2, axis_y + 32, "Mrays/s", 11, anchor="middle", color="#555"))
    out.append("</svg>")
    return "\n".join(out) + "\n"


# ----------------------------------------------------------------------------------------------


def write(path, content):
    if os.path.dirname(path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
    temp = path + ".tmp"
    with open(temp, "w", encoding="utf-8") as f:
        f.write(content)
    os.replace(temp, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="action", required=True)
    m = sub.add_parser("merge", help="join bench JSON files (one per thread count) into one")
    m.add_argument("out")
    m.add_argument("inputs", nargs="+")
    r = sub.add_parser("report", help="write the Markdown report and the SVG chart")
    r.add_argument("--bench", required=True, help="JSON of the comparison run")
    r.add_argument("--scaling", help="merged JSON of the thread-scaling runs")
    r.add_argument("--command", action="append", default=[], help="a command line that produced the JSON")
    r.add_argument("--markdown", required=True)
    r.add_argument("--chart", required=True)
    args = parser.parse_args()

    if args.action == "merge":
        merge(args.out, args.inputs)
        return
    bench = load(args.bench)
    scaling = load(args.scaling) if args.scaling else None
    chart_name = os.path.relpath(args.chart, os.path.dirname(os.path.abspath(args.markdown)) or ".")
    write(args.markdown, markdown(bench, scaling, args.command, chart_name))
    write(args.chart, chart(bench))


if __name__ == "__main__":
    main()
