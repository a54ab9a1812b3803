// What both tile checks read the same way: an SRTM .hgt DEM, read here (not by tinlod's code), and
// the tile scheme and error CesiumJS uses.
import fs from 'node:fs'
import path from 'node:path'

// CesiumJS: TerrainProvider.getEstimatedLevelZeroGeometricErrorForAHeightmap(Ellipsoid.WGS84, 65,
// 2) (heightmapTerrainQuality 0.25), halved per level by CesiumTerrainProvider.
export const WGS84_A = 6378137.0
export const WGS84_B = 6356752.3142451793
export const levelError = (z) => (WGS84_A * 2 * Math.PI * 0.25) / (65 * 2) / 2 ** z

// The geographic TMS scheme: 2 x 1 tiles at level 0, y counted from the south.
export function tileRect (z, x, y) {
  const size = 180 / 2 ** z
  return { west: -180 + x * size, south: -90 + y * size, east: -180 + (x + 1) * size, north: -90 + (y + 1) * size }
}

// SRTM .hgt: big-endian int16, square, row 0 north, named by its south-west corner.
export function readHgt (file) {
  const buf = fs.readFileSync(file)
  const n = Math.round(Math.sqrt(buf.length / 2))
  const z = new Int16Array(n * n)
  for (let i = 0; i < n * n; ++i) z[i] = buf.readInt16BE(2 * i)
  const m = /([NS])(\d\d)([EW])(\d\d\d)/i.exec(path.basename(file))
  const lat0 = Number(m[2]) * (m[1].toUpperCase() === 'S' ? -1 : 1)
  const lon0 = Number(m[4]) * (m[3].toUpperCase() === 'W' ? -1 : 1)
  return {
    n,
    lon0,
    lat0,
    lon: (c) => lon0 + c / (n - 1),
    lat: (r) => lat0 + 1 - r / (n - 1),
    col: (lon) => (lon - lon0) * (n - 1),
    row: (lat) => (lat0 + 1 - lat) * (n - 1),
    height: (c, r) => z[r * n + c], // -32768: a void, no sample
    covers: (lon, lat) => lon >= lon0 && lon <= lon0 + 1 && lat >= lat0 && lat <= lat0 + 1
  }
}
