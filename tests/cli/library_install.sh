#!/usr/bin/env bash
# wideray as an installed library: cmake --install into a temporary prefix, then examples/ built
# outside the tree with find_package(wideray) (shared and static) and by hand with pkg-config; each
# program must trace its rays and print the hits expected.
set -euo pipefail
build="${1:?usage: library_install.sh BUILD_DIR SOURCE_DIR}"
source="${2:?usage: library_install.sh BUILD_DIR SOURCE_DIR}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in include/wideray/wideray.h include/wideray/version.h lib/cmake/wideray/widerayConfig.cmake \
         lib/cmake/wideray/widerayConfigVersion.cmake lib/pkgconfig/wideray.pc; do
  [[ -f "$prefix/$f" ]] || { echo "FAIL: $f not installed" >&2; exit 1; }
done
# No internal header, Embree or OpenImageIO in the public headers.
if grep -rnE '#include [<"](embree|OpenImageIO|nlohmann|tiny_|glm|tbb|fmt|core/|accel/|backends/)' "$prefix/include/wideray"; then
  echo "FAIL: a public header includes a private one" >&2; exit 1
fi

expect() {  # program output must have these lines
  local output="$1"
  for line in "ray from (0, 0, -5): t = 4, cube" "ray from (5, 0.5, -5): t = 4, copy" "ray from (10, 0, -5): miss" \
              "packet and stream agree on 3 of 3 rays; shadow ray blocked: yes"; do
    grep -qF "$line" <<< "$output" || { echo "FAIL: missing '$line' in:" >&2; echo "$output" >&2; exit 1; }
  done
}

for linkage in OFF ON; do
  cmake -S "$source/examples" -B "$work/examples-$linkage" -DCMAKE_PREFIX_PATH="$prefix" \
        -DWIDERAY_EXAMPLE_STATIC=$linkage -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" || {
    cat "$work/configure.log" >&2; exit 1; }
  cmake --build "$work/examples-$linkage" > "$work/build.log" || { cat "$work/build.log" >&2; exit 1; }
  expect "$("$work/examples-$linkage/trace_mesh")"
  echo "find_package(wideray), static=$linkage: ok"
done

export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
# shellcheck disable=SC2046
c++ "$source/examples/trace_mesh.cpp" -o "$work/trace_mesh_pc" $(pkg-config --cflags --libs wideray) \
    -Wl,-rpath,"$prefix/lib"
expect "$("$work/trace_mesh_pc")"
echo "pkg-config wideray: ok"
