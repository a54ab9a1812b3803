// Runs the npm heightmap meshers (delatin: Garland-Heckbert greedy insertion; martini: RTIN) on a
// DEM exported by the benchmark suite and reports, per run, the time and the output; the triangles
// go to a binary file so the suite measures their error with the same exhaustive metric
// (tinlod::measure_error) as tinlod's own outputs.
//
// usage: node run_peers.mjs GRID.f32 WIDTH HEIGHT OUT_PREFIX TOOL MODE VALUE [REPEATS]
//   GRID.f32  little-endian float32 heights, row-major, row 0 = south (tinlod's Heightfield)
//   TOOL      delatin, or martini (needs a 2^k+1 square grid)
//   MODE      max_error: VALUE is the vertical bound in the grid's height units;
//             nodes: VALUE is the node count to reach (delatin inserts points until it has that
//             many; martini bisects its error bound, untimed, to the count nearest VALUE)
// prints one JSON line: {tool, mode, value, max_error, ms: [..], cpu_ms: [..], vertices,
// triangles}; ms (wall) and cpu_ms (the process's CPU time, Node's helper threads included) time
// the meshing only (martini: createTile + getMesh), not Node's start-up or the file read. Writes
// OUT_PREFIX.tri (uint32 sample ids, 3 per triangle, sample id = row * WIDTH + column).
import { readFileSync, writeFileSync } from "node:fs";
import Delatin from "delatin";
import Martini from "@mapbox/martini";

const [grid, w, h, prefix, tool, mode, valueText, repeatsText] = process.argv.slice(2);
const width = Number(w), height = Number(h), value = Number(valueText);
const repeats = Number(repeatsText ?? 3);
if (mode !== "max_error" && mode !== "nodes") throw new Error(`unknown mode ${mode}`);
const bytes = readFileSync(grid);
const heights = new Float32Array(bytes.buffer, bytes.byteOffset, width * height);

function sampleIds(vertices, triangles) {
  const ids = new Uint32Array(triangles.length);
  for (let i = 0; i < triangles.length; i++) {
    const v = triangles[i];
    ids[i] = vertices[2 * v + 1] * width + vertices[2 * v];
  }
  return ids;
}

function runDelatin() {
  const tin = new Delatin(heights, width, height);
  if (mode === "max_error") tin.run(value);
  else while (tin.coords.length / 2 < value && tin.getMaxError() > 0) tin.refine();
  return { ids: sampleIds(tin.coords, tin.triangles), vertices: tin.coords.length / 2,
           maxError: tin.getMaxError() };
}

// The martini error bound whose mesh has the node count nearest `nodes` (bisection on a log scale).
function martiniErrorFor(nodes) {
  const tile = new Martini(width).createTile(heights);
  const count = (e) => tile.getMesh(e).vertices.length / 2;
  let lo = 1e-3, hi = 1e5;
  for (let i = 0; i < 40; i++) {
    const mid = Math.sqrt(lo * hi);
    if (count(mid) > nodes) lo = mid;
    else hi = mid;
  }
  return Math.abs(count(lo) - nodes) < Math.abs(count(hi) - nodes) ? lo : hi;
}

let martiniError = value;
function runMartini() {
  const tile = new Martini(width).createTile(heights);
  const { vertices, triangles } = tile.getMesh(martiniError);
  return { ids: sampleIds(vertices, triangles), vertices: vertices.length / 2,
           maxError: martiniError };
}

let run;
if (tool === "delatin") run = runDelatin;
else if (tool === "martini") {
  if (width !== height || ((width - 1) & (width - 2)) !== 0)
    throw new Error(`martini needs a 2^k+1 square grid, got ${width}x${height}`);
  if (mode === "nodes") martiniError = martiniErrorFor(value);
  run = runMartini;
} else throw new Error(`unknown tool ${tool}`);

const ms = [], cpuMs = [];
let out;
for (let i = 0; i < repeats; i++) {
  const t0 = process.hrtime.bigint(), c0 = process.cpuUsage();
  out = run();
  ms.push(Number(process.hrtime.bigint() - t0) / 1e6);
  const c = process.cpuUsage(c0);
  cpuMs.push((c.user + c.system) / 1e3);
}
writeFileSync(`${prefix}.tri`, Buffer.from(out.ids.buffer, out.ids.byteOffset, out.ids.byteLength));
console.log(JSON.stringify({ tool, mode, value, max_error: out.maxError, ms, cpu_ms: cpuMs,
                             vertices: out.vertices, triangles: out.ids.length / 3 }));
