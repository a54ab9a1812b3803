#!/bin/sh
# The demo behind `make demo`: tinlod on a bundled real DEM (SRTM N42E001, Pyrenees and Andorra),
# step by step, with a short summary of each. Outputs land in out/demo/ (pictures in
# out/demo/pictures/, the ones the README shows).
set -eu
BIN=${1:-build/bin}
OUT=out/demo
PIC=$OUT/pictures
DEM=meshes/N42E001.hgt
EYE=8000,11000,1500
AT=50000,60000,800
CAM="--eye $EYE --at $AT"
mkdir -p "$OUT" "$PIC"
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

echo "== the DEM: tinlod info $DEM"
"$BIN/tinlod" info "$DEM" | grep -E "^(width|height|min|max|voids|crs|cell_size|bounds)"

echo
echo "== 1. full-resolution TIN (the reference every error is measured against)"
"$BIN/tinlod" retrieve "$DEM" --full -o "$OUT/full.ply" --stats "$OUT/full.json"

echo
echo "== 2. quad-tree store on disk, and view-dependent retrieval from it (tau = 1 px)"
"$BIN/tinlod" build "$DEM" -o "$OUT/n42.tlq" --stats "$OUT/build.json"
"$BIN/tinlod" retrieve "$OUT/n42.tlq" $CAM --tol 1 --cull -o "$OUT/culled.ply" --stats "$OUT/culled.json"
"$BIN/tinlod" retrieve "$DEM" $CAM --tol 1 --check -o "$OUT/retrieved.ply" --stats "$OUT/retrieve.json"

echo
echo "== 3. distance decay: retrieval at tau/2, then node erase bounded at every sample (tau = 1 px)"
"$BIN/tinlod" simplify "$DEM" $CAM --tol 1 -o "$OUT/erased.ply" --stats "$OUT/erase.json"
json "$OUT/erase.json" "'   retrieval alone %d nodes; node erase %d nodes (%.2f x fewer); measured max error %.3f px over every sample in view' % (json.load(open('$OUT/retrieve.json'))['output']['nodes'], d['output']['nodes'], json.load(open('$OUT/retrieve.json'))['output']['nodes'] / d['output']['nodes'], d['error']['max_screen_px'])"

echo
echo "== 4. pictures, and the image error of the erased TIN against the full grid"
"$BIN/tinlod" render "$OUT/full.ply" $CAM --dem-normals --reference "$DEM" -o "$PIC/full.png"
"$BIN/tinlod" render "$OUT/erased.ply" $CAM --dem-normals --reference "$DEM" -o "$PIC/erased.png"
"$BIN/tinlod" render "$OUT/erased.ply" --eye 0,-20000,25000 --at 30000,40000,0 --wire \
    --color height -o "$PIC/decay_wire.png"
"$BIN/tinlod" render "$DEM" $CAM --color sp -o "$PIC/sp.png"
"$BIN/tinlod" render "$OUT/erased.ply" $CAM --color error --reference "$DEM" -o "$PIC/error.png"
"$BIN/tinlod" compare "$OUT/erased.ply" "$DEM" $CAM --dem-normals --diff "$PIC/diff.png"
# One TIN seen from above while the observer drives up a valley: its detail follows the observer.
mkdir -p "$OUT/valley"
"$BIN/tinlod" fly "$DEM" --path meshes/paths/n42_valley.csv --fps 0.1 --frames "$OUT/valley" \
    --frames-eye 37000,12000,42000 --frames-at 37000,64000,0
cp "$OUT/valley/frame_00000.png" "$PIC/follow_start.png"
cp "$OUT/valley/frame_00002.png" "$PIC/follow_end.png"
echo "   the valley drive's TIN seen from above at its start and end: $PIC/follow_start.png, follow_end.png"

echo
echo "== 5. flying: a descent from 60 km to the ground, one TIN erased and recovered frame by frame"
"$BIN/tinlod" fly "$DEM" --path meshes/paths/n42_descent.csv --fps 0.5 --tol 1 --check \
    --stats "$OUT/fly.csv"
column -s, -t < "$OUT/fly.csv" | cut -c1-150

echo
echo "demo outputs are in $OUT/"
