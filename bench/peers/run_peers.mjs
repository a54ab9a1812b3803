// Runs the npm heightmap meshers on a DEM exported by the benchmark suite and reports, per run,
// the time and the output; the triangles go to a binary file so the suite measures their error
// with the same exhaustive metric as tinlod's own outputs.
//
// usage: node run_peers.mjs GRID.f32 WIDTH HEIGHT OUT_PREFIX TOOL MAX_ERROR [REPEATS]
//   GRID.f32   little-endian float32 heights, row-major, row 0 = south (tinlod's Heightfield)
//   TOOL       delatin (Garland-Heckbert greedy insertion) or martini (RTIN; needs 2^k+1 square)
//   MAX_ERROR  vertical bound in the grid's height units
// prints one JSON line: {tool, max_error, ms: [..], vertices, triangles}; writes
// OUT_PREFIX.tri (uint32 sample ids, 3 per triangle, sample id = row * WIDTH + column).
import { readFileSync, writeFileSync } from "node:fs";
import Delatin from "delatin";
import Martini from "@mapbox/martini";

const [grid, w, h, prefix, tool, maxErrorText, repeatsText] = process.argv.slice(2);
const width = Number(w), height = Number(h), maxError = Number(maxErrorText);
const repeats = Number(repeatsText ?? 3);
const bytes = readFileSync(grid);
const heights = new Float32Array(bytes.buffer, bytes.byteOffset, width * height);

function runDelatin() {
  const tin = new Delatin(heights, width, height);
  tin.run(maxError);
  const { coords, triangles } = tin;
  const ids = new Uint32Array(triangles.length);
  for (let i = 0; i < triangles.length; i++) {
    const v = triangles[i];
    ids[i] = coords[2 * v + 1] * width + coords[2 * v];
  }
  return { ids, vertices: coords.length / 2 };
}

function runMartini() {
  if (width !== height || ((width - 1) & (width - 2)) !== 0)
    throw new Error(`martini needs a 2^k+1 square grid, got ${width}x${height}`);
  const martini = new Martini(width);
  const tile = martini.createTile(heights);
  const { vertices, triangles } = tile.getMesh(maxError);
  const ids = new Uint32Array(triangles.length);
  for (let i = 0; i < triangles.length; i++) {
    const v = triangles[i];
    ids[i] = vertices[2 * v + 1] * width + vertices[2 * v];
  }
  return { ids, vertices: vertices.length / 2 };
}

const run = tool === "delatin" ? runDelatin : tool === "martini" ? runMartini : null;
if (!run) throw new Error(`unknown tool ${tool}`);
const ms = [];
let out;
for (let i = 0; i < repeats; i++) {
  const t0 = process.hrtime.bigint();
  out = run();
  ms.push(Number(process.hrtime.bigint() - t0) / 1e6);
}
writeFileSync(`${prefix}.tri`, Buffer.from(out.ids.buffer));
console.log(JSON.stringify({ tool, max_error: maxError, ms, vertices: out.vertices, triangles: out.ids.length / 3 }));
