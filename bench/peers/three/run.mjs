#!/usr/bin/env node
// make bench-peers (issue 16): Velvet's steady preview frame beside three.js's frame of the same
// scene on the same driver. Velvet and three.js take turns (velvet, three, velvet, three, …) so a
// change in the machine's load reaches both; each turn is one median, and the comparison is the
// median of each side's medians. Exit codes: 1 usage, 2 a missing prerequisite (chromium,
// velvet, npm packages), 3 the wrong renderer or a failed measurement.
import { spawnSync } from 'node:child_process';
import { access, constants, mkdir, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { PeerError } from './errors.mjs';
import { serve } from './serve.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../../..');

const USAGE = `Usage: node bench/peers/three/run.mjs [options]
  --rounds N       turns of each renderer, alternating (default 3)
  --frames N       three.js frames measured a turn, after the warm-up (default 60)
  --warmup N       three.js frames drawn before each turn's measurement (default 10)
  --velvet FILE    the velvet binary (default build/bin/velvet; env VELVET)
  --chromium FILE  the browser (default /usr/bin/chromium)
  --angle NAME     ANGLE backend: gl-egl (default, no display) or gl (GLX, under xvfb-run)
  --screenshot F   the three.js frame as PNG (default bench/peers/out/three.png)
  --json           one JSON object instead of the table`;

function options() {
  const { values } = parseArgs({
    options: {
      rounds: { type: 'string', default: '3' },
      frames: { type: 'string', default: '60' },
      warmup: { type: 'string', default: '10' },
      velvet: { type: 'string', default: process.env.VELVET ?? path.join(repo, 'build/bin/velvet') },
      chromium: { type: 'string', default: '/usr/bin/chromium' },
      angle: { type: 'string', default: 'gl-egl' },
      screenshot: { type: 'string', default: path.join(repo, 'bench/peers/out/three.png') },
      json: { type: 'boolean', default: false },
      help: { type: 'boolean', default: false },
    },
  });
  if (values.help) {
    console.log(USAGE);
    process.exit(0);
  }
  const count = (name) => {
    const n = Number(values[name]);
    if (!Number.isInteger(n) || n < 1) throw new PeerError(`--${name}: expected a positive integer`, 1);
    return n;
  };
  if (!['gl-egl', 'gl'].includes(values.angle)) throw new PeerError('--angle: gl-egl or gl', 1);
  return { ...values, rounds: count('rounds'), frames: count('frames'), warmup: count('warmup') };
}

// Velvet's side must exist and know `bench --frame` before a browser is started.
async function checkVelvet(velvet) {
  try {
    await access(velvet, constants.X_OK);
  } catch {
    throw new PeerError(`velvet is not built (${velvet}): run make`, 2);
  }
  const help = spawnSync(velvet, ['bench', '--help'], { encoding: 'utf8' });
  if (!/--frame\b/.test(`${help.stdout}${help.stderr}`))
    throw new PeerError(`${velvet} has no "bench --frame": rebuild it (make)`, 2);
}

/** One turn of Velvet: `velvet bench --frame --json` in its own process. */
function velvetTurn(velvet) {
  const run = spawnSync(velvet, ['bench', '--frame', '--json'], { encoding: 'utf8' });
  if (run.status !== 0)
    throw new PeerError(`velvet bench --frame failed (exit ${run.status}):\n${run.stderr}`, 3);
  const line = run.stdout.trim().split('\n').findLast((l) => l.startsWith('{'));
  let result;
  try {
    result = JSON.parse(line);
  } catch {
    throw new PeerError(`velvet bench --frame printed no JSON object:\n${run.stdout}`, 3);
  }
  for (const key of ['frame_wall_ms', 'orbit_frame_wall_ms'])
    if (!Number.isFinite(result[key]))
      throw new PeerError(`velvet bench --frame gave no ${key}:\n${line}`, 3);
  if (!/llvmpipe/i.test(result.gl_renderer ?? ''))
    throw new PeerError(`velvet does not run on llvmpipe but on "${result.gl_renderer}"`, 3);
  if (result.width !== 1280 || result.height !== 720)
    throw new PeerError(`velvet bench --frame drew ${result.width}x${result.height}, not 1280x720`, 3);
  return result;
}

const median = (v) => {
  const s = [...v].sort((a, b) => a - b), n = s.length;
  return n % 2 ? s[(n - 1) / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
};
const ms = (x) => x.toFixed(1).padStart(8);

function printTable(r) {
  console.log(`Steady preview frame, 1280x720, ${r.rounds.length} alternating turns (medians, ms)`);
  console.log(`  Velvet: ${r.velvetVersion} at ${r.commit || 'an unknown commit'}, ` +
    `${r.velvetFrames} frames a turn; GL_RENDERER ${r.velvetRenderer}`);
  console.log(`  three.js: r${r.peer.three}, ${r.threeFrames} frames a turn after ${r.warmup} unmeasured; ` +
    `WebGL ${r.peer.unmaskedRenderer}`);
  for (const note of r.peer.notes) console.log(`  peer differs: ${note}`);
  console.log('');
  // Velvet's frame after a value edit (a slider dragged: the background's pixels kept) and
  // while the camera orbits (every pixel drawn); three.js draws every pixel each frame.
  console.log('| turn | Velvet, value edit (`frame_wall_ms`) | Velvet, orbit (`orbit_frame_wall_ms`) | three.js frame |');
  console.log('|---|---:|---:|---:|');
  r.rounds.forEach((t, i) =>
    console.log(`| ${i + 1} | ${ms(t.velvet)} | ${ms(t.velvetOrbit)} | ${ms(t.three)} |`));
  console.log(`| median of the turns | ${ms(r.velvet)} | ${ms(r.velvetOrbit)} | ${ms(r.three)} |`);
  console.log('');
  console.log(`Velvet / three.js: ${r.ratio.toFixed(2)} after a value edit, ` +
    `${r.orbitRatio.toFixed(2)} while orbiting`);
  if (r.screenshot) console.log(`three.js frame: ${r.screenshot}`);
}

// puppeteer-core comes from npm into the ignored node_modules; say how to get it.
async function loadBrowser() {
  try {
    return await import('./browser.mjs');
  } catch (e) {
    if (e.code !== 'ERR_MODULE_NOT_FOUND') throw e;
    throw new PeerError(`${e.message}: run scripts/install-bench-peers.sh (npm ci)`, 2);
  }
}

async function main() {
  const o = options();
  await checkVelvet(o.velvet);
  const { openPeer } = await loadBrowser();
  const server = await serve(repo, ['bench/peers/three', 'resources']);
  const peer = await openPeer({
    chromium: o.chromium, angle: o.angle, width: 1280, height: 720,
    url: `${server.url}/bench/peers/three/index.html`,
  });
  try {
    const rounds = [];
    let velvetRenderer = '', velvetFrames = 0;
    for (let i = 0; i < o.rounds; ++i) {
      const v = velvetTurn(o.velvet);
      const t = await peer.measure(o.warmup, o.frames);
      velvetRenderer = v.gl_renderer;
      velvetFrames = v.frames;
      rounds.push({
        velvet: v.frame_wall_ms, velvetOrbit: v.orbit_frame_wall_ms, three: t.median,
        velvetDetail: v, threeDetail: t,
      });
      if (!o.json) // progress; the table comes at the end
        console.error(`turn ${i + 1}/${o.rounds}: velvet ${v.frame_wall_ms.toFixed(1)} ms ` +
          `(orbit ${v.orbit_frame_wall_ms.toFixed(1)} ms), ` +
          `three.js ${t.median.toFixed(1)} ms`);
    }
    let screenshot = null;
    if (o.screenshot) {
      await mkdir(path.dirname(o.screenshot), { recursive: true });
      await writeFile(o.screenshot, await peer.snapshot());
      screenshot = path.relative(process.cwd(), o.screenshot);
    }
    const velvet = median(rounds.map((t) => t.velvet)), three = median(rounds.map((t) => t.three));
    const velvetOrbit = median(rounds.map((t) => t.velvetOrbit));
    const velvetVersion = spawnSync(o.velvet, ['--version'], { encoding: 'utf8' }).stdout.trim();
    const commit = spawnSync('git', ['-C', repo, 'describe', '--always', '--dirty'],
      { encoding: 'utf8' }).stdout.trim();
    const result = {
      commit, velvetVersion, velvetRenderer, velvetFrames, threeFrames: o.frames,
      warmup: o.warmup, peer: peer.info, rounds, velvet, velvetOrbit, three, ratio: velvet / three,
      orbitRatio: velvetOrbit / three, screenshot,
    };
    if (o.json) console.log(JSON.stringify(result, null, 2));
    else printTable(result);
  } finally {
    await peer.close();
    await server.close();
  }
}

main().catch((e) => {
  if (e instanceof PeerError) {
    console.error(`bench-peers: ${e.message}`);
    if (e.exitCode === 1) console.error(USAGE);
    process.exit(e.exitCode);
  }
  if (e?.code?.startsWith?.('ERR_PARSE_ARGS')) {
    console.error(`bench-peers: ${e.message}\n${USAGE}`);
    process.exit(1);
  }
  console.error(`bench-peers: ${e?.stack ?? e}`);
  process.exit(3);
});
