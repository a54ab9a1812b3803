#!/usr/bin/env python3
"""Generates the camera paths in meshes/paths/ over meshes/N42E001.hgt (tinlod's local frame:
x east, y north, metres, origin at the SW sample; spacing as `tinlod info` reports it).

Each eye keeps a clearance above the highest ground within 1.5 km, so no frame is under the
terrain. Run: python3 scripts/make_paths.py (pure Python, no dependencies)."""
import array
import math
import os

DX, DY = 68.48457208961014, 92.5494479893969  # `tinlod info meshes/N42E001.hgt` cell_size
N = 1201
raw = array.array("h")
with open("meshes/N42E001.hgt", "rb") as f:
    raw.frombytes(f.read())
raw.byteswap()  # big-endian file
VALID = [v for v in raw if v != -32768]
FILL = sorted(VALID)[len(VALID) // 2]


def ground(x, y, radius=0.0):
    """Highest sample within `radius` metres of (x, y) (voids count as the median height)."""
    c0, c1 = int((x - radius) / DX), int(math.ceil((x + radius) / DX))
    r0, r1 = int((y - radius) / DY), int(math.ceil((y + radius) / DY))
    best = -1e9
    for r in range(max(0, r0), min(N - 1, r1) + 1):
        for c in range(max(0, c0), min(N - 1, c1) + 1):
            v = raw[(N - 1 - r) * N + c]  # file row 0 is north
            best = max(best, FILL if v == -32768 else v)
    return best


def write(name, keys):
    with open(os.path.join("meshes/paths", name), "w") as out:
        out.write("t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n")
        for k in keys:
            out.write(",".join(f"{v:.2f}" for v in k) + "\n")


def drive(name, start, end, clearance, look_ahead, look_down, seconds, steps):
    keys = []
    for i in range(steps + 1):
        s = i / steps
        x = start[0] + (end[0] - start[0]) * s
        y = start[1] + (end[1] - start[1]) * s
        z = ground(x, y, 1500.0) + clearance
        d = math.hypot(end[0] - start[0], end[1] - start[1])
        ux, uy = (end[0] - start[0]) / d, (end[1] - start[1]) / d
        keys.append((seconds * s, x, y, z, x + ux * look_ahead, y + uy * look_ahead, z - look_down))
    write(name, keys)


# A low drive up the Valira valley (Andorra) and on north-east, 150 m above the nearby ground.
drive("n42_valley.csv", (28000, 50000), (47000, 78000), 150.0, 4000.0, 400.0, 20.0, 20)
# A fly-over at 2.5 km above the ground, looking ahead and down, south to north.
drive("n42_flyover.csv", (40000, 8000), (42000, 100000), 2500.0, 12000.0, 4000.0, 30.0, 30)
# A descent from 60 km above the centre to 300 m above the ground, looking at the centre.
keys = []
cx, cy = 41000.0, 55000.0
for i in range(21):
    s = i / 20
    h = math.exp(math.log(60000.0) * (1 - s) + math.log(ground(cx - 3000, cy - 3000, 1500) + 300) * s)
    keys.append((20.0 * s, cx - 3000 * s, cy - 3000 - 2000 * (1 - s), h, cx, cy, ground(cx, cy)))
write("n42_descent.csv", keys)
