// Debian's Chromium, headless, drawing WebGL through ANGLE's OpenGL backend on Mesa's llvmpipe:
// the same driver Velvet's headless EGL context gets, so the two frame times compare.
import { access, constants } from 'node:fs/promises';
import puppeteer from 'puppeteer-core';
import { PeerError } from './errors.mjs';

// ANGLE backends (--angle): gl-egl is ANGLE's OpenGL backend through Mesa's EGL (an OpenGL ES 3.2
// context, no display needed); gl is the same through GLX (desktop OpenGL 4.5; needs an X
// server, e.g. xvfb-run). Without --ignore-gpu-blocklist Chromium refuses llvmpipe for WebGL,
// and it must not fall back to SwiftShader (its own CPU rasteriser), which would measure
// something else: no --enable-unsafe-swiftshader, and the renderer string is checked below.
function chromiumArgs(angle, width, height) {
  return [
    '--headless=new',
    '--no-sandbox', // as root (the bench VM); the page is ours, served from 127.0.0.1
    '--use-gl=angle',
    `--use-angle=${angle}`,
    '--ignore-gpu-blocklist',
    '--disable-gpu-vsync',
    '--disable-frame-rate-limit',
    '--disable-background-timer-throttling',
    '--disable-renderer-backgrounding',
    '--disable-extensions',
    '--no-first-run',
    `--window-size=${width},${height}`,
  ];
}

/**
 * Opens @p url (the peer's page) in Chromium and waits for its scene. Resolves to
 * { info, measure(warmup, frames), snapshot(), close() }; throws PeerError (exit code 2: a
 * missing prerequisite, 3: the wrong renderer or a failing page).
 */
export async function openPeer({ chromium, angle, url, width, height }) {
  try {
    await access(chromium, constants.X_OK);
  } catch {
    throw new PeerError(`chromium is missing (${chromium}): run scripts/install-bench-peers.sh ` +
      '(apt-get install chromium)', 2);
  }
  if (angle === 'gl' && !process.env.DISPLAY)
    throw new PeerError('--angle gl needs an X display (run under xvfb-run); gl-egl does not', 1);
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: chromiumArgs(angle, width, height),
    defaultViewport: { width, height },
    protocolTimeout: 600_000, // one measurement is many slow frames in one evaluate()
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
    await page.goto(`${url}?width=${width}&height=${height}`, { waitUntil: 'load' });
    let info;
    try {
      info = await page.evaluate(async () => (await window.peer).info);
    } catch (e) {
      throw new PeerError(`the page failed: ${e.message}\n${errors.join('\n')}`, 3);
    }
    if (!/llvmpipe/i.test(info.unmaskedRenderer ?? ''))
      throw new PeerError(`WebGL does not run on llvmpipe but on "${info.unmaskedRenderer}" ` +
        `(${info.version}): the comparison needs Velvet's driver`, 3);
    return {
      info,
      measure: (warmup, frames) =>
        page.evaluate(async (w, f) => (await window.peer).measure(w, f), warmup, frames),
      snapshot: async () => {
        const dataUrl = await page.evaluate(async () => (await window.peer).snapshot());
        return Buffer.from(dataUrl.slice(dataUrl.indexOf(',') + 1), 'base64');
      },
      close: () => browser.close(),
    };
  } catch (e) {
    await browser.close();
    throw e;
  }
}
