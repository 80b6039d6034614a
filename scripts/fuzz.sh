#!/usr/bin/env bash
# Runs each libFuzzer harness of BUILD for SECONDS (default 180), or for N inputs from a fixed random
# seed when SECONDS is runs:N (what CI does: the same inputs every time), seeded by the repository's
# own scene files and the dictionary of the scene format. The growing corpus stays in out/fuzz/<harness>/corpus;
# a crash, leak, timeout or sanitizer report is saved in out/fuzz/<harness>/ and fails the run.
set -uo pipefail
build="${1:?usage: scripts/fuzz.sh BUILD_DIR [SECONDS]}"
seconds="${2:-180}"
limit="-max_total_time=$seconds"
[[ "$seconds" == runs:* ]] && limit="-runs=${seconds#runs:} -seed=1"
root="$(cd "$(dirname "$0")/.." && pwd)"
status=0
for harness in scene_json_fuzzer trace_scene_fuzzer; do
  out="$root/out/fuzz/$harness"
  mkdir -p "$out/corpus" "$out/seeds"
  cp "$root"/scenes/*.json "$out/seeds/"
  echo "fuzz: $harness for $seconds (corpus out/fuzz/$harness/corpus)" >&2
  if ! "$build/$harness" "$out/corpus" "$out/seeds" -dict="$root/fuzz/scene.dict" $limit \
       -max_len=16384 -timeout=30 -rss_limit_mb=4096 -artifact_prefix="$out/" -print_final_stats=1 2> "$out/log.txt"; then
    echo "fuzz: $harness FAILED; input and report in out/fuzz/$harness/ (log.txt)" >&2
    tail -n 40 "$out/log.txt" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$out/log.txt" | sed "s/^/fuzz: $harness /" >&2
  fi
done
exit $status
