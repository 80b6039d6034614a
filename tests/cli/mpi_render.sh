#!/usr/bin/env bash
# Distributed rendering through mpirun: every image is the single-process image bit for bit, whether the
# ranks share whole frames (a batch) or runs of one frame's tiles (fewer frames than ranks, more ranks
# than tiles); a bad scene in a batch fails alone, with its file named and a non-zero exit code.
set -eu
mpirun="$1" wideray="$2" image_equal="$3" scenes="$4"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# As root, OpenMPI needs --allow-run-as-root; --oversubscribe lets 3 ranks run on fewer cores;
# --bind-to none lets each rank's threads use every core.
ranks() { local n="$1"; shift; "$mpirun" --allow-run-as-root --oversubscribe --bind-to none -np "$n" "$wideray" render "$@"; }
same() {
  "$image_equal" "$1" "$2" || { echo "FAIL: $3: $2 differs from the single-process $1"; exit 1; }
  echo "ok   $3"
}

# One frame, fewer frames than ranks: runs of tiles on 2 and 3 ranks (color and the cost heatmap,
# which is scaled by the whole image's largest cost).
"$wideray" render "$scenes/default.json" --size 200x150 -o "$work/one.exr" >/dev/null 2>&1
"$wideray" render "$scenes/default.json" --size 200x150 --aov cost -o "$work/one_cost.exr" >/dev/null 2>&1
for n in 2 3; do
  ranks "$n" "$scenes/default.json" --size 200x150 -o "$work/ranks$n.exr" >"$work/out$n.txt" 2>&1
  grep -q "on [1-3] rank" "$work/out$n.txt" || { cat "$work/out$n.txt"; echo "FAIL: no ranks in the line"; exit 1; }
  same "$work/one.exr" "$work/ranks$n.exr" "default scene, $n ranks"
done
ranks 3 "$scenes/default.json" --size 200x150 --aov cost -o "$work/ranks3_cost.exr" >/dev/null 2>&1
same "$work/one_cost.exr" "$work/ranks3_cost.exr" "cost heatmap, 3 ranks"

# More ranks than tiles: an 8x8 image is one tile.
"$wideray" render "$scenes/default.json" --size 8x8 -o "$work/tiny.exr" >/dev/null 2>&1
ranks 3 "$scenes/default.json" --size 8x8 -o "$work/tiny3.exr" >/dev/null 2>&1
same "$work/tiny.exr" "$work/tiny3.exr" "3 ranks, 1 tile"

# A batch with one bad scene, on 2 and 3 ranks (as many frames as ranks: whole frames).
printf '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}\n' >"$work/bad.json"
batch=("$scenes/default.json" "$work/bad.json" "$scenes/metals.json")
mkdir -p "$work/batch1"
if "$wideray" render "${batch[@]}" --size 64x48 -o "$work/batch1" >/dev/null 2>&1; then
  echo "FAIL: a batch with a bad scene exited 0"; exit 1
fi
for n in 2 3; do
  mkdir -p "$work/batch$n"
  if ranks "$n" "${batch[@]}" --size 64x48 -o "$work/batch$n" >"$work/batch$n.txt" 2>&1; then
    cat "$work/batch$n.txt"; echo "FAIL: $n ranks: a batch with a bad scene exited 0"; exit 1
  fi
  grep -q "bad.json:objects\[0\].radius" "$work/batch$n.txt" && grep -q "1 of 3 scenes failed" "$work/batch$n.txt" ||
    { cat "$work/batch$n.txt"; echo "FAIL: $n ranks: the bad scene is not reported"; exit 1; }
  [ ! -e "$work/batch$n/bad.png" ] || { echo "FAIL: an image was written for the bad scene"; exit 1; }
  for name in default metals; do same "$work/batch1/$name.png" "$work/batch$n/$name.png" "batch, $n ranks: $name"; done
done

# An animation: 4 frames over 2 ranks (whole frames), 2 frames over 3 ranks (runs of tiles).
"$wideray" render "$scenes/orbit.json" --frames 3-6 --size 96x72 -o "$work/anim1" >/dev/null 2>&1
ranks 2 "$scenes/orbit.json" --frames 3-6 --size 96x72 -o "$work/anim2" >/dev/null 2>&1
ranks 3 "$scenes/orbit.json" --frames 5-6 --size 96x72 -o "$work/anim3" >/dev/null 2>&1
for f in 0003 0004 0005 0006; do same "$work/anim1/orbit_$f.png" "$work/anim2/orbit_$f.png" "animation, 2 ranks: frame $f"; done
for f in 0005 0006; do same "$work/anim1/orbit_$f.png" "$work/anim3/orbit_$f.png" "animation, 3 ranks: frame $f"; done
[ "$(ls "$work/anim2" | wc -l)" = 4 ] || { ls "$work/anim2"; echo "FAIL: 4 frames expected"; exit 1; }
