#!/bin/sh
# The Debian package (issue #46): `cpack -G DEB` from a build gives a .deb holding the programs,
# the libraries, the headers and the CMake package, depending on the Debian packages it links;
# extracted (not installed: the test machine's root stays as it is), its `tinlod --version` runs.
#   tests/package_deb.sh BUILD_DIR SOURCE_DIR
set -eu
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "package_deb: $*" >&2; exit 1; }

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp" > "$tmp/cpack.log" 2>&1 ||
    { cat "$tmp/cpack.log"; fail "cpack failed"; }
deb=$(ls "$tmp"/*.deb)
[ -f "$deb" ] || fail "cpack made no .deb"
echo "package_deb: $(basename "$deb")"

dpkg-deb -c "$deb" | awk '{ print $NF }' > "$tmp/contents"
for f in ./usr/bin/tinlod ./usr/include/tinlod/tin.hpp ./usr/include/tinlod/version.hpp \
         ./usr/include/tinlod/om/ModDistanceDecayT.hh; do
    grep -qx "$f" "$tmp/contents" || fail "the .deb holds no $f"
done
for f in cmake/tinlod/tinlodConfig.cmake cmake/tinlod/tinlodConfigVersion.cmake \
         libtinlod_core.a libtinlod_io.a libtinlod_render.a; do
    grep -qE "^\./usr/lib/(.+/)?$f\$" "$tmp/contents" || fail "the .deb holds no /usr/lib/$f"
done
if [ -e "$build/bin/tinlod-view" ]; then
    grep -qx ./usr/bin/tinlod-view "$tmp/contents" || fail "the .deb holds no tinlod-view"
fi

# Depends: the run-time libraries the programs link (dpkg-shlibdeps) and the -dev packages the
# CMake package's find_dependency calls need.
depends=$(dpkg-deb -f "$deb" Depends)
echo "package_deb: Depends: $depends"
for p in libc6 libopenimageio libtiff libpng libproj libegl1 libopenmesh-dev libglm-dev libopenimageio-dev; do
    echo "$depends" | grep -q "$p" || fail "Depends lists no $p"
done

dpkg-deb -x "$deb" "$tmp/root"
out=$("$tmp/root/usr/bin/tinlod" --version) || fail "the extracted tinlod --version failed"
echo "$out" | head -1
expected=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
echo "$out" | grep -q "$expected" || fail "tinlod --version does not print $expected"
# It finds its modules where it was extracted (a PNG needs the PNG module, a NAD83 GeoTIFF PROJ's).
for f in crater_u16.png dem_squared.tif; do
    "$tmp/root/usr/bin/tinlod" info "$src/meshes/$f" > /dev/null ||
        fail "the extracted tinlod cannot read $f"
done
# Its CMake package, found where it was extracted, configures the examples.
cmake -S "$src/examples" -B "$tmp/examples" -DCMAKE_PREFIX_PATH="$tmp/root/usr" > "$tmp/examples.log" 2>&1 ||
    { cat "$tmp/examples.log"; fail "the .deb's CMake package does not configure the examples"; }
grep -q "$tmp/root/usr" "$tmp/examples/CMakeCache.txt" || fail "the examples found another tinlod"
echo "package_deb: ok"
