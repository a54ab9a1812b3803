#!/bin/sh
# The installed CMake package (issue #46): `cmake --install` into a temporary prefix, the
# examples/ built against it with find_package(tinlod CONFIG), each run on meshes/ and its output
# checked; the OpenMesh plugin example links no EGL, GL or OpenImageIO.
#   tests/package_examples.sh BUILD_DIR SOURCE_DIR
set -eu
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "package_examples: $*" >&2; exit 1; }

prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; fail "install failed"; }
for f in bin/tinlod lib/cmake/tinlod/tinlodConfig.cmake lib/cmake/tinlod/tinlodConfigVersion.cmake \
         lib/cmake/tinlod/tinlodTargets.cmake lib/libtinlod_core.a lib/libtinlod_io.a \
         lib/libtinlod_render.a include/tinlod/version.hpp include/tinlod/closest_point.hpp \
         include/tinlod/tin.hpp include/tinlod/om/ModDistanceDecayT.hh \
         include/tinlod/om/NodeEraseDecimaterT.hh lib/tinlod/tinlod_oiio.so lib/tinlod/tinlod_tiff.so \
         lib/tinlod/tinlod_png.so lib/tinlod/tinlod_proj.so; do
    [ -e "$prefix/$f" ] || fail "the install holds no $f"
done
if [ -e "$build/bin/tinlod-view" ] && [ ! -x "$prefix/bin/tinlod-view" ]; then
    fail "the install holds no bin/tinlod-view"
fi
# The core's interface names none of the io and render dependencies.
sed -n '/^set_target_properties(tinlod::core /,/^)/p' "$prefix/lib/cmake/tinlod/tinlodTargets.cmake" \
    > "$tmp/core"
grep -q OpenMeshCore "$tmp/core" || fail "no tinlod::core properties in tinlodTargets.cmake"
if grep -E 'OpenImageIO|GeoTIFF|PROJ|OpenGL|EGL|nlohmann' "$tmp/core"; then
    fail "tinlod::core's interface names an io or render dependency"
fi

cmake -S "$src/examples" -B "$tmp/examples" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    > "$tmp/configure.log" 2>&1 || { cat "$tmp/configure.log"; fail "examples: configure failed"; }
cmake --build "$tmp/examples" -j 2 > "$tmp/build.log" 2>&1 ||
    { cat "$tmp/build.log"; fail "examples: build failed"; }
bin=$tmp/examples

# Linking tinlod::openmesh alone brings no EGL, GL or OpenImageIO; tinlod::io does bring
# OpenImageIO (the check can see one).
readelf -d "$bin/decimate_mesh" | grep NEEDED > "$tmp/needed" || true
if grep -E 'libEGL|libGL|libOpenGL|libOpenImageIO' "$tmp/needed"; then
    fail "decimate_mesh (tinlod::openmesh) links EGL, GL or OpenImageIO"
fi
readelf -d "$bin/dem_to_tin" | grep -q 'libOpenImageIO' || fail "readelf sees no OpenImageIO in dem_to_tin"

# Greedy insertion to 5 m on a real DEM: fewer nodes than samples, every sample within 5 m (as
# `tinlod compare` measures it against the DEM).
"$bin/dem_to_tin" "$src/meshes/dem_srtm30.tif" 5 "$tmp/tin.ply" > "$tmp/dem.out"
cat "$tmp/dem.out"
set -- $(cat "$tmp/dem.out")
[ "$1" = samples ] && [ "$3" = nodes ] && [ "$4" -gt 2 ] && [ "$4" -lt "$2" ] ||
    fail "dem_to_tin: unexpected node count"
"$build/bin/tinlod" compare "$tmp/tin.ply" "$src/meshes/dem_srtm30.tif" --eye 0,0,20000 \
    --at 1000,1000,0 --json > "$tmp/tin.json"
vertical=$(sed -n 's/.*"max_vertical": *\([-0-9.eE+]*\).*/\1/p' "$tmp/tin.json")
echo "dem_to_tin: measured $vertical m"
[ -n "$vertical" ] && grep -q '"uncovered": 0' "$tmp/tin.json" &&
    awk -v v="$vertical" 'BEGIN { exit !(v > 0 && v <= 5 + 1e-4) }' ||
    fail "dem_to_tin: the TIN misses samples or measures $vertical m, over 5 m"

# The Refiner along a camera path descending onto N42E001: within the tolerance from the first
# frame, a TIN of far fewer nodes than samples every frame, and nodes recovered as the eye nears.
"$bin/follow_path" "$src/meshes/N42E001.hgt" "$src/meshes/paths/n42_descent.csv" 4 1 > "$tmp/path.out"
cat "$tmp/path.out"
set -- $(head -1 "$tmp/path.out")
[ "$1" = samples ] && awk -v b="$4" -v t="$6" 'BEGIN { exit !(b > 0 && b <= t) }' ||
    fail "follow_path: the first frame's bound is not within the tolerance"
[ "$(grep -c '^frame ' "$tmp/path.out")" -eq 3 ] || fail "follow_path: not 3 updates"
awk -v n="$2" '$1 == "frame" { if ($4 <= 0 || $4 * 10 > n) bad = 1; back += $10 }
    END { exit bad || back == 0 }' "$tmp/path.out" ||
    fail "follow_path: a frame with no nodes or over a tenth of the samples, or nothing recovered"

# The plugin on a real scan with either module, to 1 px from 350 units away: the output measured
# by the command line's own Hausdorff code (every input vertex to the output surface) is <= 1 px.
for module in decay erase; do
    "$bin/decimate_mesh" "$src/meshes/armadillo.off" "$tmp/$module.ply" $module 350 > "$tmp/$module.out"
    cat "$tmp/$module.out"
    set -- $(cat "$tmp/$module.out")
    [ "$1" = vertices ] && [ "$4" -lt "$2" ] || fail "$module: no vertex removed"
    "$build/bin/tinlod" compare "$tmp/$module.ply" "$src/meshes/armadillo.off" --eye "$6,$7,$8" \
        --at "${10},${11},${12}" --samples 0 --json > "$tmp/$module.json"
    px=$(sed -n 's/.*"max_screen_px_reference_to_mesh": *\([-0-9.eE+]*\).*/\1/p' "$tmp/$module.json")
    echo "$module: measured $px px"
    [ -n "$px" ] && awk -v px="$px" 'BEGIN { exit !(px > 0 && px <= 1 + 1e-4) }' ||
        fail "$module: the output measures $px px, over 1 px"
done
echo "package_examples: ok"
