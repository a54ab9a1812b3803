// Shows a tinlod tile set in CesiumJS (npm `cesium`) in headless Chromium (Debian's, driven by npm
// `puppeteer-core`), as a user's page would, and checks what it loads and draws.
//
//   node cesium_view.mjs DIR DEM.hgt [--png FILE] [--size WxH]
//
// A server on 127.0.0.1 (node's http) serves the page, the `cesium` package's Build/Cesium as
// CESIUM_BASE_URL and DIR as /terrain/, its .terrain files with `Content-Encoding: gzip`, as
// docs/tiles.md tells users to. The page reads the set through CesiumTerrainProvider.fromUrl with
// vertex normals, no imagery and nothing from Cesium ion (a request to any other host is blocked
// and fails the check), and colours heights with an ElevationRamp material. Two views, each drawn
// over EllipsoidTerrainProvider and then over the set once the globe's tiles are loaded: the Earth
// from 4,000 km (both level-0 tiles; the DEM a speck) and the DEM from 9 km, lit (WxH, 480x300 by
// default; --png saves this picture). Prints one JSON object with `failures` (empty when every
// check holds): no tile error (the provider's errorEvent, the page's console errors), every tile
// requested is in the set, the Earth matches the bare ellipsoid's picture but for a few pixels (a
// missing level-0 tile or a triangle cutting under the surface shows), the DEM's picture differs
// from it in a large share of its pixels (a tile culled by a wrong bounding sphere or horizon
// occlusion point leaves the bare ellipsoid), and globe.getHeight at DEM samples is within the
// error of the level that draws them.
import fs from 'node:fs'
import http from 'node:http'
import path from 'node:path'
import url from 'node:url'
import puppeteer from 'puppeteer-core'
import { levelError, readHgt } from './srtm.mjs'

const args = process.argv.slice(2)
const option = (name) => { const i = args.indexOf(name); return i >= 0 ? args.splice(i, 2)[1] : undefined }
const pngPath = option('--png')
const [width, height] = (option('--size') ?? '480x300').split('x').map(Number)
const [dir, demPath] = args
const failures = []
const fail = (what) => { if (failures.length < 50) failures.push(what) }

// Views and bounds of the checks.
const CHROMIUM = '/usr/bin/chromium'
const LOAD_TIMEOUT_MS = 40000
const PIXEL_DIFFERS = 24 // a pixel differs when a channel does by more than this
const MIN_DIFFERING_SHARE = 0.4 // of the DEM view's pixels (the DEM fills most of it)
const MAX_EARTH_SHARE = 0.02 // of the Earth view's pixels (the DEM is a speck in it)
const HEIGHT_SLACK = 1.0 // metres: Cesium stores a small tile's positions in 12 bits of its box

const here = path.dirname(url.fileURLToPath(import.meta.url))
const cesiumDir = path.join(here, 'node_modules/cesium/Build/Cesium')
const layer = JSON.parse(fs.readFileSync(path.join(dir, 'layer.json'), 'utf8'))
const dem = readHgt(demPath)

const listed = (z, x, y) => (layer.available[z] ?? []).some((r) => x >= r.startX && x <= r.endX && y >= r.startY && y <= r.endY)

// --- the server
const types = { '.js': 'text/javascript', '.json': 'application/json', '.css': 'text/css', '.png': 'image/png', '.jpg': 'image/jpeg', '.wasm': 'application/wasm', '.svg': 'image/svg+xml', '.html': 'text/html' }
const page = `<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<link rel="stylesheet" href="/cesium/Widgets/widgets.css">
<style>html, body { margin: 0; background: #000 } #globe { width: ${width}px; height: ${height}px }</style>
<script>window.CESIUM_BASE_URL = '/cesium/'</script><script src="/cesium/Cesium.js"></script>
</head><body><div id="globe"></div></body></html>`
const terrainRequests = []
function serve (req, res) {
  const p = decodeURIComponent(new URL(req.url, 'http://127.0.0.1').pathname)
  const send = (status, body, headers = {}) => { res.writeHead(status, headers); res.end(body) }
  if (p === '/') return send(200, page, { 'Content-Type': 'text/html' })
  const [root, prefix] = p.startsWith('/cesium/') ? [cesiumDir, '/cesium/'] : p.startsWith('/terrain/') ? [dir, '/terrain/'] : []
  if (!root) return send(404, '')
  const file = path.join(root, path.normalize(p.slice(prefix.length)))
  const ok = file.startsWith(path.resolve(root)) && fs.existsSync(file) && fs.statSync(file).isFile()
  if (prefix === '/terrain/') terrainRequests.push({ path: p.slice(prefix.length), status: ok ? 200 : 404 })
  if (!ok) return send(404, '')
  const headers = { 'Content-Type': types[path.extname(file)] ?? 'application/octet-stream' }
  if (file.endsWith('.terrain')) Object.assign(headers, { 'Content-Type': 'application/vnd.quantized-mesh', 'Content-Encoding': 'gzip' })
  send(200, fs.readFileSync(file), headers)
}

// --- what the page does: each view over the bare ellipsoid, then over the set's terrain
async function inPage ({ views, ramp, light, samples, timeoutMs, png }) {
  const C = window.Cesium
  const errors = []
  const widget = new C.CesiumWidget('globe', {
    baseLayer: false,
    terrainProvider: new C.EllipsoidTerrainProvider(),
    clock: new C.Clock({ currentTime: C.JulianDate.fromIso8601('2024-06-21T10:00:00Z'), shouldAnimate: false }),
    contextOptions: { webgl: { preserveDrawingBuffer: true } },
    msaaSamples: 1 // SwiftShader draws in software: no more than the picture needs
  })
  const scene = widget.scene
  const globe = scene.globe
  scene.postProcessStages.fxaa.enabled = false
  globe.showGroundAtmosphere = false
  // The globe loads tiles for at most this many milliseconds a frame (5 by default, for a smooth
  // frame rate): a frame of SwiftShader takes far longer anyway.
  globe._surface._loadQueueTimeSlice = 200
  // Heights as colours: a ramp from the DEM's lowest to its highest sample; a lit view takes a
  // fixed sun from the north-west (on the tiles' vertex normals) so the relief reads.
  const canvas = document.createElement('canvas')
  canvas.width = 256; canvas.height = 1
  const g = canvas.getContext('2d')
  const grad = g.createLinearGradient(0, 0, 256, 0)
  for (const [at, colour] of ramp.stops) grad.addColorStop(at, colour)
  g.fillStyle = grad; g.fillRect(0, 0, 256, 1)
  globe.material = C.Material.fromType('ElevationRamp', { image: canvas, minimumHeight: ramp.min, maximumHeight: ramp.max })
  const enu = C.Transforms.eastNorthUpToFixedFrame(C.Cartesian3.fromDegrees(light.lon, light.lat))
  const towardsGround = C.Matrix4.multiplyByPointAsVector(enu, new C.Cartesian3(0.5, -0.5, -0.6), new C.Cartesian3())
  scene.light = new C.DirectionalLight({ direction: C.Cartesian3.normalize(towardsGround, towardsGround), intensity: 2.2 })

  // Shows a view and resolves with its picture once the globe has had nothing to load for a few
  // frames.
  const container = document.getElementById('globe')
  const show = (view) => new Promise((resolve, reject) => {
    container.style.width = `${view.width}px`; container.style.height = `${view.height}px`
    globe.enableLighting = view.lit
    scene.camera.setView({
      destination: C.Cartesian3.fromDegrees(view.camera.lon, view.camera.lat, view.camera.height),
      orientation: { heading: C.Math.toRadians(view.camera.heading), pitch: C.Math.toRadians(view.camera.pitch), roll: 0 }
    })
    const start = performance.now()
    let frames = 0; let calm = 0
    const remove = scene.postRender.addEventListener(() => {
      ++frames
      calm = globe.tilesLoaded ? calm + 1 : 0
      if (calm >= 2 && frames >= 5) {
        remove()
        const copy = document.createElement('canvas')
        copy.width = scene.canvas.width; copy.height = scene.canvas.height
        const c2 = copy.getContext('2d')
        c2.drawImage(scene.canvas, 0, 0)
        resolve({ frames, ms: Math.round(performance.now() - start), pixels: c2.getImageData(0, 0, copy.width, copy.height).data, png: png && view.saved ? scene.canvas.toDataURL('image/png') : undefined })
      } else if (performance.now() - start > timeoutMs) {
        remove()
        reject(new Error(`${view.name}: the globe's tiles were not loaded after ${timeoutMs} ms (${frames} frames)`))
      }
    })
  })

  const bare = []
  for (const view of views) bare.push(await show(view))
  const provider = await C.CesiumTerrainProvider.fromUrl('/terrain/', { requestVertexNormals: true })
  provider.errorEvent.addEventListener((e) => errors.push(e.message))
  globe.terrainProvider = provider
  const out = { errors, views: {} }
  for (const [k, view] of views.entries()) {
    const shown = await show(view)
    // The share of pixels the terrain changed.
    let differing = 0
    const a = bare[k].pixels; const b = shown.pixels
    for (let i = 0; i < a.length; i += 4) {
      const d = Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2]))
      if (d > view.pixelDiffers) differing++
    }
    out.views[view.name] = { frames: [bare[k].frames, shown.frames], ms: [bare[k].ms, shown.ms], differing_share: differing / (a.length / 4) }
    if (shown.png) out.png = shown.png
  }

  // In the last view: the height Cesium draws at each sample, and the level of the tile it takes
  // it from (the deepest one holding a mesh, as Globe.getHeight walks the quadtree).
  out.heights = samples.map(([lon, lat]) => {
    const c = C.Cartographic.fromDegrees(lon, lat)
    const h = globe.getHeight(c)
    let tile = globe._surface._levelZeroTiles.find((t) => C.Rectangle.contains(t.rectangle, c))
    let level
    while (tile) {
      if (tile.data?.renderedMesh) level = tile.level
      tile = [tile._southwestChild, tile._southeastChild, tile._northwestChild, tile._northeastChild].find((t) => t && C.Rectangle.contains(t.rectangle, c))
    }
    return { h, level }
  })
  return out
}

// --- the run
const server = http.createServer(serve)
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve))
const origin = `http://127.0.0.1:${server.address().port}`
const browser = await puppeteer.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: ['--headless=new', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist',
    ...(process.getuid?.() === 0 ? ['--no-sandbox'] : [])],
  defaultViewport: { width, height, deviceScaleFactor: 1 }
})
const report = {}
const clock = { start: performance.now() }
const lap = (name) => { clock[name] = Math.round(performance.now() - clock.start) }
try {
  const tab = await browser.newPage()
  const foreign = []
  await tab.setRequestInterception(true)
  tab.on('request', (r) => {
    const u = new URL(r.url())
    if (/^(https?|wss?):$/.test(u.protocol) && u.hostname !== '127.0.0.1') {
      foreign.push(r.url())
      r.abort()
    } else r.continue()
  })
  const consoleErrors = []
  tab.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()) })
  tab.on('pageerror', (e) => consoleErrors.push(String(e)))
  lap('launch')
  await tab.goto(`${origin}/`, { waitUntil: 'load' })
  lap('page')

  // The views: the Earth from 4,000 km over the prime meridian (both level-0 tiles, the DEM a
  // speck: the rest must be the bare ellipsoid), then the DEM tile from its south edge at 9 km,
  // looking north to the main ridge, lit.
  const lonC = dem.lon0 + 0.5; const latC = dem.lat0 + 0.5
  const views = [
    { name: 'earth', width: 320, height: 200, lit: false, camera: { lon: 0, lat: latC - 4, height: 4e6, heading: 0, pitch: -90 }, pixelDiffers: PIXEL_DIFFERS },
    { name: 'dem', width, height, lit: true, saved: true, camera: { lon: dem.lon0 + 0.45, lat: dem.lat0 + 0.05, height: 9000, heading: 0, pitch: -16 }, pixelDiffers: PIXEL_DIFFERS }
  ]
  let lo = Infinity; let hi = -Infinity
  for (let r = 0; r < dem.n; ++r) for (let c = 0; c < dem.n; ++c) { const h = dem.height(c, r); if (h !== -32768) { lo = Math.min(lo, h); hi = Math.max(hi, h) } }
  const ramp = { min: lo, max: hi, stops: [[0, '#2f6b3a'], [0.25, '#7fa65a'], [0.5, '#c9b97a'], [0.75, '#9a7b5a'], [1, '#f4f1ec']] }
  // Every 60th post.
  const posts = []
  for (let r = 30; r < dem.n; r += 60) for (let c = 30; c < dem.n; c += 60) if (dem.height(c, r) !== -32768) posts.push([c, r])
  const samples = posts.map(([c, r]) => [dem.lon(c), dem.lat(r)])

  const got = await tab.evaluate(inPage, { views, ramp, light: { lon: lonC, lat: latC }, samples, timeoutMs: LOAD_TIMEOUT_MS, png: Boolean(pngPath) })
  lap('views')
  if (pngPath) fs.writeFileSync(pngPath, Buffer.from(got.png.replace(/^data:image\/png;base64,/, ''), 'base64'))

  for (const e of got.errors) fail(`terrain provider error: ${e}`)
  for (const e of consoleErrors) fail(`console error: ${e}`)
  for (const u of foreign) fail(`a request left 127.0.0.1: ${u}`)
  const tiles = terrainRequests.filter((r) => r.path.endsWith('.terrain'))
  if (!terrainRequests.some((r) => r.path === 'layer.json' && r.status === 200)) fail('layer.json was not read')
  for (const r of tiles) {
    const [z, x, y] = r.path.replace(/\.terrain$/, '').split('/').map(Number)
    if (r.status !== 200) fail(`${r.path}: requested, not in the set (${listed(z, x, y) ? 'though' : 'nor'} in available)`)
  }
  if (!tiles.length) fail('no tile was requested')
  const share = (name) => got.views[name].differing_share
  const percent = (x) => `${(100 * x).toFixed(1)}%`
  if (share('dem') < MIN_DIFFERING_SHARE) fail(`the DEM's picture differs from the bare ellipsoid's in ${percent(share('dem'))} of its pixels, not ${percent(MIN_DIFFERING_SHARE)}`)
  if (share('earth') > MAX_EARTH_SHARE) fail(`the Earth's picture differs from the bare ellipsoid's in ${percent(share('earth'))} of its pixels, over ${percent(MAX_EARTH_SHARE)}`)

  // Heights: within the error of the deepest level `available` lists at or above the drawing one
  // (Cesium upsamples a tile the set leaves out from its parent).
  let worst = 0; let checked = 0; const levels = {}
  got.heights.forEach(({ h, level }, i) => {
    const [lon, lat] = samples[i]
    // Not where the ray Globe.getHeight casts could hit a skirt: on the edge of a tile drawn.
    const size = 180 / 2 ** level
    const onEdge = [lon + 180, lat + 90].some((d) => Math.abs(d / size - Math.round(d / size)) < 1e-9)
    if (h === undefined || level === undefined || onEdge) return
    let z = level
    const inTile = (z) => { const s = 180 / 2 ** z; return [Math.min(2 ** (z + 1) - 1, Math.floor((lon + 180) / s)), Math.min(2 ** z - 1, Math.floor((lat + 90) / s))] }
    while (z > 0 && !listed(z, ...inTile(z))) --z
    const [c, r] = posts[i]
    const ratio = Math.max(0, Math.abs(h - dem.height(c, r)) - HEIGHT_SLACK) / levelError(z)
    if (ratio > 1) fail(`Cesium's height at (${lon.toFixed(4)}, ${lat.toFixed(4)}) is ${h.toFixed(2)} m, the DEM's ${dem.height(c, r)} m: over level ${z}'s ${levelError(z).toFixed(2)} m`)
    worst = Math.max(worst, ratio); checked++
    levels[z] = (levels[z] ?? 0) + 1
  })
  Object.assign(report, {
    tile_requests: tiles.length,
    tile_levels: [...new Set(tiles.map((r) => Number(r.path.split('/')[0])))].sort((p, q) => p - q),
    views: got.views,
    ms: { launch: clock.launch, page: clock.page, views: clock.views },
    height_samples: checked,
    height_levels: levels,
    worst_height_ratio: worst
  })
} catch (e) {
  fail(String(e?.stack ?? e))
} finally {
  await browser.close()
  server.close()
}
console.log(JSON.stringify({ ...report, failures }))
process.exit(failures.length ? 1 : 0)
