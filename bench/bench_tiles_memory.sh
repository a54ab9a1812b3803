#!/bin/sh
# `tinlod tiles` on a DEM larger than its memory (docs/tiles.md, "Memory"): a 16385 x 16385 float
# GeoTIFF (1 GiB of heights, 1-arc-second spacing, tiles of 256; written by test_tiles_memory's
# DISABLED_WriteBenchDem, a tile at a time) built within --memory-mb 512 and again with the lattice
# held whole, the peak resident size and wall time of each (/usr/bin/time), and the two tile sets
# compared byte for byte. Takes tens of minutes on 2 cores and 1.1 GiB of disk beside the tiles.
#
# usage: bench/bench_tiles_memory.sh BIN_DIR [SIDE [MEMORY_MB [MAX_ZOOM]]]
set -eu
BIN=$(cd "$1" && pwd)
SIDE=${2:-16385}
MEMORY=${3:-512}
ZOOM=${4:-}
TMP=$(mktemp -d /tmp/tinlod-bench-memory.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
TINLOD_DEM_PATH=$TMP/dem.tif TINLOD_DEM_SIDE=$SIDE "$BIN/test_tiles_memory" \
    --gtest_also_run_disabled_tests --gtest_filter=TilesMemory.DISABLED_WriteBenchDem >/dev/null
ls -l "$TMP/dem.tif"
LEVELS=""
[ -n "$ZOOM" ] && LEVELS="--max-zoom $ZOOM"
run() { # name, extra arguments
    name=$1
    shift
    /usr/bin/time -f "$name: peak %M KiB, %e s wall, %U s user" \
        "$BIN/tinlod" tiles "$TMP/dem.tif" -o "$TMP/$name" --stats "$TMP/$name.json" $LEVELS "$@"
}
run bounded --memory-mb "$MEMORY"
run whole
if diff -r "$TMP/bounded" "$TMP/whole" >/dev/null; then
    echo "tile sets: byte-identical ($(find "$TMP/whole" -name '*.terrain' | wc -l) tiles)"
else
    echo "tile sets: DIFFER" && exit 1
fi
