#!/bin/sh
# Runs every libFuzzer target in $1/bin for $2 seconds each, seeded from meshes/ and tests/fuzz/seeds.
set -eu
BUILD=$1
SECONDS_EACH=${2:-60}
mkdir -p "$BUILD/findings"
status=0
for fuzzer in "$BUILD"/bin/fuzz_*; do
    name=$(basename "$fuzzer")
    corpus="$BUILD/corpus/$name"
    mkdir -p "$corpus"
    # The first byte of an input picks the format (see each target); seeds carry it too.
    seed() { { printf "$1"; cat "$2"; } > "$corpus/seed-$(basename "$2")"; }
    case $name in
    fuzz_raster)
        for f in meshes/*.tif; do seed '\000' "$f"; done
        seed '\001' meshes/crater_u16.png
        seed '\005' meshes/fuji.png ;;
    fuzz_mesh)
        seed '\000' meshes/bun_zipper_res4.ply ;;
    esac
    [ -d "tests/fuzz/seeds/$name" ] && cp tests/fuzz/seeds/$name/* "$corpus/"
    echo "== $name ($SECONDS_EACH s)"
    if ! "$fuzzer" "$corpus" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=4096 \
        -max_len=1048576 -artifact_prefix="$BUILD/findings/$name-" -print_final_stats=1 \
        > "$BUILD/findings/$name.log" 2>&1; then
        echo "$name: FOUND A PROBLEM, see $BUILD/findings/$name.log"
        status=1
    fi
    grep -E "stat::number_of_executed_units|cov:" "$BUILD/findings/$name.log" | tail -2
done
exit $status
