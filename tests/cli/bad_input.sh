#!/usr/bin/env bash
# Bad input through the real executable: each case must fail with a non-zero exit (never a crash)
# and a message naming the file and what is wrong; no partial image may be left behind.
set -u
wideray="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# expect_error NAME PATTERN SCENE_TEXT [extra files are created by the caller]
expect_error() {
  local name="$1" pattern="$2" scene="$work/$1.json"
  local out status
  out=$("$wideray" render "$scene" -o "$work/$name.png" 2>&1)
  status=$?
  if [ $status -eq 0 ] || [ $status -ge 128 ]; then
    echo "FAIL $name: exit status $status (want 1..127)"; echo "$out"; failures=$((failures + 1)); return
  fi
  if ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL $name: message does not match /$pattern/:"; echo "$out"; failures=$((failures + 1)); return
  fi
  if ! grep -qF -- "$name.json" <<<"$out" && ! grep -qF -- "$name" <<<"$out"; then
    echo "FAIL $name: message does not name the file:"; echo "$out"; failures=$((failures + 1)); return
  fi
  if ls "$work" | grep -q "^$name.png$\|\.tmp"; then
    echo "FAIL $name: an image or temporary file was left behind"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $(head -n1 <<<"$out")"
}

good_object='{"type": "generated", "shape": "cube"}'
light='"lights": [{"type": "point", "position": [0, 5, 0]}]'

printf '{"objects": [%s], %s,\n  "camera": {"fov": 40,}\n}' "$good_object" "$light" > "$work/malformed.json"
expect_error malformed "line 2"

printf '{"objects": [%s], %s, "camra": {}}' "$good_object" "$light" > "$work/unknown_key.json"
expect_error unknown_key "camra"

printf '{"objects": [{"type": "pyramid"}], %s}' "$light" > "$work/unknown_type.json"
expect_error unknown_type "objects\[0\]"

printf '{"objects": [{"type": "mesh", "file": "nowhere.ply"}], %s}' "$light" > "$work/missing_mesh.json"
expect_error missing_mesh "nowhere.ply"

printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n' > "$work/truncated.ply"
printf '\x00\x00\x00\x00' >> "$work/truncated.ply"
printf '{"objects": [{"type": "mesh", "file": "truncated.ply"}], %s}' "$light" > "$work/truncated_ply.json"
expect_error truncated_ply "truncated.ply.*(vertex|ends)"

printf '{"objects": [{"type": "triangles", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,7]]}], %s}' "$light" > "$work/bad_index.json"
expect_error bad_index "range|index"

printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\nnan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$work/nan.ply"
printf '{"objects": [{"type": "mesh", "file": "nan.ply"}], %s}' "$light" > "$work/nan_coordinates.json"
expect_error nan_coordinates "nan.ply.*(NaN|finite|nan)"

printf '{"objects": [{"type": "csg", "operation": "difference", "operands": [{"type": "generated", "shape": "quad"}, %s]}], %s}' "$good_object" "$light" > "$work/open_csg_operand.json"
expect_error open_csg_operand "operands\[0\].*not closed"

printf '{"objects": [], %s}' "$light" > "$work/empty_scene.json"
expect_error empty_scene "no objects"

# A batch with a failing scene still renders the others and reports failure in its exit status.
printf '{"objects": [%s], %s, "image": {"width": 32, "height": 24}}' "$good_object" "$light" > "$work/good.json"
out=$("$wideray" render "$work/good.json" "$work/missing.json" -o "$work/batch" 2>&1); status=$?
if [ $status -ne 1 ] || [ ! -s "$work/batch/good.png" ] || [ -e "$work/batch/missing.png" ] || ! grep -q "1 of 2 scenes failed" <<<"$out"; then
  echo "FAIL batch: status $status"; echo "$out"; failures=$((failures + 1))
else
  echo "ok   batch: the good scene rendered, the missing one reported"
fi

# An image format that cannot be written fails cleanly and leaves nothing behind.
out=$("$wideray" render "$work/good.json" -o "$work/image.notaformat" 2>&1); status=$?
if [ $status -eq 0 ] || [ $status -ge 128 ] || ls "$work" | grep -q "notaformat"; then
  echo "FAIL unwritable format: status $status"; echo "$out"; failures=$((failures + 1))
else
  echo "ok   unwritable format: $(head -n1 <<<"$out")"
fi

# Bad command-line values are errors, and --help documents every command.
for args in "render $work/good.json --size 0x10" "render $work/good.json --isa mmx" "render $work/good.json --spp 0" "render" \
            "render $work/good.json --quality best" "info $work/good.json --quality medium" \
            "render $work/good.json --accel octree" "render $work/good.json --accel kdtree --kernel packet4" \
            "render $work/good.json --accel grid --quality high" "bench $work/good.json --accel bvh2,nope"; do
  "$wideray" $args >/dev/null 2>&1; status=$?
  if [ $status -eq 0 ] || [ $status -ge 128 ]; then echo "FAIL '$args' exited $status"; failures=$((failures + 1)); else echo "ok   '$args' rejected"; fi
done
for cmd in "" render info; do
  if ! "$wideray" $cmd --help >/dev/null; then echo "FAIL '$cmd --help'"; failures=$((failures + 1)); fi
done

passed=$(( 22 - failures ))
echo "cli: $passed passed, $failures failed"
[ $failures -eq 0 ]
