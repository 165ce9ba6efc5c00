#!/usr/bin/env node
// Computes MikkTSpace tangents with the reference algorithm (npm package mikktspace: Morten
// Mikkelsen's mikktspace.c through its Rust port, built to WebAssembly; the one three.js's
// BufferGeometryUtils.computeMikkTSpaceTangents uses), installed into tools/node by
// scripts/install-deps.sh. For tests/core/test_core_mikktspace.cpp.
//   mikktspace-reference.js IN OUT
// IN: little-endian: uint32 corner count N (a multiple of 3: unindexed triangles), then float32
// positions (3N), normals (3N), texture coordinates (2N). OUT: float32 tangents (4N) exactly as
// the reference returns them (its sign convention: w is not negated for glTF's UV space).
// Prints {"corners": N, "first_cpu_ms", "cpu_ms", "ms"}: the CPU time of the first
// generateTangents call and the CPU and wall time of a second one.
// Exit status: 0 done, 2 nothing computed (package missing, unreadable or malformed input).
// VELVET_NODE_TOOLS names another tools folder.
'use strict';
const fs = require('fs');
const path = require('path');

const toolsDir = process.env.VELVET_NODE_TOOLS || path.join(__dirname, '..', 'tools', 'node');
let mikktspace;
try {
  mikktspace = require(path.join(toolsDir, 'node_modules', 'mikktspace'));
} catch (e) {
  console.error(`mikktspace-reference: the npm package mikktspace is not installed in ` +
                `${toolsDir} (run 'make deps'): ${e.message}`);
  process.exit(2);
}
const [input, output] = process.argv.slice(2);
if (!input || !output) {
  console.error('usage: mikktspace-reference.js IN OUT');
  process.exit(2);
}
let bytes;
try {
  bytes = fs.readFileSync(input);
} catch (e) {
  console.error(`mikktspace-reference: ${input}: ${e.message}`);
  process.exit(2);
}
const n = bytes.length >= 4 ? bytes.readUInt32LE(0) : -1;
if (n < 0 || n % 3 !== 0 || bytes.length !== 4 + n * 8 * 4) {
  console.error(`mikktspace-reference: ${input}: malformed (${bytes.length} bytes)`);
  process.exit(2);
}
// Copy out of the Buffer: its offset into the pooled ArrayBuffer need not be 4-aligned.
const floats = new Float32Array(new Uint8Array(bytes.subarray(4)).buffer);
const position = floats.slice(0, 3 * n);
const normal = floats.slice(3 * n, 6 * n);
const texcoord = floats.slice(6 * n, 8 * n);
// Timed twice: the first call includes compiling the WebAssembly module's code.
const timed = () => {
  const start = process.hrtime.bigint();
  const cpuStart = process.cpuUsage();
  const result = mikktspace.generateTangents(position, normal, texcoord);
  const cpu = process.cpuUsage(cpuStart);
  return {result, ms: Number(process.hrtime.bigint() - start) / 1e6,
          cpuMs: (cpu.user + cpu.system) / 1000};
};
const first = timed();
const second = timed();
const tangents = first.result;
if (tangents.length !== 4 * n) {
  console.error(`mikktspace-reference: ${input}: ${tangents.length / 4} tangents for ${n} corners`);
  process.exit(2);
}
fs.writeFileSync(output, Buffer.from(tangents.buffer, tangents.byteOffset, tangents.byteLength));
console.log(JSON.stringify({corners: n, first_cpu_ms: first.cpuMs, cpu_ms: second.cpuMs,
                            ms: second.ms}));
