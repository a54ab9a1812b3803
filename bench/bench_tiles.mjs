// bench_tiles: `tinlod tiles` beside the tile builders people use today, as whole processes on one
// core each, on the same DEMs: tin-terrain (`dem2tintiles`, greedy-insertion quantized-mesh in the
// Web Mercator scheme), cesium-terrain-builder (`ctb-tile`: heightmap-1.0, its default, and
// quantized-mesh, `-f Mesh`, from the ahuarte47 fork), all built from bench/peers. Every set is
// then read back here, with code none of the builders share: quantized-mesh tiles by
// @here/quantized-mesh-decoder (npm, installed in tests/tiles), heightmap tiles by the few lines
// of decodeHeightmap, each as the TIN CesiumJS draws; and measured as tests/tiles/check_tiles.mjs
// measures tinlod's: every DEM sample inside a tile against the error CesiumJS assumes for its
// level, and neighbours' shared edges vertex for vertex (plus the largest vertical gap along them).
//
//   node bench/bench_tiles.mjs --bin build/bin --meshes meshes --out bench/results --tmp DIR
//        [--quick] [--command CMD]
//
// Writes OUT/tiles.csv (one row per DEM, tool and level, and one per run with its time) and
// OUT/tiles.md (the section bench/run.sh appends to RESULTS.md). Needs gdal_fillnodata.py,
// gdalwarp, gdal_translate and gdalinfo (gdal-bin) and /usr/bin/time.
import fs from 'node:fs'
import path from 'node:path'
import zlib from 'node:zlib'
import { createRequire } from 'node:module'
import { spawnSync, execFileSync } from 'node:child_process'
import os from 'node:os'
import { heightAt, locator } from '../tests/tiles/tin_locator.mjs'

const here = path.dirname(new URL(import.meta.url).pathname)
const root = path.resolve(here, '..')
const args = process.argv.slice(2)
const opt = (name, fallback) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : fallback }
const quick = args.includes('--quick')
const bin = path.resolve(opt('--bin', 'build/bin'))
const meshes = path.resolve(opt('--meshes', path.join(root, 'meshes')))
const out = path.resolve(opt('--out', path.join(root, 'bench/results')))
const tmp = fs.mkdtempSync(path.join(path.resolve(opt('--tmp', os.tmpdir())), 'tiles-'))
const command = opt('--command', 'node bench/bench_tiles.mjs')
const reps = quick ? 1 : 3
const decode = createRequire(path.join(root, 'tests/tiles/package.json'))('@here/quantized-mesh-decoder').default

// CesiumJS's bound for a level: TerrainProvider.getEstimatedLevelZeroGeometricErrorForAHeightmap
// (WGS84, 65, level-0 tiles across) halved per level. Geographic: 2 tiles across; Web Mercator: 1.
const WGS84_A = 6378137.0
const levelError = (scheme, z) => (WGS84_A * 2 * Math.PI * 0.25) / (65 * (scheme === 'mercator' ? 1 : 2)) / 2 ** z
// A Web Mercator level z tile spans the longitudes of a geographic level z - 1 tile, with the same
// bound: the level whose bound it shares, for the tables.
const boundLevel = (scheme, z) => (scheme === 'mercator' ? z - 1 : z)

function run (exe, argv, cwd = tmp) {
  const timeFile = path.join(tmp, 'time.txt')
  // Pinned to core 0, as bench_heightmap pins hmm and tinlod.
  const r = spawnSync('taskset', ['-c', '0', '/usr/bin/time', '-f', '%e %M', '-o', timeFile, exe, ...argv], { cwd, encoding: 'utf8', maxBuffer: 1 << 28 })
  if (r.status !== 0) throw new Error(`${path.basename(exe)} ${argv.join(' ')}: exit ${r.status}\n${r.stderr.slice(-2000)}`)
  const [seconds, kb] = fs.readFileSync(timeFile, 'utf8').trim().split('\n').pop().split(' ').map(Number)
  return { seconds, mb: kb / 1024 }
}

// --- the DEM as GDAL reads it: samples at pixel centres (the geotransform's), voids as NaN
function readDem (file) {
  const info = JSON.parse(execFileSync('gdalinfo', ['-json', file], { encoding: 'utf8', maxBuffer: 1 << 26 }))
  const raw = path.join(tmp, path.basename(file) + '.f32')
  execFileSync('gdal_translate', ['-q', '-of', 'ENVI', '-ot', 'Float32', file, raw])
  const buf = fs.readFileSync(raw)
  const z = new Float32Array(buf.buffer, buf.byteOffset, buf.length / 4)
  const [w, h] = info.size
  const [x0, dx, , y0, , dy] = info.geoTransform
  const nodata = info.bands[0].noDataValue
  return {
    w, h,
    lon: (c) => x0 + (c + 0.5) * dx,
    lat: (r) => y0 + (r + 0.5) * dy,
    col: (lon) => (lon - x0) / dx - 0.5,
    row: (lat) => (lat - y0) / dy - 0.5,
    height: (c, r) => { const v = z[r * w + c]; return v === nodata || Number.isNaN(v) ? NaN : v }
  }
}

// --- tiles, each read as the TIN CesiumJS draws: u, v in 0..32767 across the tile, heights in metres
function readQuantizedMesh (buf) {
  const data = new ArrayBuffer(buf.length) // the decoder views the buffer from byte 0
  new Uint8Array(data).set(buf)
  const t = decode(data)
  const n = t.vertexData.length / 3
  const { minHeight, maxHeight } = t.header
  const q = t.vertexData.subarray(2 * n, 3 * n)
  return {
    n,
    u: Float64Array.from(t.vertexData.subarray(0, n)),
    v: Float64Array.from(t.vertexData.subarray(n, 2 * n)),
    h: Float64Array.from(q, (x) => minHeight + (x / 32767) * (maxHeight - minHeight)),
    tri: t.triangleIndices
  }
}

// heightmap-1.0: 65 x 65 little-endian uint16, height = value / 5 - 1000, row 0 north, the posts
// on the tile's edges; CesiumJS's HeightmapTessellator cuts each cell from south-west to north-east.
function decodeHeightmap (buf) {
  const S = 65
  if (buf.length < 2 * S * S) throw new Error(`heightmap tile of ${buf.length} bytes`)
  const n = S * S
  const u = new Float64Array(n); const v = new Float64Array(n); const h = new Float64Array(n)
  for (let r = 0; r < S; ++r) {
    for (let c = 0; c < S; ++c) {
      const i = r * S + c
      u[i] = (c / (S - 1)) * 32767
      v[i] = ((S - 1 - r) / (S - 1)) * 32767
      h[i] = buf.readUInt16LE(2 * i) / 5 - 1000
    }
  }
  const tri = []
  for (let r = 0; r + 1 < S; ++r) {
    for (let c = 0; c + 1 < S; ++c) {
      const nw = r * S + c; const ne = nw + 1; const sw = nw + S; const se = sw + 1
      tri.push(sw, se, ne, sw, ne, nw)
    }
  }
  return { n, u, v, h, tri: Uint32Array.from(tri) }
}

const countTiles = (dir) => fs.readdirSync(dir, { recursive: true }).filter((f) => f.endsWith('.terrain')).length

function readSet (dir, format) {
  const tiles = new Map()
  for (const z of fs.readdirSync(dir)) {
    if (!/^\d+$/.test(z)) continue
    for (const x of fs.readdirSync(path.join(dir, z))) {
      for (const f of fs.readdirSync(path.join(dir, z, x))) {
        if (!f.endsWith('.terrain')) continue
        const file = fs.readFileSync(path.join(dir, z, x, f))
        const gzipped = file[0] === 0x1f && file[1] === 0x8b
        const raw = gzipped ? zlib.gunzipSync(file) : file
        // As served: gzip-compressed (Content-Encoding: gzip); a tool writing plain tiles gets zlib's default level.
        const bytes = gzipped ? file.length : zlib.gzipSync(raw).length
        const t = format === 'heightmap' ? decodeHeightmap(raw) : readQuantizedMesh(raw)
        tiles.set(`${z}/${x}/${f.slice(0, -8)}`, { ...t, bytes })
      }
    }
  }
  return tiles
}

// The tile's extent: longitudes, and latitudes (geographic) or normalised Mercator y (mercator).
function tileRect (scheme, z, x, y) {
  const span = (scheme === 'mercator' ? 360 : 180) / 2 ** z
  const west = -180 + x * span
  if (scheme === 'mercator') {
    const m = (2 * Math.PI) / 2 ** z
    return { west, east: west + span, south: -Math.PI + y * m, north: -Math.PI + (y + 1) * m }
  }
  return { west, east: west + span, south: -90 + y * span, north: -90 + (y + 1) * span }
}
const mercatorY = (lat) => Math.log(Math.tan(Math.PI / 4 + (lat * Math.PI) / 360))
const mercatorLat = (my) => (360 / Math.PI) * Math.atan(Math.exp(my)) - 90

// --- the measures of one tile set: per level, tiles, triangles, bytes, the worst error over the
// level's bound at the DEM's samples, samples under no triangle, shared edges, the edges whose
// vertices differ (check_tiles.mjs's crack) and the largest vertical gap along them.
function measure (tiles, scheme, dem) {
  const levels = new Map()
  for (const [key, t] of tiles) {
    const [z, x, y] = key.split('/').map(Number)
    const lv = levels.get(z) ?? { level: z, tiles: 0, triangles: 0, tri_max: 0, bytes: 0, worst_ratio: 0, inner_tiles: 0, worst_inner: 0, samples: 0, uncovered: 0, shared_edges: 0, cracked_edges: 0, max_gap_m: 0 }
    levels.set(z, lv)
    const nTri = t.tri.length / 3
    lv.tiles++; lv.triangles += nTri; lv.tri_max = Math.max(lv.tri_max, nTri); lv.bytes += t.bytes
    const bound = levelError(scheme, z)

    for (const [edge, other, otherEdge, along] of [['east', `${z}/${x + 1}/${y}`, 'west', 'v'], ['north', `${z}/${x}/${y + 1}`, 'south', 'u']]) {
      const n = tiles.get(other)
      if (!n) continue
      lv.shared_edges++
      const mine = edgePolyline(t, edge, along); const theirs = edgePolyline(n, otherEdge, along)
      const same = mine.length === theirs.length && mine.every((p, i) => p[0] === theirs[i][0] && Math.abs(p[1] - theirs[i][1]) <= 1e-6 * Math.max(1, Math.abs(p[1])))
      if (same) continue
      lv.cracked_edges++
      lv.max_gap_m = Math.max(lv.max_gap_m, gap(mine, theirs), gap(theirs, mine))
    }

    const rect = tileRect(scheme, z, x, y)
    const pu = (lon) => ((lon - rect.west) / (rect.east - rect.west)) * 32767
    const pv = scheme === 'mercator'
      ? (lat) => ((mercatorY(lat) - rect.south) / (rect.north - rect.south)) * 32767
      : (lat) => ((lat - rect.south) / (rect.north - rect.south)) * 32767
    const latNorth = scheme === 'mercator' ? mercatorLat(rect.north) : rect.north
    const latSouth = scheme === 'mercator' ? mercatorLat(rect.south) : rect.south
    const c0 = Math.max(0, Math.ceil(dem.col(rect.west) - 1e-9)); const c1 = Math.min(dem.w - 1, Math.floor(dem.col(rect.east) + 1e-9))
    const r0 = Math.max(0, Math.ceil(dem.row(latNorth) - 1e-9)); const r1 = Math.min(dem.h - 1, Math.floor(dem.row(latSouth) + 1e-9))
    if (c0 > c1 || r0 > r1) continue
    const locate = locator(t)
    let worst = 0
    for (let r = r0; r <= r1; ++r) {
      const sv = pv(dem.lat(r))
      if (sv < 0 || sv > 32767) continue
      for (let c = c0; c <= c1; ++c) {
        const su = pu(dem.lon(c))
        const sample = dem.height(c, r)
        if (su < 0 || su > 32767 || Number.isNaN(sample)) continue
        lv.samples++
        const h = heightAt(t, locate, su, sv)
        if (Number.isNaN(h)) { lv.uncovered++; continue }
        worst = Math.max(worst, Math.abs(h - sample) / bound)
      }
    }
    lv.worst_ratio = Math.max(lv.worst_ratio, worst)
    // Tiles wholly inside the DEM's samples: no coverage edge, no fill, nothing to resample across.
    if (rect.west >= dem.lon(0) && rect.east <= dem.lon(dem.w - 1) && latNorth <= dem.lat(0) && latSouth >= dem.lat(dem.h - 1)) {
      lv.inner_tiles++
      lv.worst_inner = Math.max(lv.worst_inner, worst)
    }
  }
  return [...levels.values()].sort((a, b) => a.level - b.level)
}

// The vertices on one edge of a tile, [position along it, height], in order.
function edgePolyline (t, edge, along) {
  const on = { west: (i) => t.u[i] === 0, east: (i) => t.u[i] === 32767, south: (i) => t.v[i] === 0, north: (i) => t.v[i] === 32767 }[edge]
  const p = []
  for (let i = 0; i < t.n; ++i) if (on(i)) p.push([t[along][i], t.h[i]])
  return p.sort((a, b) => a[0] - b[0] || a[1] - b[1])
}

// The largest height difference between the vertices of `a` and the polyline `b` where b spans them.
function gap (a, b) {
  let worst = 0; let j = 0
  for (const [s, h] of a) {
    while (j + 1 < b.length && b[j + 1][0] < s) ++j
    if (j + 1 >= b.length || b[j][0] > s) continue
    const [s0, h0] = b[j]; const [s1, h1] = b[j + 1]
    const hb = s1 === s0 ? h0 : h0 + ((s - s0) / (s1 - s0)) * (h1 - h0)
    worst = Math.max(worst, Math.abs(h - hb))
  }
  return worst
}

// --- the runs
const inputs = [
  { name: 'N42E001', file: path.join(meshes, 'N42E001.hgt'), about: 'SRTM3, 1201², 3″, 7,652 voids' },
  { name: 'dem_srtm30', file: path.join(meshes, 'dem_srtm30.tif'), about: 'SRTM30 GeoTIFF, 300², 30″' }
]
const rows = []
const runs = []
const matchedRuns = []
for (const input of inputs) {
  // The peers get the DEM with its voids filled by GDAL (tinlod fills its own); tin-terrain reads
  // Web Mercator only, so it gets that warped (bilinear) at gdalwarp's default resolution.
  const filled = path.join(tmp, `${input.name}-filled.tif`)
  const mercator = path.join(tmp, `${input.name}-3857.tif`)
  execFileSync('gdal_fillnodata.py', ['-q', input.file, filled])
  execFileSync('gdalwarp', ['-q', '-t_srs', 'EPSG:3857', '-r', 'bilinear', filled, mercator])
  const dem = readDem(input.file)
  // tinlod's default last level, given to ctb-tile too: the first whose tiles' 64 spacings are no
  // coarser than the DEM's (docs/tiles.md, "The default --max-zoom").
  const spacing = Math.min(Math.abs(dem.lon(1) - dem.lon(0)), Math.abs(dem.lat(1) - dem.lat(0)))
  const maxZoom = Math.ceil(Math.log2(180 / (64 * spacing)) - 1e-9)
  // argv(dir, lo, hi): the run writing levels lo to hi into dir (tin-terrain: its own levels).
  const tools = [
    { tool: 'tinlod', scheme: 'geographic', format: 'quantized-mesh', exe: 'tinlod', argv: (o, lo, hi) => ['--threads', '1', 'tiles', input.file, '-o', o, '--min-zoom', String(lo), '--max-zoom', String(hi)] },
    { tool: 'tin-terrain', scheme: 'mercator', format: 'quantized-mesh', exe: 'tin-terrain', argv: (o) => ['--log', 'none', 'dem2tintiles', '--input', mercator, '--output-dir', o, '--min-zoom', '0', '--max-zoom', '21'] },
    { tool: 'ctb heightmap', scheme: 'geographic', format: 'heightmap', exe: 'ctb-tile', argv: (o, lo, hi) => ['-q', '-c', '1', '-s', String(hi), '-e', String(lo), '-o', o, filled] },
    { tool: 'ctb mesh', scheme: 'geographic', format: 'quantized-mesh', exe: 'ctb-tile', argv: (o, lo, hi) => ['-q', '-c', '1', '-f', 'Mesh', '-s', String(hi), '-e', String(lo), '-o', o, filled] }
  ]
  // Each tool `reps` times, alternated (reversed every other round); the least wall time.
  const timeRuns = (list, lo, hi, keep) => {
    const best = new Map()
    for (let rep = 0; rep < reps; ++rep) {
      for (const t of rep % 2 ? [...list].reverse() : list) {
        const dir = path.join(tmp, `${input.name}-${t.tool.replace(' ', '-')}`)
        fs.rmSync(dir, { recursive: true, force: true })
        fs.mkdirSync(dir)
        const r = run(path.join(bin, t.exe), t.argv(dir, lo, hi))
        const b = best.get(t.tool)
        const tiles = keep ? 0 : countTiles(dir)
        if (!keep) fs.rmSync(dir, { recursive: true })
        best.set(t.tool, { seconds: Math.min(b?.seconds ?? Infinity, r.seconds), mb: Math.max(b?.mb ?? 0, r.mb), dir, tiles })
      }
    }
    return best
  }
  const best = timeRuns(tools, 0, maxZoom, true)
  for (const t of tools) {
    const { seconds, mb, dir } = best.get(t.tool)
    const levels = measure(readSet(dir, t.format), t.scheme, dem)
    fs.rmSync(dir, { recursive: true })
    const sum = (k) => levels.reduce((s, l) => s + l[k], 0)
    const max = (k) => levels.reduce((s, l) => Math.max(s, l[k]), 0)
    const total = {
      dem: input.name, tool: t.tool, scheme: t.scheme, format: t.format, seconds, peak_mb: mb,
      first: levels[0].level, last: levels.at(-1).level, tiles: sum('tiles'), triangles: sum('triangles'),
      tri_max: max('tri_max'), bytes: sum('bytes'), worst_ratio: max('worst_ratio'), inner_tiles: sum('inner_tiles'), worst_inner: max('worst_inner'), samples: sum('samples'),
      uncovered: sum('uncovered'), shared_edges: sum('shared_edges'), cracked_edges: sum('cracked_edges'), max_gap_m: max('max_gap_m')
    }
    runs.push(total)
    for (const l of levels) rows.push({ dem: input.name, tool: t.tool, scheme: t.scheme, format: t.format, bound_level: boundLevel(t.scheme, l.level), bound_m: levelError(t.scheme, l.level), ...l })
    console.error(`bench_tiles: ${input.name} ${t.tool}: ${total.tiles} tiles in ${seconds} s, worst ${total.worst_ratio.toFixed(3)}, ${total.cracked_edges}/${total.shared_edges} edges differ`)
  }
  // Time on tin-terrain's levels alone (by bound): the others run again on just those.
  const tt = runs.find((r) => r.dem === input.name && r.tool === 'tin-terrain')
  const lo = boundLevel('mercator', tt.first); const hi = Math.min(maxZoom, boundLevel('mercator', tt.last))
  const others = tools.filter((t) => t.scheme === 'geographic')
  const matched = timeRuns(others, lo, hi, false)
  matchedRuns.push({ dem: input.name, lo, hi, tools: [{ tool: 'tin-terrain', seconds: tt.seconds, tiles: tt.tiles }, ...others.map((t) => ({ tool: t.tool, ...matched.get(t.tool) }))] })
}
fs.rmSync(tmp, { recursive: true, force: true })

// --- tiles.csv and tiles.md
fs.mkdirSync(out, { recursive: true })
const csvCols = ['dem', 'tool', 'scheme', 'format', 'level', 'bound_level', 'bound_m', 'tiles', 'triangles', 'tri_max', 'bytes', 'worst_ratio', 'inner_tiles', 'worst_inner', 'samples', 'uncovered', 'shared_edges', 'cracked_edges', 'max_gap_m', 'seconds', 'peak_mb']
const csvRow = (r) => csvCols.map((k) => (r[k] === undefined ? '' : typeof r[k] === 'number' && !Number.isInteger(r[k]) ? r[k].toPrecision(6) : r[k])).join(',')
fs.writeFileSync(path.join(out, 'tiles.csv'), [csvCols.join(','), ...runs.map((r) => csvRow({ ...r, level: 'all' })),
  ...matchedRuns.flatMap((m) => m.tools.map((x) => csvRow({ dem: m.dem, tool: x.tool, level: `bounds ${m.lo}-${m.hi}`, tiles: x.tiles, seconds: x.seconds, peak_mb: x.mb }))), ...rows.map(csvRow)].join('\n') + '\n')

const f = (x, d = 2) => x.toFixed(d)
const ratio = (a, b) => (b ? `${f(a / b)}×` : '–')
let md = `\n## Terrain tiles: tinlod tiles against tin-terrain and cesium-terrain-builder (bench_tiles.mjs; tiles.csv)\n\n`
md += `\`${command}\`: each builder as a whole process on one core (\`tinlod --threads 1\`, \`ctb-tile -c 1\`; tin-terrain has one thread), alternated, least wall time of ${reps}; `
md += 'every set read back by an npm decoder (heightmap tiles as CesiumJS tessellates them) and measured at every DEM sample inside every tile against the error CesiumJS assumes for the tile\'s level. '
md += 'tin-terrain writes Web Mercator tiles (a level z tile has the longitudes and the bound of a geographic level z - 1 tile) and only the levels its DEM\'s resolution suggests; ctb-tile is given tinlod\'s levels. '
md += 'Inner tiles: those wholly inside the DEM\'s samples (no coverage edge). Bytes are gzip as served (tin-terrain\'s plain tiles gzipped here). Cracks: shared tile edges whose vertices differ (position or decoded height), of all shared edges; gap: the largest height difference along such an edge.\n'
for (const input of inputs) {
  const mine = runs.filter((r) => r.dem === input.name)
  const base = mine.find((r) => r.tool === 'tinlod')
  md += `\n### ${input.name} (${input.about})\n\n`
  md += '| tool | levels | tiles | time s | tiles/s | MB gzip | triangles/tile mean, max | worst error / bound: all tiles, inner | samples under no triangle | cracks (edges) | gap m | peak MB | time, bytes, triangles vs tinlod |\n'
  md += '| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n'
  for (const r of mine) {
    md += `| ${r.tool} | ${r.first}-${r.last}${r.scheme === 'mercator' ? ' (Mercator)' : ''} | ${r.tiles} | ${f(r.seconds)} | ${f(r.tiles / r.seconds, 0)} | ${f(r.bytes / 1e6)} | ${f(r.triangles / r.tiles, 0)}, ${r.tri_max} | ${f(r.worst_ratio, 3)}, ${r.inner_tiles ? f(r.worst_inner, 3) : '–'} | ${r.uncovered} | ${r.cracked_edges} / ${r.shared_edges} | ${f(r.max_gap_m, 1)} | ${f(r.peak_mb, 0)} | `
    md += r === base ? '1 |\n' : `${ratio(r.seconds, base.seconds)}, ${ratio(r.bytes, base.bytes)}, ${ratio(r.triangles, base.triangles)} |\n`
  }
  // tin-terrain's levels, by bound: what each builder needs to cover the DEM at the same error.
  const m = matchedRuns.find((x) => x.dem === input.name)
  const at = (tool, l) => rows.find((x) => x.dem === input.name && x.tool === tool && x.bound_level === l)
  const mBase = m.tools.find((x) => x.tool === 'tinlod')
  md += `\nOn tin-terrain's levels (Web Mercator ${m.lo + 1}-${m.hi + 1}), the others run again on the geographic levels of the same bounds, ${m.lo}-${m.hi}: `
  md += `${m.tools.map((x) => `${x.tool} ${x.tiles} tiles in ${f(x.seconds)} s (${f(x.tiles / x.seconds, 0)} tiles/s${x === mBase ? '' : `, time ${ratio(x.seconds, mBase.seconds)} tinlod's`})`).join('; ')}. `
  md += 'Per level: triangles (× tinlod\'s), worst error / bound, cracked / shared edges, and samples under no triangle where there are any.\n\n'
  md += `| level | bound m | ${mine.map((r) => r.tool).join(' | ')} |\n| ---: | ---: |${mine.map(() => ' --- |').join('')}\n`
  for (let l = m.lo; l <= m.hi; ++l) {
    const b = at('tinlod', l)
    md += `| ${l} | ${f(b.bound_m, 1)} | ${mine.map((r) => {
      const x = at(r.tool, l)
      if (!x) return '–'
      return `${x.triangles}${x === b ? '' : ` (${ratio(x.triangles, b.triangles)})`}, ${f(x.worst_ratio, 2)}, ${x.cracked_edges}/${x.shared_edges}${x.uncovered ? `, ${x.uncovered} uncovered` : ''}`
    }).join(' | ')} |\n`
  }
}
fs.writeFileSync(path.join(out, 'tiles.md'), md)
console.log(md)
