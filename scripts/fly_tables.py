#!/usr/bin/env python3
"""Flies the three shipped paths over meshes/N42E001.hgt with `tinlod fly` and prints the two
tables of the README's "Flying: per-frame cost" in Markdown: each path at 4 and 30 frames per
second of path time (hysteresis 0.25), then at 30 with hysteresis 0.1, 0.25, 0.4 and 0.5.

Run after a build: python3 scripts/fly_tables.py [BIN_DIR] (default build/bin; the flights read
meshes/ of the repository the script is in).
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
        try:
            out = subprocess.run(
                [tinlod, "fly", "meshes/N42E001.hgt", "--path", f"meshes/paths/n42_{path}.csv",
                 "--tol", "1", "--fps", str(fps), "--hysteresis", str(hysteresis), "--stats",
                 stats], check=True, capture_output=True, text=True).stdout
        except FileNotFoundError:
            sys.exit(f"fly_tables.py: {tinlod}: no such program (build first, or pass BIN_DIR)")
        except subprocess.CalledProcessError as e:
            sys.exit(f"fly_tables.py: the {path} flight failed: {e.stderr.strip()}")
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
    bin_dir = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "build/bin")
    tinlod = os.path.join(bin_dir, "tinlod")
    os.chdir(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the repository
    # Every flight first, then the tables: a failed flight prints no partial table.
    lines = ["| path | fps | frames | first frame (retrieval + erase) | per frame p50 | p99 "
             "| nodes per frame (mean) | recovered in all | of which entered |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for fps in (4, 30):
        for name, path in PATHS:
            print(f"{name} at {fps} fps", file=sys.stderr, flush=True)
            r = fly(tinlod, path, fps, 0.25)
            lines.append(f"| {name} | {fps} | {r['frames']:.0f} | {r['first'] / 1000:.1f} s "
                         f"| {r['p50']:.1f} ms | {r['p99']:.1f} ms | {r['nodes']:,.0f} "
                         f"| {r['recovered']:,.0f} | {r['entered']:,.0f} |")
    lines += ["", "| path | h | nodes per frame | changed per frame | p50 | p99 |",
              "| --- | --- | --- | --- | --- | --- |"]
    for name, path in PATHS:
        for h in (0.1, 0.25, 0.4, 0.5):
            print(f"{name} at 30 fps, hysteresis {h}", file=sys.stderr, flush=True)
            r = fly(tinlod, path, 30, h)
            lines.append(f"| {name} | {h} | {r['nodes']:,.0f} | {r['changed']:,.0f} "
                         f"| {r['p50']:.1f} ms | {r['p99']:.1f} ms |")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
