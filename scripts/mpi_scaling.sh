#!/usr/bin/env bash
# Ranks x threads for distributed rendering (docs/scaling.md): wall time of whole `wideray render`
# commands, one process against mpirun with ranks x threads, median of RUNS runs, printed as a
# Markdown table. Usage: scripts/mpi_scaling.sh [BUILD] [RUNS] [CONFIGS]
# CONFIGS: "ranksxthreads ..." (0 ranks: a plain render without mpirun).
set -euo pipefail
build="${1:-build}" runs="${2:-3}" configs="${3:-0x2 1x2 2x1 2x2 3x1 4x1}"
scenes_dir="${WIDERAY_SCENES:-../shared/scenes}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

workloads=("one frame: default scene 1280x960, 16 spp|scenes/default.json --size 1280x960 --spp 16"
           "batch: orbit.json, 48 frames of 480x360|scenes/orbit.json")
[ -d "$scenes_dir/crytek-sponza" ] &&
  workloads+=("one frame: sponza_interior.json 1024x1024, path tracer 4 spp|scenes/sponza_interior.json --size 1024x1024 --integrator path --spp 4")

median() { sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
seconds() {  # ranks threads args...
  local ranks="$1" threads="$2"; shift 2
  local start end
  start=$(date +%s.%N)
  if [ "$ranks" = 0 ]; then
    "$build/wideray" render "$@" --threads "$threads" -o "$work/out" >/dev/null 2>&1
  else
    mpirun --allow-run-as-root --oversubscribe --bind-to none -np "$ranks" "$build/wideray" render "$@" --threads "$threads" \
      -o "$work/out" >/dev/null 2>&1
  fi
  end=$(date +%s.%N)
  awk "BEGIN {print $end - $start}"
}

header="| workload |"; rule="| --- |"
for c in $configs; do
  r="${c%x*}" t="${c#*x}"
  [ "$r" = 0 ] && header+=" 1 process x $t threads |" || header+=" mpirun $r x $t |"
  rule+=" --- |"
done
echo "$header"; echo "$rule"
for w in "${workloads[@]}"; do
  name="${w%%|*}" args="${w#*|}"
  row="| $name |"
  base=""
  for c in $configs; do
    r="${c%x*}" t="${c#*x}"
    # shellcheck disable=SC2086
    s=$(for i in $(seq "$runs"); do seconds "$r" "$t" $args; done | median)
    [ -z "$base" ] && base="$s"
    row+=" $(printf '%.2f s (%.2fx)' "$s" "$(awk "BEGIN {print $base / $s}")") |"
    echo "  $name, $c: $s s" >&2
  done
  echo "$row"
done
