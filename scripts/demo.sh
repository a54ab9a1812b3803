#!/bin/sh
# The demo behind `make demo`: runs tinlod on a bundled real DEM and prints a short summary.
# Outputs land in out/demo/.
set -eu
BIN=${1:-build/bin}
OUT=out/demo
DEM=meshes/N42E001.hgt
mkdir -p "$OUT"
echo "== tinlod info $DEM"
"$BIN/tinlod" info "$DEM"
echo
echo "== full-resolution TIN"
"$BIN/tinlod" retrieve "$DEM" --full -o "$OUT/full.ply" --stats "$OUT/full.json"
echo
echo "demo outputs are in $OUT/"
