#!/usr/bin/env python3
"""Flies the three shipped paths over meshes/N42E001.hgt with `tinlod fly` and prints the two
tables of the README's "Flying: per-frame cost" in Markdown: each path at 4 and 30 frames per
second of path time (hysteresis 0.25), then at 30 with hysteresis 0.1, 0.25, 0.4 and 0.5.

Run from the repository after a build: python3 scripts/fly_tables.py [BIN_DIR] (default build/bin).
One flight at a time, so the frames are timed on a core that nothing else of this script uses."""
import csv
import os
import re
import subprocess
import sys
import tempfile

PATHS = [("valley drive", "valley"), ("fly-over", "flyover"), ("descent", "descent")]
SUMMARY = re.compile(
    r"(?P<frames>\d+) frames, tau [\d.]+ px: first frame (?P<first>\d+) ms .*?"
    r"per frame p50 (?P<p50>[\d.]+) ms, p99 (?P<p99>[\d.]+) ms; \d+ erased, "
    r"(?P<recovered>\d+) recovered in all \((?P<entered>\d+) there for the first time"
)


def fly(tinlod, path, fps, hysteresis):
    """One flight: its summary line's numbers and the mean nodes and changed nodes of the frames
    after the first (from --stats)."""
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "frames.csv")
        out = subprocess.run(
            [tinlod, "fly", "meshes/N42E001.hgt", "--path", f"meshes/paths/n42_{path}.csv",
             "--tol", "1", "--fps", str(fps), "--hysteresis", str(hysteresis), "--stats", stats],
            check=True, capture_output=True, text=True).stdout
        match = SUMMARY.search(out)
        if not match:
            sys.exit(f"fly_tables.py: no summary line in the output of the {path} flight:\n{out}")
        with open(stats, newline="") as f:
            rows = list(csv.DictReader(f))[1:]
    result = {k: float(v) for k, v in match.groupdict().items()}
    result["nodes"] = sum(float(r["nodes"]) for r in rows) / len(rows)
    result["changed"] = sum(float(r["erased"]) + float(r["recovered"]) for r in rows) / len(rows)
    return result


def main():
    tinlod = os.path.join(sys.argv[1] if len(sys.argv) > 1 else "build/bin", "tinlod")
    print("| path | fps | frames | first frame (retrieval + erase) | per frame p50 | p99 "
          "| nodes per frame (mean) | recovered in all | of which entered |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for fps in (4, 30):
        for name, path in PATHS:
            r = fly(tinlod, path, fps, 0.25)
            print(f"| {name} | {fps} | {r['frames']:.0f} | {r['first'] / 1000:.1f} s "
                  f"| {r['p50']:.1f} ms | {r['p99']:.1f} ms | {r['nodes']:,.0f} "
                  f"| {r['recovered']:,.0f} | {r['entered']:,.0f} |", flush=True)
    print()
    print("| path | h | nodes per frame | changed per frame | p50 | p99 |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, path in PATHS:
        for h in (0.1, 0.25, 0.4, 0.5):
            r = fly(tinlod, path, 30, h)
            print(f"| {name} | {h} | {r['nodes']:,.0f} | {r['changed']:,.0f} "
                  f"| {r['p50']:.1f} ms | {r['p99']:.1f} ms |", flush=True)


if __name__ == "__main__":
    main()
