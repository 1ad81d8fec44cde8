// Converts the Stanford bunny of the npm package `bunny` (public domain) into
// assets/bunny/bunny.xyzn: one "x y z nx ny nz" line per mesh vertex.
//
//   node assets/bunny/convert_bunny.mjs [BUNNY_PACKAGE_DIR] [OUTPUT]
//
// BUNNY_PACKAGE_DIR defaults to the `bunny` package resolved from the current directory
// (node_modules/bunny); OUTPUT defaults to bunny.xyzn next to this script.
// Normals: area-weighted (sum of the unnormalised face normals), oriented outward (the mesh
// is flipped if its signed volume is negative). Points: centred at the bounding-box centre and
// scaled so the largest distance from the centre is 1. Numbers are written with JavaScript's
// shortest round-trip representation, which reads back to the identical double.

import { createRequire } from 'node:module';
import { writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(process.cwd(), 'noop.js'));
const packageArg = process.argv[2];
const bunny = require(packageArg ? path.resolve(packageArg) : 'bunny');
const output = process.argv[3] ? path.resolve(process.argv[3]) : path.join(here, 'bunny.xyzn');

const positions = bunny.positions;
const cells = bunny.cells;
const n = positions.length;

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

for (const c of cells) {
  if (c.length !== 3 || c.some((i) => !Number.isInteger(i) || i < 0 || i >= n)) {
    throw new Error(`bad cell ${JSON.stringify(c)}`);
  }
}

// Six times the signed volume: positive when the triangles wind counter-clockwise seen from outside.
let volume6 = 0;
for (const [i, j, k] of cells) volume6 += dot(positions[i], cross(positions[j], positions[k]));
const orientation = volume6 < 0 ? -1 : 1;

// Sum of the face normals with length 2·area: area-weighted vertex normals.
const normals = positions.map(() => [0, 0, 0]);
for (const [i, j, k] of cells) {
  const fn = cross(sub(positions[j], positions[i]), sub(positions[k], positions[i]));
  for (const v of [i, j, k]) for (let d = 0; d < 3; d++) normals[v][d] += orientation * fn[d];
}

const lo = [Infinity, Infinity, Infinity];
const hi = [-Infinity, -Infinity, -Infinity];
for (const p of positions) {
  for (let d = 0; d < 3; d++) {
    lo[d] = Math.min(lo[d], p[d]);
    hi[d] = Math.max(hi[d], p[d]);
  }
}
const centre = [0, 1, 2].map((d) => 0.5 * (lo[d] + hi[d]));
let maxDistance = 0;
for (const p of positions) maxDistance = Math.max(maxDistance, Math.hypot(...sub(p, centre)));

const lines = [];
for (let v = 0; v < n; v++) {
  const p = sub(positions[v], centre).map((x) => x / maxDistance);
  const length = Math.hypot(...normals[v]);
  if (!(length > 0)) throw new Error(`vertex ${v} has no incident area`);
  const nv = normals[v].map((x) => x / length);
  lines.push([...p, ...nv].map((x) => String(x)).join(' '));
}
writeFileSync(output, lines.join('\n') + '\n');
console.log(`${n} vertices, ${cells.length} triangles, signed volume ${(volume6 / 6).toPrecision(6)}` +
  `${orientation < 0 ? ' (flipped)' : ''} -> ${output}`);
