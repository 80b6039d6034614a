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
# At 8 spp the frame takes long enough that every rank renders parts of it.
"$wideray" render "$scenes/default.json" --size 200x150 --spp 8 -o "$work/one.exr" >/dev/null 2>&1
"$wideray" render "$scenes/default.json" --size 200x150 --aov cost -o "$work/one_cost.exr" >/dev/null 2>&1
for n in 2 3; do
  ranks "$n" "$scenes/default.json" --size 200x150 --spp 8 -o "$work/ranks$n.exr" >"$work/out$n.txt" 2>&1
  grep -q "on $n ranks" "$work/out$n.txt" || { cat "$work/out$n.txt"; echo "FAIL: not every rank rendered parts"; exit 1; }
  same "$work/one.exr" "$work/ranks$n.exr" "default scene, $n ranks"
done
ranks 3 "$scenes/default.json" --size 200x150 --aov cost -o "$work/ranks3_cost.exr" >/dev/null 2>&1
same "$work/one_cost.exr" "$work/ranks3_cost.exr" "cost heatmap, 3 ranks"

# More ranks than tiles: an 8x8 image is one tile.
"$wideray" render "$scenes/default.json" --size 8x8 -o "$work/tiny.exr" >/dev/null 2>&1
ranks 3 "$scenes/default.json" --size 8x8 -o "$work/tiny3.exr" >/dev/null 2>&1
same "$work/tiny.exr" "$work/tiny3.exr" "3 ranks, 1 tile"

# A batch with a bad scene of 3 frames, on 2 and 3 ranks (more frames than ranks: whole frames).
printf '{"animation": {"keyframes": [{"frame": 1}, {"frame": 3, "position": [1, 0, 5]}]},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}\n' >"$work/bad.json"
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
  [ "$(grep -c "bad.json:objects\[0\].radius" "$work/batch$n.txt")" = 1 ] && grep -q "1 of 3 scenes failed" "$work/batch$n.txt" ||
    { cat "$work/batch$n.txt"; echo "FAIL: $n ranks: the bad scene is not reported once"; exit 1; }
  ! ls "$work/batch$n" | grep -q bad || { echo "FAIL: an image was written for the bad scene"; exit 1; }
  for name in default metals; do same "$work/batch1/$name.png" "$work/batch$n/$name.png" "batch, $n ranks: $name"; done
done

# An animation: 4 frames over 2 ranks (whole frames), 2 frames over 3 ranks (runs of tiles).
"$wideray" render "$scenes/orbit.json" --frames 3-6 --size 96x72 -o "$work/anim1" >/dev/null 2>&1
ranks 2 "$scenes/orbit.json" --frames 3-6 --size 96x72 -o "$work/anim2" >/dev/null 2>&1
ranks 3 "$scenes/orbit.json" --frames 5-6 --size 96x72 -o "$work/anim3" >/dev/null 2>&1
for f in 0003 0004 0005 0006; do same "$work/anim1/orbit_$f.png" "$work/anim2/orbit_$f.png" "animation, 2 ranks: frame $f"; done
for f in 0005 0006; do same "$work/anim1/orbit_$f.png" "$work/anim3/orbit_$f.png" "animation, 3 ranks: frame $f"; done
[ "$(ls "$work/anim2" | wc -l)" = 4 ] || { ls "$work/anim2"; echo "FAIL: 4 frames expected"; exit 1; }
if ranks 2 "$scenes/orbit.json" --frames 40-60 -o "$work/anim4" 2>"$work/range.txt" >/dev/null; then
  echo "FAIL: frames outside the animation were accepted"; exit 1
fi
grep -q "outside the animation's 1-48" "$work/range.txt" || { cat "$work/range.txt"; echo "FAIL: --frames message"; exit 1; }
echo "ok   --frames outside the animation refused"
