#!/bin/sh
# The benchmark suite end to end (`make bench`, `make bench ARGS=--quick`): set-up (gnuplot,
# /usr/bin/time, the npm peers), the flight benchmark (bench_fly), the side-by-side suite
# (bench_suite, which puts the flight's claims and section into RESULTS.md), tinlod against hmm as
# whole processes (bench_heightmap, its section appended to RESULTS.md), `tinlod tiles` against
# tin-terrain and cesium-terrain-builder (bench_tiles.mjs, likewise), the Google Benchmark
# micro-benchmarks (bench_micro), the plots; everything lands in bench/results/.
#
# usage: bench/run.sh BIN_DIR [--quick]
set -eu
BIN=$(cd "$1" && pwd)
shift
QUICK=""
for a in "$@"; do
    case "$a" in
    --quick) QUICK=--quick ;;
    *) echo "run.sh: unknown argument $a (only --quick)" >&2; exit 2 ;;
    esac
done
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DATA=${TINLOD_DATA:-$ROOT/../shared/data}
OUT=$ROOT/bench/results
START=$(date +%s)
for f in dem/N42E001.hgt dem/N48W125.hgt.zip; do
    [ -f "$DATA/$f" ] || {
        echo "run.sh: $DATA/$f: not found (the bench reads ../shared/data beside the repository, or TINLOD_DATA)" >&2
        exit 1
    }
done

# GDAL, Boost and fmt for the tile builders bench_tiles runs beside tinlod (bench/peers).
"$ROOT/scripts/setup.sh" gnuplot-nox time libgdal-dev gdal-bin libboost-program-options-dev \
    libboost-filesystem-dev libfmt-dev
command -v node >/dev/null || "$ROOT/scripts/setup.sh" nodejs npm
(cd "$ROOT/bench/peers" && npm ci --no-audit --no-fund --loglevel=error) ||
    { [ -d "$ROOT/bench/peers/node_modules/delatin" ] && echo "run.sh: npm ci failed; using the installed peers" >&2; } ||
    exit 1

TMP=$(mktemp -d /tmp/tinlod-bench.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
unzip -q -o "$DATA/dem/N48W125.hgt.zip" -d "$TMP"
mkdir -p "$OUT"

COMMAND="make bench${QUICK:+ ARGS=--quick}"
"$BIN/bench_fly" $QUICK --data "$DATA" --out "$OUT" --tmp "$TMP"
"$BIN/bench_suite" $QUICK --data "$DATA" --peers "$ROOT/bench/peers" --out "$OUT" --tmp "$TMP" \
    --command "$COMMAND" --flight "$TMP/flight.json"
"$BIN/bench_heightmap" $QUICK --bin "$BIN" --meshes "$ROOT/meshes" --peers "$ROOT/bench/peers" \
    --out "$OUT" --tmp "$TMP" --command "$COMMAND"
cat "$OUT/hmm.md" >>"$OUT/RESULTS.md"

# tin-terrain and ctb-tile are built only where GDAL is found, so the build folder BIN is in is
# configured again now that set-up has installed it (not part of `make build`: see bench/CMakeLists.txt).
BUILD=$(dirname "$BIN")
cmake -S "$ROOT" -B "$BUILD" >"$BUILD/configure-peers.log" 2>&1 ||
    { cat "$BUILD/configure-peers.log"; exit 1; }
cmake --build "$BUILD" -j "$(nproc)" --target tin-terrain ctb-tile
node "$ROOT/bench/bench_tiles.mjs" $QUICK --bin "$BIN" --meshes "$ROOT/meshes" --out "$OUT" --tmp "$TMP" \
    --command "$COMMAND"
cat "$OUT/tiles.md" >>"$OUT/RESULTS.md"

MIN_TIME=0.5
[ -n "$QUICK" ] && MIN_TIME=0.1
"$BIN/bench_micro" --benchmark_min_time="$MIN_TIME" --benchmark_out="$OUT/micro.json" \
    --benchmark_out_format=json | tee "$OUT/micro.txt"
{
    printf '\n## Micro-benchmarks (bench_micro, Google Benchmark; micro.json, micro.txt)\n\n```\n'
    grep -v '^\*\*\*' "$OUT/micro.txt"
    printf '```\n'
} >>"$OUT/RESULTS.md"

gnuplot -e "tmp='$TMP'; out='$OUT'" "$ROOT/bench/plot.gp"
END=$(date +%s)
printf '\nWhole suite: %d s wall time.\n' $((END - START)) >>"$OUT/RESULTS.md"
echo "bench: results in $OUT (RESULTS.md, *.csv, *.png) after $((END - START)) s"
