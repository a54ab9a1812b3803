// The triangle of a decoded quantized-mesh tile under a place, shared by the tile check and the
// tiles benchmark so both measure a tile the same way.

// locator(t) for a tile with u, v (0..32767) and tri (3 indices per triangle) returns
// locate(pu, pv): [a, b, c, l1, l2, l3], the triangle's vertices and the place's barycentric
// weights, or null under no triangle. Triangles are found through a grid of buckets, and the last
// one found is tried first (samples come row by row, most in the triangle of the one before).
export function locator (t) {
  const tri = t.tri
  const B = Math.max(4, Math.min(128, Math.ceil(Math.sqrt(tri.length / 3)))); const cell = 32768 / B
  const buckets = Array.from({ length: B * B }, () => [])
  for (let i = 0; i < tri.length; i += 3) {
    const us = [t.u[tri[i]], t.u[tri[i + 1]], t.u[tri[i + 2]]]; const vs = [t.v[tri[i]], t.v[tri[i + 1]], t.v[tri[i + 2]]]
    for (let by = Math.floor(Math.min(...vs) / cell); by <= Math.floor(Math.max(...vs) / cell); ++by) {
      for (let bx = Math.floor(Math.min(...us) / cell); bx <= Math.floor(Math.max(...us) / cell); ++bx) buckets[by * B + bx].push(i)
    }
  }
  const inTriangle = (i, pu, pv) => {
    const a = tri[i]; const b = tri[i + 1]; const c = tri[i + 2]
    const d = (t.v[b] - t.v[c]) * (t.u[a] - t.u[c]) + (t.u[c] - t.u[b]) * (t.v[a] - t.v[c])
    if (d === 0) return null
    const l1 = ((t.v[b] - t.v[c]) * (pu - t.u[c]) + (t.u[c] - t.u[b]) * (pv - t.v[c])) / d
    const l2 = ((t.v[c] - t.v[a]) * (pu - t.u[c]) + (t.u[a] - t.u[c]) * (pv - t.v[c])) / d
    const l3 = 1 - l1 - l2
    const eps = -1e-9
    return l1 >= eps && l2 >= eps && l3 >= eps ? [a, b, c, l1, l2, l3] : null
  }
  let last = -1
  return (pu, pv) => {
    if (last >= 0) {
      const w = inTriangle(last, pu, pv)
      if (w) return w
    }
    const bx = Math.min(B - 1, Math.floor(pu / cell)); const by = Math.min(B - 1, Math.floor(pv / cell))
    for (const i of buckets[by * B + bx]) {
      const w = inTriangle(i, pu, pv)
      if (w) { last = i; return w }
    }
    return null
  }
}

// The tile's height at (pu, pv) through locate, or NaN under no triangle.
export function heightAt (t, locate, pu, pv) {
  const w = locate(pu, pv)
  if (!w) return NaN
  const [a, b, c, l1, l2, l3] = w
  return l1 * t.h[a] + l2 * t.h[b] + l3 * t.h[c]
}
