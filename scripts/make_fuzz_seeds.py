#!/usr/bin/env python3
"""Writes the small seed rasters of the raster fuzz targets (tests/fuzz/seeds/fuzz_raster/ and
fuzz_hgt/): crops of the real files in meshes/, a few samples a side, so that one execution costs
little and mutations reach every header field. A fuzz_raster seed starts with the byte that picks
the format (fuzz_raster.cpp); a fuzz_hgt seed is a file name and a run of samples (fuzz_hgt.cpp).

GeoTIFFs are written here (OpenImageIO drops the GeoTIFF tags on a crop): int16 geographic with a
nodata tag and a void, float32 geographic (NAD83) and float32 projected with PixelIsPoint. PNG and
EXR crops go through oiiotool. Run: python3 scripts/make_fuzz_seeds.py (needs oiiotool)."""
import os
import re
import struct
import subprocess
import tempfile

OUT = "tests/fuzz/seeds/fuzz_raster"
PICK_TIF, PICK_PNG, PICK_EXR, PICK_TERRAIN_PNG = 0, 1, 2, 5


def crop(src, w, h, x, y, out):
    subprocess.run(["oiiotool", src, "--cut", f"{w}x{h}+{x}+{y}", "-o", out], check=True)


def samples(path):
    """Pixel values of a one-channel image, row-major, as oiiotool prints them."""
    text = subprocess.run(["oiiotool", "--dumpdata", path], check=True, capture_output=True,
                          text=True).stdout
    return [float(v) for v in re.findall(r"Pixel \(\d+, \d+\): (\S+)", text)]


def geotiff(w, h, fmt, values, scale, tie, keys, nodata=None):
    """A baseline TIFF, one strip, with the GeoTIFF tags tinlod reads (pixel scale, tie point,
    GeoKey directory, GDAL_NODATA)."""
    bits = struct.calcsize(fmt) * 8
    sample_format = 3 if fmt == "f" else 2
    data = struct.pack("<%d%s" % (len(values), fmt), *values)
    geokeys = [1, 1, 0, len(keys)] + [v for k, val in keys for v in (k, 0, 1, val)]
    extra = []  # (tag, type, count, payload bytes)
    extra.append((33550, 12, 3, struct.pack("<3d", scale[0], scale[1], 0.0)))
    extra.append((33922, 12, 6, struct.pack("<6d", 0.0, 0.0, 0.0, tie[0], tie[1], 0.0)))
    extra.append((34735, 3, len(geokeys), struct.pack("<%dH" % len(geokeys), *geokeys)))
    if nodata is not None:
        text = nodata.encode() + b"\0"
        extra.append((42113, 2, len(text), text))
    tags = [(256, 3, 1, w), (257, 3, 1, h), (258, 3, 1, bits), (259, 3, 1, 1), (262, 3, 1, 1),
            (273, 4, 1, None), (277, 3, 1, 1), (278, 3, 1, h), (279, 4, 1, len(data)),
            (284, 3, 1, 1), (339, 3, 1, sample_format)]
    entries = len(tags) + len(extra)
    ifd_at = 8
    blobs_at = ifd_at + 2 + 12 * entries + 4
    blobs = b""
    rows = []
    for tag, typ, count, payload in extra:
        if len(payload) <= 4:
            rows.append((tag, typ, count, payload.ljust(4, b"\0")))
        else:
            rows.append((tag, typ, count, struct.pack("<I", blobs_at + len(blobs))))
            blobs += payload + (b"\0" if len(payload) % 2 else b"")
    data_at = blobs_at + len(blobs)
    for tag, typ, count, value in tags:
        value = data_at if tag == 273 else value
        payload = struct.pack("<HH", value, 0) if typ == 3 else struct.pack("<I", value)
        rows.append((tag, typ, count, payload))
    rows.sort()
    ifd = struct.pack("<H", entries)
    for tag, typ, count, payload in rows:
        ifd += struct.pack("<HHI", tag, typ, count) + payload
    ifd += struct.pack("<I", 0)
    return b"II*\0" + struct.pack("<I", ifd_at) + ifd + blobs + data


def write(name, pick, body, folder=OUT):
    with open(os.path.join(folder, name), "wb") as f:
        f.write(bytes([pick] if pick is not None else []) + body)


def main():
    os.makedirs(OUT, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        # dem_srtm30.tif: int16, EPSG:4326, 30" pixels, nodata -9999 (one void put in).
        cut = os.path.join(tmp, "srtm30.tif")
        crop("meshes/dem_srtm30.tif", 8, 8, 140, 150, cut)
        z = [int(v) for v in samples(cut)]
        z[9] = -9999
        write("srtm30_int16_geographic.tif", PICK_TIF,
              geotiff(8, 8, "h", z, (1 / 120, 1 / 120), (138.5, 36.0),
                      [(1024, 2), (1025, 1), (2048, 4326)], "-9999"))
        # dem_squared.tif: float32, EPSG:4269, 1" pixels, nodata -3.4028e38.
        cut = os.path.join(tmp, "squared.tif")
        crop("meshes/dem_squared.tif", 8, 8, 60, 60, cut)
        z = samples(cut)
        write("squared_float32_geographic.tif", PICK_TIF,
              geotiff(8, 8, "f", z, (1 / 3600, 1 / 3600), (-122.15, 37.93),
                      [(1024, 2), (1025, 1), (2048, 4269)], "-3.4028234663852886e+38"))
        write("squared_float32_utm_point.tif", PICK_TIF,
              geotiff(8, 8, "f", z, (30.0, 30.0), (570000.0, 4198000.0),
                      [(1024, 1), (1025, 2), (3072, 32610)]))
        # The EXR strip is also the small store seed of fuzz_store (scripts/fuzz.sh): 70 samples
        # wide make four tiles.
        for src, name, pick, w, h, x, y in [
            ("meshes/crater_u16.png", "crater_u16.png", PICK_PNG, 8, 8, 160, 220),
            ("meshes/fuji.png", "fuji_terrain_rgb.png", PICK_TERRAIN_PNG, 8, 8, 250, 250),
            ("meshes/dem_squared.tif", "squared_strip.exr", PICK_EXR, 70, 9, 50, 60),
        ]:
            out = os.path.join(tmp, name)
            crop(src, w, h, x, y, out)
            with open(out, "rb") as f:
                write(name, pick, f.read())
    # .hgt: a file name, then samples the harness repeats to fill a 1201x1201 tile.
    hgt = "tests/fuzz/seeds/fuzz_hgt"
    os.makedirs(hgt, exist_ok=True)
    with open("meshes/N42E001.hgt", "rb") as f:
        write("N42E001_row.hgt", None, b"N42E001" + f.read(2 * 64), hgt)
    write("S89W180_void.hgt", None, b"S89W180" + b"\x80\x00\x01\x00", hgt)


if __name__ == "__main__":
    main()
