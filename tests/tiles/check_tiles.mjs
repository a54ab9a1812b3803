// Checks a quantized-mesh tile set with code tinlod's writer does not share: every tile is read by
// @here/quantized-mesh-decoder (npm), and the DEM (an SRTM .hgt) by srtm.mjs.
//
//   node check_tiles.mjs DIR [DEM.hgt...] [--no-error]
//
// Prints one JSON object: counts, the worst error over the level's bound, and `failures` (empty
// when every check holds). Checks: layer.json's fields and that `available` lists exactly the
// tiles on disk; per tile: indices in range, triangles counter-clockwise in u/v, the four edge lists
// hold exactly the vertices on their edges, every vertex inside the bounding sphere, the horizon
// occlusion point as CesiumJS computes one (EllipsoidalOccluder) or farther; neighbours of a level
// share their common edge vertex for vertex (the same place, the same decoded height); every DEM
// sample inside a tile is within the level's error of the decoded TIN (where DEMs overlap, the
// first one's samples, as tinlod takes them), and within it of the TIN as CesiumJS draws it: the
// sample's Earth-centred position against the point of its triangle, drawn flat between its
// vertices' Earth-centred positions, at the sample's place in the triangle (a point of the drawn
// surface, so its distance bounds the sample's distance to that surface).
import decoder from '@here/quantized-mesh-decoder'
import fs from 'node:fs'
import path from 'node:path'
import zlib from 'node:zlib'
import { WGS84_A, WGS84_B, levelError, readHgt, tileRect } from './srtm.mjs'
import { locator } from './tin_locator.mjs'

const decode = decoder.default
const [dir, ...rest] = process.argv.slice(2)
const checkError = !rest.includes('--no-error')
const demPaths = rest.filter((a) => !a.startsWith('--'))
const failures = []
const fail = (what) => { if (failures.length < 50) failures.push(what) }

function ecef (lonDeg, latDeg, h) {
  const l = lonDeg * Math.PI / 180; const p = latDeg * Math.PI / 180
  const e2 = 1 - (WGS84_B * WGS84_B) / (WGS84_A * WGS84_A)
  const n = WGS84_A / Math.sqrt(1 - e2 * Math.sin(p) ** 2)
  return [(n + h) * Math.cos(p) * Math.cos(l), (n + h) * Math.cos(p) * Math.sin(l), (n * (1 - e2) + h) * Math.sin(p)]
}

// --- tiles
function readTile (file) {
  const raw = zlib.gunzipSync(fs.readFileSync(file))
  const data = new ArrayBuffer(raw.length) // the decoder views the buffer from byte 0
  new Uint8Array(data).set(raw)
  const t = decode(data)
  const n = t.vertexData.length / 3
  const u = t.vertexData.subarray(0, n); const v = t.vertexData.subarray(n, 2 * n)
  const q = t.vertexData.subarray(2 * n, 3 * n)
  const { minHeight, maxHeight } = t.header
  const h = Float64Array.from(q, (x) => minHeight + (x / 32767) * (maxHeight - minHeight))
  return { ...t, n, u, v, h, bytes: raw.length }
}

const layer = JSON.parse(fs.readFileSync(path.join(dir, 'layer.json'), 'utf8'))
for (const [key, want] of Object.entries({ format: 'quantized-mesh-1.0', scheme: 'tms', projection: 'EPSG:4326', tilejson: '2.1.0' })) {
  if (layer[key] !== want) fail(`layer.json: ${key} is ${layer[key]}, not ${want}`)
}
if (!Array.isArray(layer.tiles) || !layer.tiles[0].includes('{z}/{x}/{y}.terrain')) fail('layer.json: tiles template')
if (!Array.isArray(layer.available)) fail('layer.json: no available')

const listed = new Set()
layer.available.forEach((rects, z) => {
  for (const r of rects) {
    for (let y = r.startY; y <= r.endY; ++y) for (let x = r.startX; x <= r.endX; ++x) listed.add(`${z}/${x}/${y}`)
  }
})
const onDisk = new Set()
for (const z of fs.readdirSync(dir)) {
  if (!/^\d+$/.test(z)) continue
  for (const x of fs.readdirSync(path.join(dir, z))) {
    for (const f of fs.readdirSync(path.join(dir, z, x))) onDisk.add(`${z}/${x}/${f.replace(/\.terrain$/, '')}`)
  }
}
for (const k of onDisk) if (!listed.has(k)) fail(`${k}: on disk, not in available`)
for (const k of listed) if (!onDisk.has(k)) fail(`${k}: in available, not on disk`)

const tiles = new Map()
for (const k of onDisk) tiles.set(k, readTile(path.join(dir, `${k}.terrain`)))

const dems = checkError ? demPaths.map(readHgt) : []
// Each DEM's rows and columns as ecef() reads them, once: a sample's position is then a few
// products.
const E2 = 1 - (WGS84_B * WGS84_B) / (WGS84_A * WGS84_A)
for (const dem of dems) {
  const idx = [...Array(dem.n).keys()]
  const rows = idx.map((r) => dem.lat(r) * Math.PI / 180)
  const cols = idx.map((c) => dem.lon(c) * Math.PI / 180)
  dem.rowTrig = rows.map((p) => ({ cos: Math.cos(p), sin: Math.sin(p), n: WGS84_A / Math.sqrt(1 - E2 * Math.sin(p) ** 2) }))
  dem.colTrig = cols.map((l) => ({ cos: Math.cos(l), sin: Math.sin(l) }))
  dem.ecef = (c, r, h) => {
    const p = dem.rowTrig[r]; const l = dem.colTrig[c]
    return [(p.n + h) * p.cos * l.cos, (p.n + h) * p.cos * l.sin, (p.n * (1 - E2) + h) * p.sin]
  }
}
const summary = { tiles: 0, triangles: 0, samples: 0, shared_edges: 0, worst_ratio: 0, worst_drawn_ratio: 0, worst_chord_ratio: 0, levels: {} }
// CesiumJS draws a triangle flat between its vertices' Earth-centred positions: that may stray from
// the tile's surface (heights linear in u/v) by at most this share of the level's error.
const CHORD_SHARE = 1 / 16

// CesiumJS's EllipsoidalOccluder.computeMagnitude, for the occlusion point's check.
function occlusionMagnitude (radii, p, dir) {
  const s = [p[0] / radii[0], p[1] / radii[1], p[2] / radii[2]]
  let m2 = s[0] ** 2 + s[1] ** 2 + s[2] ** 2
  let m = Math.sqrt(m2)
  const d = s.map((x) => x / m)
  m2 = Math.max(1, m2); m = Math.max(1, m)
  const cosA = d[0] * dir[0] + d[1] * dir[1] + d[2] * dir[2]
  const cr = [d[1] * dir[2] - d[2] * dir[1], d[2] * dir[0] - d[0] * dir[2], d[0] * dir[1] - d[1] * dir[0]]
  const sinA = Math.hypot(...cr)
  const cosB = 1 / m; const sinB = Math.sqrt(m2 - 1) * cosB
  return 1 / (cosA * cosB - sinA * sinB)
}

for (const [key, t] of tiles) {
  const [z, x, y] = key.split('/').map(Number)
  const rect = tileRect(z, x, y)
  const lon = (uu) => rect.west + (uu / 32767) * (rect.east - rect.west)
  const lat = (vv) => rect.south + (vv / 32767) * (rect.north - rect.south)
  const tri = t.triangleIndices
  summary.tiles++
  summary.triangles += tri.length / 3
  const lv = (summary.levels[z] ??= { tiles: 0, triangles: 0, worst_ratio: 0, worst_drawn_ratio: 0 })
  lv.tiles++; lv.triangles += tri.length / 3
  for (let i = 0; i < tri.length; ++i) if (tri[i] >= t.n) { fail(`${key}: index ${tri[i]} of ${t.n} vertices`); break }
  let flipped = 0
  for (let i = 0; i < tri.length; i += 3) {
    const [a, b, c] = [tri[i], tri[i + 1], tri[i + 2]]
    if ((t.u[b] - t.u[a]) * (t.v[c] - t.v[a]) - (t.v[b] - t.v[a]) * (t.u[c] - t.u[a]) < 0) flipped++
  }
  if (flipped) fail(`${key}: ${flipped} triangles clockwise in u/v`)
  const edges = { west: (i) => t.u[i] === 0, south: (i) => t.v[i] === 0, east: (i) => t.u[i] === 32767, north: (i) => t.v[i] === 32767 }
  for (const [name, on] of Object.entries(edges)) {
    const list = t[`${name}Indices`]
    const want = []
    for (let i = 0; i < t.n; ++i) if (on(i)) want.push(i)
    const got = [...list].sort((p, q) => p - q)
    if (got.length !== want.length || got.some((g, i) => g !== want[i])) fail(`${key}: ${name} edge list is not the vertices on the edge`)
  }
  // Header: the bounding sphere holds every vertex; the occlusion point is CesiumJS's or farther.
  const hd = t.header
  const centre = [hd.boundingSphereCenterX, hd.boundingSphereCenterY, hd.boundingSphereCenterZ]
  const radii = hd.minHeight < 0 ? [WGS84_A + hd.minHeight, WGS84_A + hd.minHeight, WGS84_B + hd.minHeight] : [WGS84_A, WGS84_A, WGS84_B]
  const hop = [hd.horizonOcclusionPointX, hd.horizonOcclusionPointY, hd.horizonOcclusionPointZ]
  const hopLength = Math.hypot(...hop)
  const dir = hop.map((c) => c / hopLength)
  let magnitude = 0
  const xyz = []
  for (let i = 0; i < t.n; ++i) xyz.push(ecef(lon(t.u[i]), lat(t.v[i]), t.h[i]))
  for (let i = 0; i < t.n; ++i) {
    const p = xyz[i]
    if (Math.hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]) > hd.boundingSphereRadius * (1 + 1e-9) + 1e-6) {
      fail(`${key}: vertex ${i} outside the bounding sphere`); break
    }
    const m = occlusionMagnitude(radii, p, dir)
    magnitude = m < 0 || !Number.isFinite(m) ? Infinity : Math.max(magnitude, m)
  }
  if (Number.isFinite(magnitude) && hopLength < magnitude * (1 - 1e-9)) fail(`${key}: horizon occlusion point nearer than CesiumJS's (${hopLength} < ${magnitude})`)
  if (t.header.minHeight > t.header.maxHeight) fail(`${key}: minimum height over maximum`)
  // The flat triangle against the surface at its centroid, its edges' midpoints and three points
  // between (where the gap, nearly a paraboloid over the triangle, peaks).
  let chord = 0
  const places = [[1 / 3, 1 / 3, 1 / 3], [0.5, 0.5, 0], [0, 0.5, 0.5], [0.5, 0, 0.5], [2 / 3, 1 / 6, 1 / 6], [1 / 6, 2 / 3, 1 / 6], [1 / 6, 1 / 6, 2 / 3]]
  for (let i = 0; i < tri.length; i += 3) {
    const k = [tri[i], tri[i + 1], tri[i + 2]]
    const corners = k.map((j) => xyz[j])
    for (const w of places) {
      const at = (a) => w[0] * a[0] + w[1] * a[1] + w[2] * a[2]
      const flat = [0, 1, 2].map((c) => at(corners.map((p) => p[c])))
      const surface = ecef(lon(at(k.map((j) => t.u[j]))), lat(at(k.map((j) => t.v[j]))), at(k.map((j) => t.h[j])))
      chord = Math.max(chord, Math.hypot(flat[0] - surface[0], flat[1] - surface[1], flat[2] - surface[2]))
    }
  }
  if (chord > CHORD_SHARE * levelError(z)) fail(`${key}: a triangle drawn flat strays ${chord.toFixed(1)} m from the tile's surface, over ${CHORD_SHARE} of the level's error`)
  summary.worst_chord_ratio = Math.max(summary.worst_chord_ratio, chord / levelError(z))
  if (t.extensions?.vertexNormals && t.extensions.vertexNormals.length !== 2 * t.n) fail(`${key}: normals of ${t.extensions.vertexNormals.length / 2} vertices`)

  // Neighbours: the east and north ones share the tile's east and north edges.
  for (const [edge, other, otherEdge, along] of [['east', `${z}/${x + 1}/${y}`, 'west', 'v'], ['north', `${z}/${x}/${y + 1}`, 'south', 'u']]) {
    const n = tiles.get(other)
    if (!n) continue
    const mine = [...t[`${edge}Indices`]].map((i) => [t[along][i], t.h[i]]).sort((p, q) => p[0] - q[0])
    const theirs = [...n[`${otherEdge}Indices`]].map((i) => [n[along][i], n.h[i]]).sort((p, q) => p[0] - q[0])
    summary.shared_edges++
    if (mine.length !== theirs.length || mine.some((p, i) => p[0] !== theirs[i][0] || Math.abs(p[1] - theirs[i][1]) > 1e-6 * Math.max(1, Math.abs(p[1])))) {
      fail(`${key} and ${other}: the shared edge differs (${mine.length} and ${theirs.length} vertices)`)
    }
  }

  if (!checkError) continue
  // The error at every DEM sample inside the tile.
  const locate = locator({ u: t.u, v: t.v, tri })
  const bound = levelError(z)
  let worst = 0
  let worstDrawn = 0
  dems.forEach((dem, k) => {
    const earlier = dems.slice(0, k)
    const c0 = Math.max(0, Math.ceil(dem.col(rect.west))); const c1 = Math.min(dem.n - 1, Math.floor(dem.col(rect.east)))
    const r0 = Math.max(0, Math.ceil(dem.row(rect.north))); const r1 = Math.min(dem.n - 1, Math.floor(dem.row(rect.south)))
    for (let r = r0; r <= r1; ++r) {
      const pv = ((dem.lat(r) - rect.south) / (rect.north - rect.south)) * 32767
      if (pv < 0 || pv > 32767) continue
      for (let c = c0; c <= c1; ++c) {
        const pu = ((dem.lon(c) - rect.west) / (rect.east - rect.west)) * 32767
        const sample = dem.height(c, r)
        if (pu < 0 || pu > 32767 || sample === -32768) continue
        if (earlier.length && earlier.some((d) => d.covers(dem.lon(c), dem.lat(r)))) continue
        const w = locate(pu, pv)
        summary.samples++
        if (!w) { fail(`${key}: sample (${c}, ${r}) under no triangle`); continue }
        const [a, b, cc, l1, l2, l3] = w
        worst = Math.max(worst, Math.abs(l1 * t.h[a] + l2 * t.h[b] + l3 * t.h[cc] - sample) / bound)
        const p = dem.ecef(c, r, sample)
        const d = [0, 1, 2].map((k) => l1 * xyz[a][k] + l2 * xyz[b][k] + l3 * xyz[cc][k] - p[k])
        worstDrawn = Math.max(worstDrawn, Math.hypot(d[0], d[1], d[2]) / bound)
      }
    }
  })
  if (worst > 1) fail(`${key}: error ${(worst * bound).toFixed(3)} m over the level's ${bound.toFixed(3)} m`)
  if (worstDrawn > 1) fail(`${key}: drawn flat, ${(worstDrawn * bound).toFixed(3)} m from a sample, over the level's ${bound.toFixed(3)} m`)
  lv.worst_ratio = Math.max(lv.worst_ratio, worst)
  lv.worst_drawn_ratio = Math.max(lv.worst_drawn_ratio, worstDrawn)
  summary.worst_ratio = Math.max(summary.worst_ratio, worst)
  summary.worst_drawn_ratio = Math.max(summary.worst_drawn_ratio, worstDrawn)
}

console.log(JSON.stringify({ ...summary, failures }))
process.exit(failures.length ? 1 : 0)
