#!/bin/bash
# outputs.sh BIN OUT PNGS: runs a fixed set of `tinlod simplify` commands and prints each output's
# sha256, so that a change meant to keep every output can be checked against main's list.
# Run from the repository's root (meshes/ is read from there); BIN holds tinlod; PNGS is the
# `--tmp` folder of `bench_heightmap --quick` (crater_u16.png there).
set -u
if [ $# -ne 3 ]; then
    echo "usage: scripts/outputs.sh BIN OUT PNGS" >&2
    exit 2
fi
BIN=$(readlink -f "$1"); OUT=$2; PNGS=$(readlink -f "$3"); M=meshes
rm -rf "$OUT"; mkdir -p "$OUT"
run() { local name=$1; shift; "$BIN/tinlod" --threads 1 "$@" > "$OUT/$name.log" 2>&1 || echo "$name: exit $?"; }
run s_me1    simplify $M/N42E001.hgt --max-error 1 -o "$OUT/s_me1.ply"
run s_me5    simplify $M/N42E001.hgt --max-error 5 -o "$OUT/s_me5.ply"
run s_me20   simplify $M/N42E001.hgt --max-error 20 -o "$OUT/s_me20.ply"
run s_srtm30 simplify $M/dem_srtm30.tif --max-error 2 -o "$OUT/s_srtm30.ply"
run s_crater simplify "$PNGS/crater_u16.png" --cell 1 --zscale 0.015625 --max-error 5 -o "$OUT/s_crater.ply"
run s_crat1  simplify "$PNGS/crater_u16.png" --cell 1 --zscale 0.015625 --max-error 1 -o "$OUT/s_crat1.ply"
run s_sq05   simplify $M/dem_squared.tif --max-error 0.5 -o "$OUT/s_sq05.ply"
run s_samp   simplify $M/dem_srtm30.tif --max-error 2 --sample-heights -o "$OUT/s_samp.ply"
run s_budget simplify $M/dem_srtm30.tif --max-nodes 5000 -o "$OUT/s_budget.ply"
run s_view   simplify $M/dem_srtm30.tif --eye 0,-3000,2500 --at 0,0,500 --tol 1 -o "$OUT/s_view.ply"
run s_mesh   simplify $M/bun_zipper_res2.ply --eye 0,0.1,0.4 --at 0,0.1,0 --tol 2 -o "$OUT/s_mesh.ply"
cd "$OUT" && sha256sum ./*.ply | sed 's#  ./# #'
