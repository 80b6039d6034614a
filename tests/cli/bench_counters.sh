#!/usr/bin/env bash
# wideray bench --counters through the real executable, on a tiny image of the default scene: every
# result of ours (closest-hit and occlusion) carries its work per ray, Embree's carry none.
set -eu
wideray="$1" scene="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$wideray" bench "$scene" --size 24x16 --runs 1 --threads 1 --counters --json "$work/bench.json" >"$work/out.txt" 2>/dev/null
grep -q "nodes/ray leaves/ray prims/ray" "$work/out.txt"
python3 - "$work/bench.json" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))["results"]
fields = ("nodes_per_ray", "leaves_per_ray", "primitives_per_ray")
counted = [r for r in results if r["backend"] == "wideray" and not r["kernel"].endswith("+cache")]  # no costs there
assert {r["ray_kind"] for r in counted} == {"primary", "shadow", "diffuse", "bounce"}, "a ray kind without results of ours"
for r in counted:
    assert all(r.get(f, 0) > 0 for f in fields), r
    assert r["leaves_per_ray"] <= r["primitives_per_ray"], r
for r in results:
    if r["backend"] == "embree" or r["kernel"].endswith("+cache"):
        assert not any(f in r for f in fields), r
print("ok   bench --counters: %d results with work per ray" % len(counted))
PY

# --accel: each structure's single-ray kernel is measured with its work per ray, and every result and
# build names its structure.
"$wideray" bench "$scene" --size 24x16 --runs 1 --threads 1 --counters --rays primary,shadow --backend wideray \
  --accel bvh4,kdtree,grid,rgrid --json "$work/accel.json" >/dev/null 2>&1
python3 - "$work/accel.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
accels = {"bvh8", "bvh4", "kdtree", "grid", "rgrid"}
assert {r["accel"] for r in doc["results"]} == accels, {r["accel"] for r in doc["results"]}
assert {b["accel"] for b in doc["builds"] if b["backend"] == "wideray"} == accels
hits = {}
for r in doc["results"]:
    if r["accel"] in ("kdtree", "grid", "rgrid"):
        assert r["kernel"] == "single" and "mailbox_hits_per_ray" in r and r["nodes_per_ray"] > 0, r
    hits.setdefault(r["ray_kind"], set()).add(r["hits"])
assert all(len(h) == 1 for h in hits.values()), hits  # every structure finds the same hits
print("ok   bench --accel: %d results over %d structures" % (len(doc["results"]), len(accels)))
PY
