#!/bin/sh
# Runs every libFuzzer target in $1/bin, one after the other, for $2 seconds each (or until
# $3 executions, default unbounded), seeded from meshes/ and tests/fuzz/seeds/.
set -eu
BUILD=$1
SECONDS_EACH=${2:-60}
RUNS=${3:--1}
mkdir -p "$BUILD/findings" "$BUILD/seed-files"
made="$BUILD/seed-files"
status=0
for fuzzer in "$BUILD"/bin/fuzz_*; do
    name=$(basename "$fuzzer")
    corpus="$BUILD/corpus/$name"
    mkdir -p "$corpus"
    # The first byte of an input picks the format (see each target); seeds carry it too.
    seed() { { printf "$1"; cat "$2"; } > "$corpus/seed-$(basename "$2")"; }
    # Inputs stay small: a fuzzer is fast only when one input is cheap to read.
    max_len=4096
    sanitizer_options=
    case $name in
    fuzz_raster)
        max_len=16384
        # OpenImageIO leaks in its PNG reader (tests/fuzz/lsan.supp); its frames show only in
        # stacks unwound the slow way, a few frames deep.
        sanitizer_options=yes ;;
    fuzz_mesh)
        max_len=40000
        seed '\000' meshes/bun_zipper_res4.ply
        # A TIN of a few dozen triangles in every mesh format tinlod writes.
        for ext in ply obj off stl; do
            "$BUILD/bin/tinlod" retrieve meshes/dem_squared.tif --eye 0,0,2000 --at 1000,1000,0 \
                --tol 64 -o "$made/tin.$ext" > /dev/null
        done
        seed '\000' "$made/tin.ply"
        seed '\001' "$made/tin.obj"
        seed '\002' "$made/tin.off"
        seed '\003' "$made/tin.stl" ;;
    fuzz_store)
        max_len=160000
        # Stores of the DEM of meshes/ and of the 70x9 raster seed (four tiles); bit 0 of the
        # first byte re-seals the checksums after mutation.
        "$BUILD/bin/tinlod" build meshes/dem_squared.tif -o "$made/squared.tlq" > /dev/null
        tail -c +2 tests/fuzz/seeds/fuzz_raster/squared_strip.exr > "$made/strip.exr"
        "$BUILD/bin/tinlod" build "$made/strip.exr" -o "$made/strip.tlq" > /dev/null
        seed '\001' "$made/squared.tlq"
        seed '\001' "$made/strip.tlq" ;;
    fuzz_camera_path)
        for f in meshes/paths/*.csv; do cp "$f" "$corpus/seed-$(basename "$f")"; done ;;
    esac
    if [ -d "tests/fuzz/seeds/$name" ]; then cp tests/fuzz/seeds/$name/* "$corpus/"; fi
    echo "== $name ($SECONDS_EACH s)"
    if ! env ${sanitizer_options:+ASAN_OPTIONS=fast_unwind_on_malloc=0:malloc_context_size=8} \
        LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp:print_suppressions=0" \
        "$fuzzer" "$corpus" -max_total_time="$SECONDS_EACH" -runs="$RUNS" -timeout=20 \
        -rss_limit_mb=4096 -max_len="$max_len" -artifact_prefix="$BUILD/findings/$name-" \
        -print_final_stats=1 > "$BUILD/findings/$name.log" 2>&1; then
        echo "$name: FOUND A PROBLEM, see $BUILD/findings/$name.log"
        status=1
    fi
    grep -E "stat::number_of_executed_units|DONE|cov:" "$BUILD/findings/$name.log" | tail -2
done
exit $status
